// SPDX-License-Identifier: Apache-2.0
#include "photon/hit_point.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace ppm {

HitPointBounds measure_hit_points(const HitPoint *points, std::size_t count) {
    using Range = tbb::blocked_range<std::size_t>;
    return tbb::parallel_reduce(
        Range(0, count, 16384), HitPointBounds{},
        [&](const Range &range, HitPointBounds b) {
            for (std::size_t i = range.begin(); i < range.end(); ++i) b.add(points[i]);
            return b;
        },
        [](HitPointBounds a, const HitPointBounds &b) {
            a.add(b);
            return a;
        });
}

} // namespace ppm
