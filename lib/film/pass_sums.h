// SPDX-License-Identifier: Apache-2.0
// The state of a pass-independent render: per pixel, the sums over its passes of the pass
// estimates (radiance, gather radius, photons found), and which passes they hold.
//
// Exactness: each pass's estimate is rounded once to a multiple of the quantum q = 2^-40 (in
// radiance units, W/(m^2 sr), or scene units for the radius) and the multiples are summed as
// 128-bit integers. Integer addition is associative and exact, so the sums of a set of passes
// are the same bits whatever order the passes were rendered or merged in and however they
// were split between processes. A pass estimate below q/2 adds nothing; one at or above
// 2^40 (about 1.1e12) adds 2^40, and NaN or a negative value adds zero: both are counted in
// rejected(). The image is the sum divided by the pass count.
#pragma once

#include "film/pass_set.h"
#include "math/rgb.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace ppm {

__extension__ typedef __int128 Fixed128; // multiples of PassSums::kQuantum

class PassSums {
public:
    static constexpr int kFractionBits = 40;
    static constexpr double kQuantum = 0x1p-40;

    struct Pixel {
        Fixed128 radiance[3] = {0, 0, 0};
        Fixed128 radius = 0;
        std::uint64_t photons = 0; // photons found within the radius, summed
    };

    PassSums() = default;
    explicit PassSums(std::size_t pixels) : pixels_(pixels) {}

    std::size_t pixel_count() const { return pixels_.size(); }
    const std::vector<Pixel> &pixels() const { return pixels_; }
    std::vector<Pixel> &pixels() { return pixels_; }
    const PassSet &passes() const { return passes_; }
    PassSet &passes() { return passes_; }
    std::uint64_t photons_emitted() const { return photons_emitted_; }
    void add_photons_emitted(std::uint64_t n) { photons_emitted_ += n; }
    std::uint64_t rejected() const { return rejected_; }
    void add_rejected(std::uint64_t n) { rejected_ += n; }

    // One pass estimate at `pixel`; distinct pixels may be added from distinct threads.
    // Returns the number of rejected values (see above) for the caller to count.
    int add(std::size_t pixel, const Rgb &radiance, double radius, std::uint64_t photons);

    // Adds `other`'s sums, passes and counts (the caller checks that the passes are disjoint
    // and the pixel counts equal).
    void merge(const PassSums &other);

    // Per pixel: the mean radiance (3 floats), mean radius (1) or photon sum (1).
    void mean_radiance(float *out) const;
    void mean_radius(float *out) const;
    void photon_sums(float *out) const;

    static Fixed128 to_fixed(double v, int &rejected);
    static double to_double(Fixed128 v) { return static_cast<double>(v) * kQuantum; }

private:
    std::vector<Pixel> pixels_;
    PassSet passes_;
    std::uint64_t photons_emitted_ = 0;
    std::uint64_t rejected_ = 0;
};

} // namespace ppm
