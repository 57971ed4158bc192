// SPDX-License-Identifier: Apache-2.0
#include "driver.h"

#include "measure.h"
#include "timed_trace.h"

#include <cmath>

#include <cstdio>

namespace bench {

namespace {

size_t mismatches(const Trace &a, const Trace &b) {
    size_t count = 0;
    for (size_t i = 0; i < a.size(); ++i) count += !(a.t[i] == b.t[i] || (std::isinf(a.t[i]) && std::isinf(b.t[i])));
    return count;
}

} // namespace

MethodResult run_method(Method &method, const std::vector<RaySet> &sets, const DriverOptions &options,
                        bool keep_traces) {
    MethodResult result;
    result.info = method.info();
    const MethodInfo &info = result.info;
    const double accuracy = info.tolerance;

    Stopwatch build;
    result.memory = method.build(1);
    result.build_seconds_1t = build.wall_seconds();
    std::fprintf(stderr, "%-20s %9zu primitives, built in %8.2f ms:", info.name.c_str(), info.primitives,
                 1e3 * result.build_seconds_1t);
    std::vector<Trace> traces(sets.size());
    for (size_t s = 0; s < sets.size(); ++s) {
        const RayBatch &batch = sets[s].batch(info.spawn_tolerance);
        const Timing timing = timed_trace(method, batch.rays, 1, options.min_seconds, traces[s]);
        SetResult r;
        r.rays_per_second_1t = timing.cpu > 0 ? double(timing.rays) / timing.cpu : 0;
        r.rays_per_second_1t_wall = timing.wall > 0 ? double(timing.rays) / timing.wall : 0;
        r.stats = evaluate(traces[s], batch.rays, batch.truth, options.diagonal, accuracy);
        result.sets.push_back(r);
        std::fprintf(stderr, " %s", sets[s].name.c_str());
    }
    method.release();
    std::fprintf(stderr, "\n");

    if (options.threads > 1) {
        result.threads_all = options.threads;
        build.restart();
        method.build(options.threads);
        result.build_seconds_all = build.wall_seconds();
        for (size_t s = 0; s < sets.size(); ++s) {
            const RayBatch &batch = sets[s].batch(info.spawn_tolerance);
            Trace trace;
            const Timing timing = timed_trace(method, batch.rays, options.threads, options.min_seconds, trace);
            result.sets[s].rays_per_second_all = timing.wall > 0 ? double(timing.rays) / timing.wall : 0;
            result.sets[s].thread_mismatches = mismatches(trace, traces[s]);
        }
        method.release();
    }
    if (keep_traces) result.traces = std::move(traces);
    return result;
}

} // namespace bench
