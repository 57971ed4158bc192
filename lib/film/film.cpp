// SPDX-License-Identifier: Apache-2.0
#include "film/film.h"

#include "core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace ppm {

std::string Film::description() const {
    return "the film of " + std::to_string(width_) + " x " + std::to_string(height_) + " pixels";
}

void Film::set_slots(std::vector<std::uint32_t> slot_pixel) {
    // Built aside and moved in, so that a failed allocation leaves the film as it was.
    std::vector<PixelStatistics> stats(slot_pixel.size(), PixelStatistics{});
    std::vector<Rgb> pass_direct(slot_pixel.size(), Rgb());
    slot_pixel_ = std::move(slot_pixel);
    stats_ = std::move(stats);
    pass_direct_ = std::move(pass_direct);
}

void Film::commit_pass(Context &context, SlotPhotons &photons_found, double alpha, std::uint64_t photons) {
    std::lock_guard<std::mutex> lock(mutex_);
    context.run([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slot_pixel_.size(), 4096), [&](const auto &range) {
            for (std::size_t slot = range.begin(); slot < range.end(); ++slot) {
                PixelStatistics &s = stats_[slot];
                const std::uint32_t index = static_cast<std::uint32_t>(slot);
                const PassPhotons pass_photons = photons_found.take(index);
                // The first pass's radius: the hit point's (the initial radius while s.r2 == 0).
                const HitPoint &hit_point = photons_found.hit_point(index);
                if (hit_point.present() && s.r2 == 0) s.r2 = hit_point.r2;
                progressive_update(s, pass_photons, alpha);
                s.direct += pass_direct_[slot];
            }
        });
    });
    photons_emitted_ += photons;
    passes_ += 1;
}

void Film::set_pass_independent(bool independent) {
    if (independent == independent_) return;
    if (passes_.load() > 0) fail(PPM_ERROR_INVALID_OPERATION, "the film's mode cannot change after a pass");
    independent_ = independent;
    sums_ = PassSums();
}

void Film::ensure_sums() {
    if (sums_.pixel_count() == pixel_count()) return;
    PassSums sums;
    allocate_or_fail("the pass sums of " + description(), std::uint64_t(pixel_count()) * sizeof(PassSums::Pixel),
                     [&] { sums = PassSums(pixel_count()); });
    sums_ = std::move(sums);
}

void Film::commit_independent_pass(Context &context, SlotPhotons &photons_found, std::uint64_t pass,
                                   std::uint64_t photons) {
    std::lock_guard<std::mutex> lock(mutex_);
    ensure_sums();
    const double per_photon = 1.0 / static_cast<double>(photons);
    std::atomic<std::uint64_t> rejected{0};
    context.run([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slot_pixel_.size(), 4096), [&](const auto &range) {
            std::uint64_t rejected_here = 0;
            for (std::size_t slot = range.begin(); slot < range.end(); ++slot) {
                const std::uint32_t index = static_cast<std::uint32_t>(slot);
                const PassPhotons pass_photons = photons_found.take(index);
                const HitPoint &hit_point = photons_found.hit_point(index);
                Rgb l = pass_direct_[slot];
                double radius = 0;
                if (hit_point.present()) {
                    radius = std::sqrt(hit_point.r2);
                    if (pass_photons.m > 0 && hit_point.r2 > 0)
                        l += pass_photons.phi * (per_photon / (M_PI * hit_point.r2));
                }
                // One slot per pixel: each pixel's sums are added to by one thread.
                rejected_here += sums_.add(slot_pixel_[slot], l, radius, pass_photons.m);
            }
            rejected.fetch_add(rejected_here, std::memory_order_relaxed);
        });
    });
    sums_.add_rejected(rejected.load());
    sums_.passes().insert(pass);
    sums_.add_photons_emitted(photons);
    photons_emitted_ += photons;
    passes_.store(sums_.passes().count());
}

void Film::commit_estimated_pass(std::uint64_t pass, const PassEstimate &estimate) {
    std::lock_guard<std::mutex> lock(mutex_);
    ensure_sums();
    std::uint64_t rejected = 0;
    for (std::uint32_t p = 0; p < pixel_count(); ++p)
        rejected += sums_.add(p, estimate.radiance[p], estimate.radius, estimate.merges[p]);
    sums_.add_rejected(rejected);
    sums_.passes().insert(pass);
    sums_.add_photons_emitted(estimate.light_paths);
    photons_emitted_ += estimate.light_paths;
    passes_.store(sums_.passes().count());
}

void Film::merge_sums(const PassSums &other) {
    std::lock_guard<std::mutex> lock(mutex_);
    ensure_sums();
    sums_.merge(other);
    photons_emitted_.store(sums_.photons_emitted());
    passes_.store(sums_.passes().count());
}

std::uint64_t Film::lowest_missing_pass() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return sums_.passes().lowest_missing();
}

bool Film::holds_pass(std::uint64_t pass) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return sums_.passes().contains(pass);
}

std::size_t Film::layer_channels(const std::string &name) {
    if (name == "radiance") return 3;
    if (name == "radius" || name == "photons") return 1;
    invalid_argument("unknown image layer '" + name + "' (layers: radiance, radius, photons)");
}

void Film::read_layer(const std::string &name, float *out) const {
    const std::size_t channels = layer_channels(name);
    const std::size_t pixels = pixel_count();
    std::fill(out, out + pixels * channels, 0.0f);
    std::lock_guard<std::mutex> lock(mutex_);
    const std::uint64_t emitted = photons_emitted_.load(), passes = passes_.load();
    // Until a pass completes, the running pass makes the slots and statistics without this
    // lock (SPPM's slots, PPM's first eye pass): there is nothing to read yet, and touching
    // them would race. passes_ grows under the lock once they are final.
    if (passes == 0) return;
    if (independent_) {
        if (name == "radiance")
            sums_.mean_radiance(out);
        else if (name == "radius")
            sums_.mean_radius(out);
        else
            sums_.photon_sums(out);
        return;
    }
    for (std::size_t slot = 0; slot < slot_pixel_.size(); ++slot) {
        const PixelStatistics &s = stats_[slot];
        float *pixel = out + static_cast<std::size_t>(slot_pixel_[slot]) * channels;
        if (name == "radiance") {
            const Rgb l = radiance_estimate(s, emitted, passes);
            pixel[0] += static_cast<float>(l.r);
            pixel[1] += static_cast<float>(l.g);
            pixel[2] += static_cast<float>(l.b);
        } else if (name == "radius") {
            pixel[0] = std::max(pixel[0], static_cast<float>(std::sqrt(s.r2)));
        } else {
            pixel[0] += static_cast<float>(s.n);
        }
    }
}

void Film::restore(std::vector<PixelStatistics> stats, std::uint64_t passes, std::uint64_t photons_emitted) {
    std::lock_guard<std::mutex> lock(mutex_);
    stats_ = std::move(stats);
    photons_emitted_.store(photons_emitted);
    passes_.store(passes);
}

} // namespace ppm
