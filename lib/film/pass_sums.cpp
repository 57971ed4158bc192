// SPDX-License-Identifier: Apache-2.0
#include "film/pass_sums.h"

#include <cmath>

namespace ppm {

namespace {

constexpr double kMaxQuanta = 0x1p80; // a pass estimate of 2^40 radiance units

} // namespace

Fixed128 PassSums::to_fixed(double v, int &rejected) {
    double x = v * 0x1p40; // exact: a power of two
    if (!(x >= 0)) {
        ++rejected;
        return 0;
    }
    if (x >= kMaxQuanta) {
        ++rejected;
        x = kMaxQuanta;
    }
    // Round half up; std::floor of a double is exact, and below 2^81 its conversion is too.
    return static_cast<Fixed128>(std::floor(x + 0.5));
}

int PassSums::add(std::size_t pixel, const Rgb &radiance, double radius, std::uint64_t photons) {
    int rejected = 0;
    Pixel &p = pixels_[pixel];
    p.radiance[0] += to_fixed(radiance.r, rejected);
    p.radiance[1] += to_fixed(radiance.g, rejected);
    p.radiance[2] += to_fixed(radiance.b, rejected);
    p.radius += to_fixed(radius, rejected);
    p.photons += photons;
    return rejected;
}

void PassSums::merge(const PassSums &other) {
    for (std::size_t i = 0; i < pixels_.size(); ++i) {
        Pixel &p = pixels_[i];
        const Pixel &o = other.pixels_[i];
        for (int c = 0; c < 3; ++c) p.radiance[c] += o.radiance[c];
        p.radius += o.radius;
        p.photons += o.photons;
    }
    passes_.merge(other.passes_);
    photons_emitted_ += other.photons_emitted_;
    rejected_ += other.rejected_;
}

void PassSums::mean_radiance(float *out) const {
    const std::uint64_t n = passes_.count();
    for (std::size_t i = 0; i < pixels_.size(); ++i)
        for (int c = 0; c < 3; ++c)
            out[3 * i + c] = n == 0 ? 0.0f : static_cast<float>(to_double(pixels_[i].radiance[c]) / double(n));
}

void PassSums::mean_radius(float *out) const {
    const std::uint64_t n = passes_.count();
    for (std::size_t i = 0; i < pixels_.size(); ++i)
        out[i] = n == 0 ? 0.0f : static_cast<float>(to_double(pixels_[i].radius) / double(n));
}

void PassSums::photon_sums(float *out) const {
    for (std::size_t i = 0; i < pixels_.size(); ++i) out[i] = static_cast<float>(pixels_[i].photons);
}

} // namespace ppm
