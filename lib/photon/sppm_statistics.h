// SPDX-License-Identifier: Apache-2.0
// Per-pixel statistics of stochastic progressive photon mapping (Hachisuka and Jensen 2009)
// and the accumulator that gathers one pass's photons into them.
//
// Each pass, for every pixel: M photons landed within its radius R of its visible point,
// carrying flux Phi in total (photon flux times the visible point's BSDF and path weight).
// The update is
//     N'   = N + alpha M
//     R'^2 = R^2 (N + alpha M) / (N + M)
//     tau' = (tau + Phi) R'^2 / R^2
// and the pixel's radiance after P passes and N_e photons emitted in all (including those
// that left the scene) is
//     L = tau / (pi R^2 N_e) + (sum of the passes' direct light) / P.
// A photon's flux is the power it carries as if it were the only photon emitted: dividing by
// N_e averages them.
#pragma once

#include "math/rgb.h"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace ppm {

// alpha = 2/3 gives the asymptotically fastest mean squared error, O(N^-2/3).
constexpr double kDefaultAlpha = 2.0 / 3.0;

struct PixelStatistics {
    double n = 0;  // N: photons accumulated so far, shrunk by alpha (fractional)
    double r2 = 0; // R^2: the gather radius squared; the renderer sets it before the first pass
    Rgb tau;       // flux within R, rescaled as R shrank
    Rgb direct;    // sum over passes of the direct light estimate at the pass's visible point
};

// One pass's photons at one pixel.
struct PassPhotons {
    std::uint64_t m = 0; // M
    Rgb phi;             // Phi
};

// Applies one pass with M photons of total flux Phi. M = 0 changes nothing (Phi is a sum over
// the M photons, so it is zero too, and the ratio would be 0/0 on the first pass).
void progressive_update(PixelStatistics &s, const PassPhotons &pass, double alpha = kDefaultAlpha);

// L above; the photon term is zero before any photon is emitted, the direct term before any pass.
Rgb radiance_estimate(const PixelStatistics &s, std::uint64_t photons_emitted, std::uint64_t passes);

// M and Phi for every pixel during a photon pass, added to by many threads at once, with sums
// that are bit-identical whatever the order of the additions and the number of threads.
//
// Floating-point sums depend on their order, so Phi is summed in fixed point: each channel of
// a photon's flux is rounded to a multiple of the quantum q = 2^(e-40), where 2^e is the
// power of two at or above the `flux_scale` given to the constructor, and the integers are
// added with atomic fetch-adds (exact, hence order-independent). A pass then reads the sum
// back as a double. Per-thread buffers merged in a fixed order would be deterministic only
// for a fixed split of photons into threads, and cost a frame buffer per thread.
//
// Range and precision, with S = 2^e (flux_scale <= S < 2 flux_scale):
//  - a channel value v is rounded to the nearest multiple of q = S 2^-40 (about 1e-12 S), so
//    photons much fainter than S lose relative precision, and below q/2 they add nothing;
//  - values in [0, 2^22 S) are taken as they are. Negative or NaN values add zero, values of
//    2^22 S or more (including +inf) add 2^22 S; both count in rejected(). Pick flux_scale
//    near the largest flux a photon normally carries (e.g. the brightest light's power);
//  - the sum per pixel and channel is a 96-bit integer (a 64-bit word whose wrap-arounds are
//    counted in a 32-bit word), so it cannot overflow before 2^56 S in one pass.
//  - M is a 64-bit count.
class FluxAccumulator {
public:
    FluxAccumulator(std::size_t pixel_count, double flux_scale);

    std::size_t pixel_count() const { return pixel_count_; }
    double quantum() const { return quantum_; }

    // Counts one photon at `pixel` < pixel_count() (M += 1) and adds its flux to Phi.
    // Thread-safe, lock-free.
    void add(std::size_t pixel, const Rgb &flux);

    // M and Phi of `pixel`, resetting them to zero for the next pass. Not to be called while
    // other threads add (a pass ends with a join, which orders the relaxed atomics).
    PassPhotons take(std::size_t pixel);

    // Channel values that were out of range since construction (see above).
    std::uint64_t rejected() const { return rejected_.load(std::memory_order_relaxed); }

private:
    // One cache line per pixel: a photon's four atomic adds then touch one line, not two.
    struct alignas(64) Cell {
        std::atomic<std::uint64_t> m{0};
        std::atomic<std::uint64_t> low[3] = {{0}, {0}, {0}};
        std::atomic<std::uint32_t> wraps[3] = {{0}, {0}, {0}};
    };

    void add_channel(Cell &c, int channel, double v);

    std::size_t pixel_count_;
    double quantum_;
    double inv_quantum_;
    std::unique_ptr<Cell[]> cells_;
    std::atomic<std::uint64_t> rejected_{0};
};

} // namespace ppm
