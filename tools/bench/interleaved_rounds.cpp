// SPDX-License-Identifier: Apache-2.0
#include "interleaved_rounds.h"

#include "measure.h"

#include <cmath>
#include <cstdio>

namespace bench {

namespace {

size_t hit_miss_differences(const Trace &a, const Trace &b) {
    size_t count = 0;
    for (size_t i = 0; i < a.size(); ++i) count += std::isinf(a.t[i]) != std::isinf(b.t[i]);
    return count;
}

} // namespace

std::vector<double> RoundsResult::rates(size_t method, size_t set) const {
    std::vector<double> out(size_t(rounds), 0.0);
    for (const Sample &s : samples)
        if (s.method == method && s.set == set) out[size_t(s.round)] = s.rays_per_second();
    return out;
}

RoundsResult run_rounds(const std::vector<BuiltMethod> &methods, const std::vector<RaySet> &sets, int rounds,
                        double min_seconds) {
    RoundsResult result;
    result.rounds = rounds;
    const size_t count = methods.size();
    // The first round's traces, compared with methods[0]'s once the round is over.
    std::vector<std::vector<Trace>> first(count, std::vector<Trace>(sets.size()));
    Stopwatch clock;
    for (int round = 0; round < rounds; ++round) {
        std::fprintf(stderr, "round %d/%d:", round + 1, rounds);
        for (size_t position = 0; position < count; ++position) {
            const size_t m = (size_t(round) + position) % count;
            const Method &method = *methods[m].method;
            std::fprintf(stderr, " %s", method.info().name.c_str());
            for (size_t s = 0; s < sets.size(); ++s) {
                Trace scratch;
                Trace &trace = round == 0 ? first[m][s] : scratch;
                const Timing timing = timed_trace(method, sets[s].base.rays, 1, min_seconds, trace);
                result.samples.push_back(Sample{round, int(position), m, s, timing});
            }
        }
        std::fprintf(stderr, " (%.1f s)\n", clock.wall_seconds());
        if (round == 0) {
            result.hit_differences.assign(count, std::vector<size_t>(sets.size(), 0));
            for (size_t m = 0; m < count; ++m)
                for (size_t s = 0; s < sets.size(); ++s)
                    result.hit_differences[m][s] = hit_miss_differences(first[m][s], first[0][s]);
            first.clear();
        }
    }
    return result;
}

} // namespace bench
