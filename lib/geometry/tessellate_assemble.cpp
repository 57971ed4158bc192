// SPDX-License-Identifier: Apache-2.0
#include "geometry/tessellate_assemble.h"

#include "geometry/tessellate_budget.h"

#include <algorithm>
#include <cstring>
#include <unordered_map>

namespace ppm {
namespace tess {

namespace {

struct PositionKey {
    double x, y, z;
    bool operator==(const PositionKey &o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PositionHash {
    size_t operator()(const PositionKey &k) const {
        uint64_t h = 0xcbf29ce484222325ull;
        for (double d : {k.x, k.y, k.z}) {
            uint64_t bits;
            std::memcpy(&bits, &d, sizeof bits);
            h = (h ^ bits) * 0x100000001b3ull;
            h ^= h >> 29;
        }
        return size_t(h);
    }
};

} // namespace

PatchMesh assemble(std::vector<Piece> &pieces) {
    PatchMesh mesh;
    size_t vertices = 0, triangles = 0;
    for (const Piece &piece : pieces) {
        vertices += piece.uvs.size() / 2;
        triangles += piece.triangle_count();
    }
    if (vertices >= 0xFFFFFFFFu) over_budget(double(triangles));
    mesh.positions.reserve(3 * vertices);
    mesh.normals.reserve(3 * vertices);
    mesh.uvs.reserve(2 * vertices);
    mesh.welded.reserve(vertices);
    mesh.indices.reserve(3 * triangles);
    mesh.triangle_patch.reserve(triangles);
    // Only border vertices can coincide with another patch's; the rest get ids of their own.
    std::unordered_map<PositionKey, uint32_t, PositionHash> border_ids;
    uint32_t next_id = 0;
    for (size_t p = 0; p < pieces.size(); ++p) {
        Piece &piece = pieces[p];
        const uint32_t base = uint32_t(mesh.uvs.size() / 2);
        for (size_t v = 0; v < piece.on_border.size(); ++v) {
            if (piece.on_border[v]) {
                // + 0.0 turns -0 into +0, which compares equal but hashes differently.
                const PositionKey key{piece.positions[3 * v] + 0.0, piece.positions[3 * v + 1] + 0.0,
                                      piece.positions[3 * v + 2] + 0.0};
                const auto inserted = border_ids.emplace(key, next_id);
                if (inserted.second) ++next_id;
                mesh.welded.push_back(inserted.first->second);
            } else {
                mesh.welded.push_back(next_id++);
            }
        }
        mesh.positions.insert(mesh.positions.end(), piece.positions.begin(), piece.positions.end());
        mesh.normals.insert(mesh.normals.end(), piece.normals.begin(), piece.normals.end());
        mesh.uvs.insert(mesh.uvs.end(), piece.uvs.begin(), piece.uvs.end());
        for (uint32_t index : piece.indices) mesh.indices.push_back(base + index);
        mesh.triangle_patch.insert(mesh.triangle_patch.end(), piece.triangle_count(), uint32_t(p));
        mesh.max_deviation = std::max(mesh.max_deviation, piece.deviation);
        piece = Piece(); // release as we go: the mesh may be large
    }
    mesh.welded_count = next_id;
    return mesh;
}

} // namespace tess
} // namespace ppm
