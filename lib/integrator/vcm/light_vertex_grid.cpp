// SPDX-License-Identifier: Apache-2.0
#include "integrator/vcm/light_vertex_grid.h"

#include <algorithm>
#include <cmath>

namespace ppm {

namespace {

// Cell coordinates clamped far inside the 64-bit range (points are finite scene points).
std::int64_t cell(double v) { return static_cast<std::int64_t>(std::floor(std::clamp(v, -1e15, 1e15))); }

} // namespace

std::uint32_t LightVertexGrid::bucket_of(std::int64_t x, std::int64_t y, std::int64_t z) const {
    const std::uint64_t h = (static_cast<std::uint64_t>(x) * 73856093u) ^ (static_cast<std::uint64_t>(y) * 19349663u) ^
                            (static_cast<std::uint64_t>(z) * 83492791u);
    return static_cast<std::uint32_t>(h % (bucket_start_.size() - 1));
}

void LightVertexGrid::build(const std::vector<Vec3> &points, double radius) {
    r2_ = radius * radius;
    inv_cell_ = 1.0 / (2.0 * radius);
    const std::size_t n = points.size();
    bucket_start_.assign(std::max<std::size_t>(n, 1) + 1, 0);
    std::vector<std::uint32_t> bucket(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 &q = points[i];
        bucket[i] = bucket_of(cell(q.x * inv_cell_), cell(q.y * inv_cell_), cell(q.z * inv_cell_));
        ++bucket_start_[bucket[i] + 1];
    }
    for (std::size_t b = 1; b < bucket_start_.size(); ++b) bucket_start_[b] += bucket_start_[b - 1];
    order_.resize(n);
    std::vector<std::uint32_t> next(bucket_start_.begin(), bucket_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order_[next[bucket[i]]++] = static_cast<std::uint32_t>(i);
    sorted_points_.resize(n);
    for (std::size_t k = 0; k < n; ++k) sorted_points_[k] = points[order_[k]];
}

int LightVertexGrid::near_buckets(const Vec3 &p, std::uint32_t out[8]) const {
    // The cell holding p and, on each axis, its neighbour on the side of p's nearer face.
    std::int64_t lo[3];
    const double c[3] = {p.x * inv_cell_, p.y * inv_cell_, p.z * inv_cell_};
    for (int a = 0; a < 3; ++a) {
        const std::int64_t i = cell(c[a]);
        lo[a] = c[a] - static_cast<double>(i) < 0.5 ? i - 1 : i;
    }
    int count = 0;
    for (int k = 0; k < 8; ++k) {
        const std::uint32_t b = bucket_of(lo[0] + (k & 1), lo[1] + ((k >> 1) & 1), lo[2] + ((k >> 2) & 1));
        if (std::find(out, out + count, b) == out + count) out[count++] = b;
    }
    return count;
}

} // namespace ppm
