// SPDX-License-Identifier: Apache-2.0
// Runs one method over every ray set: built and traced on one thread, then on all threads,
// each trace timed and judged against the reference.
#pragma once

#include "evaluate.h"
#include "method.h"
#include "ray_sets.h"

#include <vector>

namespace bench {

struct SetResult {
    double rays_per_second_1t = 0;      // one thread, rays / process CPU time
    double rays_per_second_1t_wall = 0; // one thread, rays / wall time
    double rays_per_second_all = 0;     // all threads, rays / wall time (0 if not run)
    size_t thread_mismatches = 0;       // rays whose all-thread t differs from the one-thread t
    Stats stats;
};

struct MethodResult {
    MethodInfo info;
    BuildMemory memory;           // of the one-thread build
    double build_seconds_1t = 0;  // wall
    double build_seconds_all = 0; // wall (0 if not run)
    int threads_all = 0;          // threads of the all-thread run (0 if not run)
    std::vector<SetResult> sets;  // in the order of the ray sets
    std::vector<Trace> traces;    // one-thread traces, kept only when asked for
};

struct DriverOptions {
    int threads = 1; // of the all-thread run; 1 skips it
    double min_seconds = 0.1;
    double diagonal = 1;
};

MethodResult run_method(Method &method, const std::vector<RaySet> &sets, const DriverOptions &options,
                        bool keep_traces);

} // namespace bench
