// SPDX-License-Identifier: Apache-2.0
// Rays leaving a patch: when can a ray not meet the sub-patch it starts on again?
//
// A secondary ray starts a hair off the surface point it leaves, and the sub-patch holding
// that point is always among the first Embree hands to the patch search, which then proves
// and solves the root the ray starts on only to reject it (t < 0): a third of all patch
// searches on the glass teapot. The bound here settles most of them in a few dot products.
//
// Chord bound: with n a unit normal of the sub-patch (its slab normal), every chord Q - P
// between two of its points satisfies |n . (Q - P)| <= slope * |(Q - P) x n| (it rises out of
// the plane at most that steeply). Proof, for the in-plane coordinates q = (e1 . S, e2 . S)
// and height h = n . S of the surface S(w): Q - P = (integral of the Jacobian along the
// segment w0 -> w1) (w1 - w0), whose entries lie in the derivative hulls. For any Y,
// |Y Dq (w1 - w0)| >= (1 - c) |w1 - w0| where c = |I - Y Dq| over the hulls (c < 1: the
// projection onto the plane is injective, the sub-patch is a graph over it), so the in-plane
// part is at least (1 - c) / |Y| |w1 - w0| (infinity norms) while the height changes by at
// most (|h_a| + |h_b|) |w1 - w0|.
//
// A ray org + t dir (t >= 0) leaving S(w0), org = S(w0) + offset, meets the sub-patch again
// at S(w1) only if S(w1) - S(w0) = t dir + offset is such a chord. When dir and offset both
// rise more steeply than the slope, on the same side of the plane, every t dir + offset does
// (the steep vectors on one side form a convex cone), so no such w1 exists: not even the
// start root, which lies behind the origin.
#pragma once

#include "geometry/patch_intersector.h"
#include "math/vec3.h"

namespace ppm {

// The chord slope bound of the sub-patch with control points `grid` for the plane with unit
// normal n; INFINITY where none can be proven (a collapsed edge, a sub-patch that folds over
// the plane). Rounding of the control points is covered.
double chord_slope_bound(const ControlGrid &grid, const Vec3 &n);

// Whether the ray org + t dir, t >= 0, with org = S(w0) + offset for a point S(w0) of the
// sub-patch (offset known to within offset_error), cannot meet the sub-patch at all. n is the
// normal the slope was bound for or any positive multiple of it (a float rounding of it, as
// stored): rises and runs scale alike, and no square root is needed here.
bool leaves_for_good(const Vec3 &n, double slope, const Vec3 &offset, double offset_error, const Vec3 &dir);

} // namespace ppm
