// SPDX-License-Identifier: Apache-2.0
// Times several built methods on the same ray sets in interleaved rounds, on one thread. On a
// shared machine the speed of the moment drifts by tens of percent within seconds; timing the
// methods one after another charges that drift to whichever method ran during it. In rounds,
// every method is timed once per round close in time to the others, so the ratio of two
// methods within one round sees mostly the same load, and the median over rounds discards the
// rounds a burst did hit.
#pragma once

#include "method.h"
#include "ray_sets.h"
#include "timed_trace.h"

#include <memory>
#include <vector>

namespace bench {

struct BuiltMethod {
    std::unique_ptr<Method> method; // built, kept built for every round
    BuildMemory memory;             // of its one-thread build
    double build_seconds = 0;       // wall

    size_t bytes() const { return memory.array_bytes + memory.structure_bytes; }
};

// One timing: one method tracing one ray set for at least min_seconds.
struct Sample {
    int round;          // 0-based
    int position;       // the method's place in the round's order, 0 = first
    size_t method, set; // indices into the methods and the ray sets
    Timing timing;

    // rays / process CPU time; 0 if no CPU time was measured.
    double rays_per_second() const { return timing.cpu > 0 ? double(timing.rays) / timing.cpu : 0; }
};

struct RoundsResult {
    int rounds = 0;
    std::vector<Sample> samples; // in the order they were taken
    // [method][set]: rays that the method hits and methods[0] misses, or the reverse, on their
    // first trace; a method that skips work looks fast, this shows it.
    std::vector<std::vector<size_t>> hit_differences;

    // Rays/s of `method` on `set`, indexed by round.
    std::vector<double> rates(size_t method, size_t set) const;
};

// Each round times every method on every set (the method order starts one further each
// round, so no method is always first or last); every timing is one timed_trace on one
// thread. Progress goes to stderr.
RoundsResult run_rounds(const std::vector<BuiltMethod> &methods, const std::vector<RaySet> &sets, int rounds,
                        double min_seconds);

} // namespace bench
