// SPDX-License-Identifier: Apache-2.0
// A hashed uniform grid over points with one search radius r (the light vertices of a
// bidirectional pass, merged with camera vertices). Cells are 2r wide, so the points within r
// of a query lie in the 2 x 2 x 2 cells nearest to it; cells hash into as many buckets as
// there are points (Teschner et al. 2003's hash), and a bucket shared by several cells is
// visited once. Points are kept in index order within a bucket, so a query visits them in a
// fixed order: sums over them do not depend on threads.
#pragma once

#include "math/vec3.h"

#include <cstdint>
#include <vector>

namespace ppm {

class LightVertexGrid {
public:
    // Indexes points[0 .. n) (copied); radius > 0.
    void build(const std::vector<Vec3> &points, double radius);
    bool empty() const { return sorted_points_.empty(); }

    // The points' indices in the grid's order (by bucket).
    const std::vector<std::uint32_t> &order() const { return order_; }

    // f(k) for every point within the radius of p (distance^2 <= r^2), k its position in
    // order() (so that data kept in that order is read bucket by bucket, not at random).
    template <class F> void for_each_within(const Vec3 &p, F &&f) const {
        if (sorted_points_.empty()) return;
        std::uint32_t buckets[8];
        const int count = near_buckets(p, buckets);
        for (int b = 0; b < count; ++b)
            for (std::uint32_t k = bucket_start_[buckets[b]]; k < bucket_start_[buckets[b] + 1]; ++k)
                if (length2(sorted_points_[k] - p) <= r2_) f(k);
    }

private:
    std::uint32_t bucket_of(std::int64_t x, std::int64_t y, std::int64_t z) const;
    int near_buckets(const Vec3 &p, std::uint32_t out[8]) const; // distinct buckets

    std::vector<std::uint32_t> bucket_start_; // buckets + 1 entries
    std::vector<std::uint32_t> order_;        // point indices sorted by bucket, stable
    std::vector<Vec3> sorted_points_;         // the points in that order: a bucket is read in one go
    double inv_cell_ = 0, r2_ = 0;
};

} // namespace ppm
