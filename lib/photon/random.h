// Counter-based random numbers: Philox4x32-10 (Salmon, Moraes, Dror and Shaw 2011, "Parallel
// random numbers: as easy as 1, 2, 3"; the generator of Random123 and cuRAND).
//
// Every number is a pure function of (seed, stream, pass, sample index, dimension), so a
// photon or a pixel sees the same numbers whichever thread traces it and in whatever order:
// images are independent of the thread count. Philox is a 10-round bijection of a 128-bit
// counter under a 64-bit key; it passes TestU01 BigCrush with rounds to spare (7 suffice).
//
// Layout: key = seed; counter = (index low 32 bits, index high 32 bits, pass,
// stream << 24 | block), and each block gives two doubles (dimensions 2b and 2b + 1).
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
inline double uniform_from_bits(std::uint64_t bits) {
    return static_cast<double>(bits >> 11) * 0x1p-53;
}

// The random numbers of one sample (a photon path, or a pixel's camera path) in one pass.
// `stream` keeps the renderer's uses apart (say 0 for camera paths, 1 for photons). A sample
// has 2^25 dimensions; beyond that they repeat. Lives on the stack; never allocates.
class CounterRng {
public:
    CounterRng(std::uint64_t seed, std::uint8_t stream, std::uint32_t pass, std::uint64_t index)
        : key_{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)},
          counter_{static_cast<std::uint32_t>(index), static_cast<std::uint32_t>(index >> 32), pass,
                   static_cast<std::uint32_t>(stream) << 24} {}

    // The next dimension, uniform in [0, 1).
    double uniform() {
        const std::uint32_t d = dimension_++;
        if (d & 1) return second_;
        const PhiloxCounter r = block(d >> 1);
        second_ = uniform_from_bits(join(r[3], r[2]));
        return uniform_from_bits(join(r[1], r[0]));
    }

    // Dimension d of this sample, whatever has been drawn so far: uniform() returns
    // uniform_at(0), uniform_at(1), ... in turn.
    double uniform_at(std::uint32_t d) const {
        const PhiloxCounter r = block(d >> 1);
        return (d & 1) ? uniform_from_bits(join(r[3], r[2])) : uniform_from_bits(join(r[1], r[0]));
    }

    // Dimensions drawn by uniform() so far.
    std::uint32_t dimension() const { return dimension_; }

private:
    static std::uint64_t join(std::uint32_t high, std::uint32_t low) {
        return static_cast<std::uint64_t>(high) << 32 | low;
    }
    PhiloxCounter block(std::uint32_t b) const {
        PhiloxCounter c = counter_;
        c[3] |= b & 0xFFFFFFu;
        return philox4x32_10(c, key_);
    }

    PhiloxKey key_;
    PhiloxCounter counter_;
    std::uint32_t dimension_ = 0;
    double second_ = 0; // dimension 2b + 1, drawn with 2b
};

} // namespace ppm
