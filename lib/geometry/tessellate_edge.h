// SPDX-License-Identifier: Apache-2.0
// Patch edges for tessellation: the edge curves in a canonical direction, their points and
// segment counts, computed from the edge's four control points alone so that the two patches
// of a seam agree bit for bit.
#pragma once

#include "geometry/bezier.h"

#include <cstdint>
#include <vector>

namespace ppm {
namespace tess {

inline Vec3 curve_sum(const Vec3 c[4], const double b[4]) {
    return c[0] * b[0] + c[1] * b[1] + c[2] * b[2] + c[3] * b[3];
}

// Distance from x to the cubic curve c, by Newton steps on C'(t) . (C(t) - x) from t. Every
// accepted step brings the curve point closer, so the result bounds the true distance.
double curve_distance(const Vec3 c[4], const Vec3 &x, double t);

// Sides of a patch, each run in the direction of increasing parameter.
enum Side { side_v0 = 0, side_u1 = 1, side_v1 = 2, side_u0 = 3 };

// A patch edge's four control points in a canonical direction (the lexicographically smaller
// of the two readings), so that two patches sharing the edge in either direction see the same
// curve, count the same segments and compute bit-identical points.
struct Edge {
    Vec3 c[4];
    bool reversed = false; // the canonical direction runs against the patch parameter
    bool collapsed = false;
};

Edge patch_edge(const BezierPatch &patch, int side);

// Points k / n of the edge, k = 0..n, in canonical order. The ends are the control points
// exactly, and a collapsed edge is its one point, so corners and apexes weld across patches.
// The only place that evaluates edge points, so that both patches of a seam run the same code.
std::vector<Vec3> edge_points(const Edge &e, uint32_t n);

// Fewest segments whose chords stay within `tolerance` of the edge: a function of the edge's
// curve alone, so the two patches of a seam agree.
uint32_t edge_segments(const Edge &e, double tolerance);

// Point m of n along a side, in the patch's direction.
inline const Vec3 &side_point(const std::vector<Vec3> &points, const Edge &e, uint32_t m, uint32_t n) {
    return points[e.reversed ? n - m : m];
}

} // namespace tess
} // namespace ppm
