// SPDX-License-Identifier: Apache-2.0
// The few spheres a scene tests every ray against outside the BVH (huge ones such as
// Hachisuka's walls of radius 1e5, or every sphere of a scene of a few spheres; see Scene),
// stored coordinate by coordinate so that the exact test runs on all of them at once in SIMD
// lanes.
#pragma once

#include "scene/ray_query.h"
#include "scene/sphere_geometry.h"

namespace ppm {

class SphereSet {
public:
    static constexpr int kCapacity = 16;

    void clear() { *this = SphereSet(); }
    // Adds a sphere as the next index; throws ppm::Error (invalid operation) beyond kCapacity.
    void add(const Vec3 &center, double radius);
    int size() const { return count_; }

    // Records the nearest hit with t in [query.tnear, query.hit.t] (query.hit.geom_id is left
    // to the caller) and returns its sphere's index, or -1 when no sphere was hit.
    int intersect(RayQuery &query) const;
    // Whether any sphere is hit within [query.tnear, query.hit.t].
    bool occluded(RayQuery &query) const;

private:
    // t[i]: sphere i's nearest root within [query.tnear, query.hit.t], or infinity.
    void nearest_roots(const RayQuery &query, double *t) const;

    // Unused lanes hold an empty sphere (radius2 < 0), which no test accepts.
    alignas(64) double cx_[kCapacity] = {}, cy_[kCapacity] = {}, cz_[kCapacity] = {};
    alignas(64) double radius2_[kCapacity] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
    int count_ = 0;
    int used_lanes_ = 0; // count_ rounded up to whole groups of four lanes
};

} // namespace ppm
