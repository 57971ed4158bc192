// SPDX-License-Identifier: Apache-2.0
#include "photon/sppm_statistics.h"

#include "core/error.h"

#include <cmath>

namespace ppm {

void progressive_update(PixelStatistics &s, const PassPhotons &pass, double alpha) {
    if (pass.m == 0) return;
    const double m = static_cast<double>(pass.m);
    const double n_next = s.n + alpha * m;
    // R'^2 / R^2 directly, rather than dividing the new radius by the old one.
    const double ratio = n_next / (s.n + m);
    s.n = n_next;
    s.r2 *= ratio;
    s.tau = (s.tau + pass.phi) * ratio;
}

Rgb radiance_estimate(const PixelStatistics &s, std::uint64_t photons_emitted, std::uint64_t passes) {
    Rgb l;
    if (photons_emitted > 0 && s.r2 > 0) l = s.tau / (M_PI * s.r2 * static_cast<double>(photons_emitted));
    if (passes > 0) l += s.direct / static_cast<double>(passes);
    return l;
}

namespace {

constexpr int kFractionBits = 40;     // q = S 2^-40
constexpr double kMaxQuanta = 0x1p62; // per value: v < 2^22 S
constexpr double kWrap = 0x1p64;      // weight of one wrap-around of the low word

} // namespace

FluxAccumulator::FluxAccumulator(std::size_t pixel_count, double flux_scale) : pixel_count_(pixel_count) {
    if (!(flux_scale > 0) || !std::isfinite(flux_scale))
        invalid_argument("flux scale must be positive and finite, got " + format_number(flux_scale));
    // S = 2^e, the power of two at or above flux_scale; q and 1/q are then exact powers of two
    // and v / q is one exact multiplication.
    int e;
    const double mantissa = std::frexp(flux_scale, &e); // flux_scale = mantissa 2^e, mantissa in [0.5, 1)
    if (mantissa == 0.5) --e;
    quantum_ = std::ldexp(1.0, e - kFractionBits);
    inv_quantum_ = std::ldexp(1.0, kFractionBits - e);
    if (!(quantum_ > 0) || !std::isfinite(inv_quantum_))
        invalid_argument("flux scale " + format_number(flux_scale) + " is out of range");
    cells_ = std::make_unique<Cell[]>(pixel_count);
}

void FluxAccumulator::add_channel(Cell &c, int channel, double v) {
    double x = v * inv_quantum_;
    if (!(x >= 0)) {
        x = 0;
        rejected_.fetch_add(1, std::memory_order_relaxed);
    } else if (x >= kMaxQuanta) {
        x = kMaxQuanta;
        rejected_.fetch_add(1, std::memory_order_relaxed);
    }
    // Round half up; x + 0.5 < 2^63, so the signed conversion is a single instruction.
    const auto quanta = static_cast<std::uint64_t>(static_cast<std::int64_t>(x + 0.5));
    if (quanta == 0) return;
    const std::uint64_t before = c.low[channel].fetch_add(quanta, std::memory_order_relaxed);
    // The addition that wraps the low word around is the one that sees it wrap: counting
    // those keeps the exact 96-bit sum whatever the order of the additions.
    if (before + quanta < before) c.wraps[channel].fetch_add(1, std::memory_order_relaxed);
}

void FluxAccumulator::add(std::size_t pixel, const Rgb &flux) {
    Cell &c = cells_[pixel];
    c.m.fetch_add(1, std::memory_order_relaxed);
    add_channel(c, 0, flux.r);
    add_channel(c, 1, flux.g);
    add_channel(c, 2, flux.b);
}

PassPhotons FluxAccumulator::take(std::size_t pixel) {
    Cell &c = cells_[pixel];
    double sum[3];
    for (int k = 0; k < 3; ++k) {
        const std::uint64_t low = c.low[k].exchange(0, std::memory_order_relaxed);
        const std::uint32_t wraps = c.wraps[k].exchange(0, std::memory_order_relaxed);
        // The integer sum is exact; turning it into a double rounds it the same way every run.
        sum[k] = (static_cast<double>(wraps) * kWrap + static_cast<double>(low)) * quantum_;
    }
    PassPhotons pass;
    pass.m = c.m.exchange(0, std::memory_order_relaxed);
    pass.phi = {sum[0], sum[1], sum[2]};
    return pass;
}

} // namespace ppm
