// SPDX-License-Identifier: Apache-2.0
// One patch's triangles: a uniform grid, or the adaptive interior grid with a ring stitched to
// the edge vertices. Each patch is built on its own (in parallel) and assembled later.
#pragma once

#include "geometry/bezier.h"
#include "geometry/tessellate_edge.h"

#include <cstdint>
#include <vector>

namespace ppm {
namespace tess {

struct Piece {
    std::vector<double> positions, normals, uvs;
    std::vector<uint8_t> on_border; // vertex on the patch border: welded with the neighbours
    std::vector<uint32_t> indices;
    double deviation = 0;

    size_t triangle_count() const { return indices.size() / 3; }
};

// n x n quads over the patch, the border vertices taken from the edge curves.
Piece build_grid(const BezierPatch &patch, uint32_t n);

// Inner grid lines us[1..nu-1] and vs[1..nv-1], edge vertices from each edge's own
// segment count, a ring stitching the two; a collapsed edge is a fan with one apex vertex per
// triangle, at the (u, v) that interpolates best.
Piece build_adaptive(const BezierPatch &patch, const Edge edges[4], const uint32_t segments[4],
                     const std::vector<double> &us, const std::vector<double> &vs);

} // namespace tess
} // namespace ppm
