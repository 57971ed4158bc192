// SPDX-License-Identifier: Apache-2.0
#include "timed_trace.h"

#include "measure.h"
#include "parallel.h"

namespace bench {

Timing timed_trace(const Method &method, const std::vector<ppm_ray> &rays, int threads, double min_seconds,
                   Trace &trace) {
    auto once = [&](Trace &out) {
        out.resize(rays.size());
        if (method.threads_inside() || threads <= 1)
            method.trace(rays, 0, rays.size(), out);
        else
            parallel_chunks(rays.size(), threads, 256,
                            [&](size_t begin, size_t end) { method.trace(rays, begin, end, out); });
    };
    Timing timing;
    Stopwatch clock;
    once(trace);
    timing.rays = rays.size();
    Trace scratch;
    while (clock.wall_seconds() < min_seconds && !rays.empty()) {
        once(scratch);
        timing.rays += rays.size();
    }
    timing.wall = clock.wall_seconds();
    timing.cpu = clock.cpu_seconds();
    return timing;
}

} // namespace bench
