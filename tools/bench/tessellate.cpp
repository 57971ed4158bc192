// SPDX-License-Identifier: Apache-2.0
#include "tessellate.h"

#include "common/handle.h"
#include "common/status.h"
#include "measure.h"
#include "ray_sets.h"

#include <ppm/ppm.h>

#include <cmath>
#include <stdexcept>

namespace bench {

using ppm_tools::check_with_status;

Mesh tessellate(const std::vector<double> &control_points, int grid, double relative_tolerance, double diagonal) {
    Mesh out;
    out.grid = grid;
    out.relative_tolerance = grid > 0 ? 0 : relative_tolerance;
    out.label = grid > 0 ? "N" + std::to_string(grid) : "adaptive-" + format_number(relative_tolerance);
    ppm_tools::Mesh mesh;
    Stopwatch clock;
    check_with_status(ppm_tessellate_patches(control_points.data(), control_points.size() / 48,
                                             grid > 0 ? 0.0 : relative_tolerance * diagonal, uint32_t(grid),
                                             mesh.out()),
                      "ppm_tessellate_patches");
    out.seconds = clock.wall_seconds();

    const double *positions = nullptr, *normals = nullptr;
    const uint32_t *indices = nullptr, *patches = nullptr, *welded = nullptr;
    size_t vertex_count = 0, triangle_count = 0, welded_count = 0;
    double deviation = 0;
    check_with_status(ppm_mesh_get_vertices(mesh, &positions, &normals, nullptr, &vertex_count),
                      "ppm_mesh_get_vertices");
    check_with_status(ppm_mesh_get_triangles(mesh, &indices, &triangle_count), "ppm_mesh_get_triangles");
    check_with_status(ppm_mesh_get_triangle_patches(mesh, &patches), "ppm_mesh_get_triangle_patches");
    check_with_status(ppm_mesh_get_welded_vertices(mesh, &welded, &welded_count), "ppm_mesh_get_welded_vertices");
    check_with_status(ppm_mesh_get_double(mesh, "max_deviation", &deviation), "ppm_mesh_get_double");
    out.deviation = deviation / diagonal;

    out.positions.assign(3 * welded_count, 0.0);
    for (size_t v = 0; v < vertex_count; ++v)
        for (int c = 0; c < 3; ++c) out.positions[3 * size_t(welded[v]) + c] = positions[3 * v + c];
    out.indices.resize(3 * triangle_count);
    out.corner_normal.resize(9 * triangle_count);
    for (size_t k = 0; k < 3 * triangle_count; ++k) {
        const uint32_t v = indices[k];
        out.indices[k] = welded[v];
        for (int c = 0; c < 3; ++c) out.corner_normal[3 * k + c] = float(normals[3 * size_t(v) + c]);
    }
    out.triangle_patch.assign(patches, patches + triangle_count);
    return out;
}

void interpolate_normal(const Mesh &mesh, size_t tri, double b1, double b2, float out[3]) {
    const float *n = &mesh.corner_normal[9 * tri];
    const double b0 = 1.0 - b1 - b2;
    double s[3], l = 0;
    for (int c = 0; c < 3; ++c) {
        s[c] = b0 * n[c] + b1 * n[3 + c] + b2 * n[6 + c];
        l += s[c] * s[c];
    }
    l = std::sqrt(l);
    for (int c = 0; c < 3; ++c) out[c] = l > 0 ? float(s[c] / l) : 0.0f;
}

} // namespace bench
