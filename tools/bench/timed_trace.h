// SPDX-License-Identifier: Apache-2.0
// One timed trace of a ray set, shared by `intersect` (driver.cpp) and `targets`.
#pragma once

#include "method.h"

#include <cstddef>
#include <vector>

namespace bench {

struct Timing {
    double cpu = 0, wall = 0; // process CPU seconds, wall seconds
    size_t rays = 0;          // rays traced, over every repetition
};

// Traces `rays` into `trace`, then again into a scratch trace until `min_seconds` of wall
// time have passed, so fast methods on small sets are timed over enough work. Single-thread
// runs (threads <= 1) are judged by rays / cpu: on a shared machine CPU time is the steadier
// of the two.
Timing timed_trace(const Method &method, const std::vector<ppm_ray> &rays, int threads, double min_seconds,
                   Trace &trace);

} // namespace bench
