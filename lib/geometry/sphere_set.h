// The few huge spheres a scene tests every ray against outside the BVH (Hachisuka's walls of
// radius 1e5, see Scene), stored coordinate by coordinate so that the cheap tests run on all
// of them at once in SIMD lanes and only the spheres that may be hit get the exact test with
// its sqrt and division.
#pragma once

#include "geometry/sphere_geometry.h"
#include "scene/ray_query.h"

namespace ppm {

class SphereSet {
public:
    static constexpr int kCapacity = 8;

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
    struct Lanes; // the ray's terms for every sphere (sphere_set.cpp)
    void compute_terms(const RayQuery &query, Lanes &lanes) const;
    // Whether sphere_ruled_out() leaves each lane's sphere (false for unused lanes).
    void may_hit(const RayQuery &query, const Lanes &lanes, bool *out) const;
    bool test_lane(const Lanes &lanes, int i, RayQuery &query) const;

    // Unused lanes hold an empty sphere (radius2 < 0), which no test accepts.
    alignas(64) double cx_[kCapacity] = {}, cy_[kCapacity] = {}, cz_[kCapacity] = {};
    alignas(64) double radius2_[kCapacity] = {-1, -1, -1, -1, -1, -1, -1, -1};
    int count_ = 0;
};

} // namespace ppm
