// SPDX-License-Identifier: Apache-2.0
// Counter-based random numbers: Philox4x32-10 (Salmon, Moraes, Dror and Shaw 2011, "Parallel
// random numbers: as easy as 1, 2, 3"; the generator of Random123 and cuRAND).
//
// Every number is a pure function of (seed, stream, pass, sample index, dimension), so a
// photon or a pixel sees the same numbers whichever thread traces it and in whatever order:
// images are independent of the thread count. Philox is a 10-round bijection of a 128-bit
// counter under a 64-bit key; it passes TestU01 BigCrush with rounds to spare (7 suffice).
//
// Layout: key = seed; counter = (index low 32 bits, index high 32 bits, pass,
// stream << 24 | block), and each block gives four uniforms of 32 bits (dimensions 4b to
// 4b + 3): a block costs ~13 ns, and the renderer draws about 10 numbers per photon path.
// 32 bits are as fine as single-precision renderers sample (pbrt-v4 draws floats).
#pragma once

#include <array>
#include <cstdint>

namespace ppm {

using PhiloxCounter = std::array<std::uint32_t, 4>;
using PhiloxKey = std::array<std::uint32_t, 2>;

inline PhiloxCounter philox4x32_10(PhiloxCounter c, PhiloxKey k) {
    constexpr std::uint32_t kM0 = 0xD2511F53, kM1 = 0xCD9E8D57; // round multipliers
    constexpr std::uint32_t kW0 = 0x9E3779B9, kW1 = 0xBB67AE85; // key schedule (Weyl)
    for (int round = 0; round < 10; ++round) {
        if (round > 0) {
            k[0] += kW0;
            k[1] += kW1;
        }
        const std::uint64_t p0 = static_cast<std::uint64_t>(kM0) * c[0];
        const std::uint64_t p1 = static_cast<std::uint64_t>(kM1) * c[2];
        c = {static_cast<std::uint32_t>(p1 >> 32) ^ c[1] ^ k[0], static_cast<std::uint32_t>(p1),
             static_cast<std::uint32_t>(p0 >> 32) ^ c[3] ^ k[1], static_cast<std::uint32_t>(p0)};
    }
    return c;
}

// The top 53 bits as a double in [0, 1): a multiple of 2^-53, at most 1 - 2^-53.
inline double uniform_from_bits(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1p-53; }

// 32 bits as a double in [0, 1): a multiple of 2^-32, at most 1 - 2^-32 (exact in a double).
inline double uniform_from_bits32(std::uint32_t bits) { return static_cast<double>(bits) * 0x1p-32; }

// The random numbers of one sample (a photon path, or a pixel's camera path) in one pass.
// `stream` keeps the renderer's uses apart (say 0 for camera paths, 1 for photons). A sample
// has 2^26 dimensions; beyond that they repeat. Lives on the stack; never allocates.
class CounterRng {
public:
    CounterRng() = default; // key and counter 0: assign a real one before use
    CounterRng(std::uint64_t seed, std::uint8_t stream, std::uint32_t pass, std::uint64_t index)
        : key_{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)},
          counter_{static_cast<std::uint32_t>(index), static_cast<std::uint32_t>(index >> 32), pass,
                   static_cast<std::uint32_t>(stream) << 24} {}

    // The next dimension, uniform in [0, 1).
    double uniform() {
        const std::uint32_t d = dimension_++;
        if ((d & 3) == 0) current_ = block(d >> 2);
        return uniform_from_bits32(current_[d & 3]);
    }

    // Dimension d of this sample, whatever has been drawn so far: uniform() returns
    // uniform_at(0), uniform_at(1), ... in turn.
    double uniform_at(std::uint32_t d) const { return uniform_from_bits32(block(d >> 2)[d & 3]); }

    // Dimensions drawn by uniform() so far.
    std::uint32_t dimension() const { return dimension_; }

private:
    PhiloxCounter block(std::uint32_t b) const {
        PhiloxCounter c = counter_;
        c[3] |= b & 0xFFFFFFu;
        return philox4x32_10(c, key_);
    }

    PhiloxKey key_;
    PhiloxCounter counter_;
    std::uint32_t dimension_ = 0;
    PhiloxCounter current_{}; // the block of the last dimension drawn
};

} // namespace ppm
