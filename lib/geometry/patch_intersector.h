// SPDX-License-Identifier: Apache-2.0
// Exact ray / bicubic patch intersection in ray space.
//
// The patch is projected onto a frame whose z axis is the ray: the ray hits S(a, b) where the
// projected x(a, b) = y(a, b) = 0, at distance z(a, b). Regions of the parameter domain are
// culled by the 2D box of their control points and by their depth range, tested with an
// interval Newton (Krawczyk) operator that proves "no root" or "exactly one root", and split
// with De Casteljau otherwise, nearer child first. A region proven to hold one root is solved
// by a guarded Newton iteration. Regions whose ray-space extent falls below the tolerance
// (tangent rays, collapsed edges) end the subdivision: there the surface is within the
// tolerance of the ray.
#pragma once

#include "geometry/bezier.h"

namespace ppm {

// A ray expressed in the frame used for projection, built once per ray.
struct RayFrame {
    Vec3 org;              // ray origin
    Vec3 e1, e2, axis;     // orthonormal, axis = dir / |dir|
    double dir_length = 1; // |dir|: ray parameter t = distance / dir_length

    static RayFrame from_ray(const Vec3 &org, const Vec3 &dir);
    // The same with |dir| known (a query has it, exact to rounding for unit directions).
    static RayFrame from_ray(const Vec3 &org, const Vec3 &dir, double dir_length);
};

// Control points as a structure of arrays (index i * 4 + j as in BezierPatch): the layout
// the intersector computes in, so that its loops over the 16 points vectorise.
struct ControlGrid {
    double x[16], y[16], z[16];
    // Bound on |dS/du|_1 + ... : the largest |dS/du| or |dS/dv| (1-norm) over the patch, from
    // the derivative control points. Rotation invariant, so it holds in ray space too.
    double derivative_bound;
    static ControlGrid from(const BezierPatch &patch);
    // derivative_bound of the points x, y, z.
    double bound_derivatives() const;
};

struct PatchRootQuery {
    double tnear = 0; // accepted ray parameters: [tnear, tfar]
    double tfar = INFINITY;
    double tolerance = 1e-9; // absolute distance below which a region counts as a point
    bool any_hit = false;    // stop at the first root found (occlusion queries)
};

struct PatchRoot {
    double t = INFINITY; // ray parameter
    double a = 0, b = 0; // parameters in the patch passed in (u, v)
};

// Searches the patch for the root with the smallest t in [tnear, tfar] (any root when
// any_hit). Returns true and fills `root` when one exists.
bool intersect_patch(const ControlGrid &patch, const RayFrame &ray, const PatchRootQuery &query, PatchRoot &root);
inline bool intersect_patch(const BezierPatch &patch, const RayFrame &ray, const PatchRootQuery &query,
                            PatchRoot &root) {
    return intersect_patch(ControlGrid::from(patch), ray, query, root);
}

} // namespace ppm
