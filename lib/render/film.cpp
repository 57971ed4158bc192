#include "render/film.h"

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

void Film::commit_pass(Context &context, DensityEstimator &estimator, double alpha, std::uint64_t photons) {
    std::lock_guard<std::mutex> lock(mutex_);
    context.run([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slot_pixel_.size(), 4096), [&](const auto &range) {
            for (std::size_t slot = range.begin(); slot < range.end(); ++slot) {
                PixelStatistics &s = stats_[slot];
                const std::uint32_t index = static_cast<std::uint32_t>(slot);
                const PassPhotons pass_photons = estimator.take(index);
                // The first pass's radius: the hit point's (the initial radius while s.r2 == 0).
                const HitPoint &hit_point = estimator.hit_point(index);
                if (hit_point.present() && s.r2 == 0) s.r2 = hit_point.r2;
                progressive_update(s, pass_photons, alpha);
                s.direct += pass_direct_[slot];
            }
        });
    });
    photons_emitted_ += photons;
    passes_ += 1;
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
