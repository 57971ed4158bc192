// SPDX-License-Identifier: Apache-2.0
// Tessellation of bicubic Bezier patches into triangles: a uniform grid per patch, or an
// adaptive mesh whose distance from the surface is measured and held below a tolerance.
//
// Seams. Every vertex belongs to one patch and carries that patch's (u, v) and normal, so a
// point on a seam appears once per patch. Its position is computed from the shared edge
// curve alone (the four control points of the edge, in a canonical direction), so both
// patches produce bit-identical positions. `welded` gives border vertices at one position one
// index (every other vertex an index of its own); read through it, the mesh is closed across
// every seam whose two patches share the edge's control points (in either direction).
//
// Adaptive scheme. Each patch edge gets a segment count from its own curve (the smallest
// count whose chords stay within a share of the tolerance, measured), so neighbours agree.
// Each patch gets an interior tensor grid of nu x nv cells, the counts chosen per patch and per
// direction from the normal curvature of the surface (the second fundamental form sampled over
// the patch), the lines spaced more densely where it bends more; a ring of triangles stitches
// the grid's outermost rows to the edge vertices. A collapsed edge (four equal control points)
// is a single point: the ring becomes a fan to it, with no zero-area triangle. The mesh is then
// measured (measure_deviation) and patches that exceed the tolerance are refined until none
// does.
#pragma once

#include "geometry/bezier.h"

#include <cstdint>
#include <vector>

namespace ppm {

struct PatchMesh {
    std::vector<double> positions; // 3 per vertex
    std::vector<double> normals;   // 3 per vertex: unit geometric normal of the patch
    std::vector<double> uvs;       // 2 per vertex: (u, v) in the vertex's patch
    std::vector<uint32_t> welded;  // per vertex: shared by border vertices at one position
    uint32_t welded_count = 0;
    std::vector<uint32_t> indices;        // 3 per triangle, counter-clockwise in (u, v)
    std::vector<uint32_t> triangle_patch; // per triangle: its patch
    double max_deviation = 0;             // measured, see measure_deviation

    size_t vertex_count() const { return uvs.size() / 2; }
    size_t triangle_count() const { return triangle_patch.size(); }
};

// More triangles than this is refused (INVALID_ARGUMENT) before anything large is allocated.
constexpr double max_tessellation_triangles = 200e6;

// grid x grid quads per patch, two triangles each, split along the diagonal whose midpoint lies
// closer to the surface. A collapsed edge makes half of its row's triangles zero-area.
PatchMesh tessellate_uniform(const std::vector<BezierPatch> &patches, uint32_t grid);

// Every point of every triangle within `tolerance` (absolute, > 0) of the surface, as measured.
// Throws INVALID_ARGUMENT if the estimate exceeds max_tessellation_triangles, UNSUPPORTED if the
// tolerance cannot be met (it is below what double precision resolves).
PatchMesh tessellate_adaptive(const std::vector<BezierPatch> &patches, double tolerance);

// Largest distance found from points of the triangles (`indices` into `positions` and `uvs`)
// to `patch`: each triangle is sampled on a barycentric lattice, each sample mapped to (u, v) by
// interpolating the vertex uvs, and Gauss-Newton steps from there find the nearest surface
// point (samples on the patch border are also measured to the border's curve, and samples
// farther than `focus` are searched for again around the triangle). Every value is the
// distance to a real surface point, so the result bounds the true deviation at the samples
// from above. Triangles whose coarse samples come within 80% of min(focus, the largest coarse
// value) are searched to their maximum on lattices up to 8 times finer.
double measure_deviation(const BezierPatch &patch, const std::vector<double> &positions, const std::vector<double> &uvs,
                         const uint32_t *indices, size_t triangle_count, double focus);

} // namespace ppm
