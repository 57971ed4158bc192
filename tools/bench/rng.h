// SPDX-License-Identifier: Apache-2.0
// The bench's random numbers: its own generator (splitmix64), not the platform's <random>
// distributions, so that every ray set is the same on every system for a given seed.
#pragma once

#include <cstdint>

namespace bench {

class SplitMix64 {
public:
    explicit SplitMix64(uint64_t seed) : state_(seed) {}
    uint64_t next() {
        uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, 1) with 53 random bits.
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }

private:
    uint64_t state_;
};

// A seed for stream `stream` of a generator seeded with `seed` (independent streams).
inline uint64_t derive_seed(uint64_t seed, uint64_t stream) {
    SplitMix64 mix(seed ^ (0xD1B54A32D192ED03ull * (stream + 1)));
    return mix.next();
}

} // namespace bench
