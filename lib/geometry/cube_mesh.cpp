// SPDX-License-Identifier: Apache-2.0
#include "geometry/cube_mesh.h"

namespace ppm {

MeshData cube_mesh() {
    // A face's corner at (u, v) is normal + (2u - 1) along_u + (2v - 1) along_v.
    struct Face {
        Vec3 normal, along_u, along_v;
    };
    static const Face faces[6] = {
        {{0, -1, 0}, {0, 0, 1}, {1, 0, 0}}, {{0, 1, 0}, {-1, 0, 0}, {0, 0, -1}}, {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}},
        {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}},  {{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}},  {{0, 0, -1}, {0, -1, 0}, {1, 0, 0}},
    };
    // The corners in Mitsuba's order, and its two triangles per face (both wound outwards).
    static const double corner_uv[4][2] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    static const uint32_t corner_triangles[6] = {0, 1, 2, 3, 0, 2};
    MeshData mesh;
    for (const Face &face : faces) {
        const uint32_t first = static_cast<uint32_t>(mesh.positions.size());
        for (const auto &uv : corner_uv) {
            mesh.positions.push_back(face.normal + face.along_u * (2 * uv[0] - 1) + face.along_v * (2 * uv[1] - 1));
            mesh.normals.push_back(face.normal);
            mesh.uvs.push_back(uv[0]);
            mesh.uvs.push_back(uv[1]);
        }
        for (uint32_t corner : corner_triangles) mesh.indices.push_back(first + corner);
    }
    return mesh;
}

} // namespace ppm
