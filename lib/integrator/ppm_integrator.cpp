// SPDX-License-Identifier: Apache-2.0
#include "integrator/ppm_integrator.h"

#include "core/error.h"
#include "integrator/camera_paths.h"
#include "scene/spawn.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace ppm {

namespace {

// A pixel's path is split at glass at most this many times; further glass is sampled.
constexpr int kSplitBudget = 16;

} // namespace

// The visible points of one pixel's path in PPM mode, splitting at glass (both branches,
// Fresnel-weighted) and at coats (a visible point for the diffuse base and a branch for the
// reflection), and the emission seen along the way.
struct SplitPaths {
    std::vector<VisiblePoint> points;
    Rgb emitted;
};

template <class Emit> void PpmIntegrator::trace_split_path(const PassInputs &in, const ppm_ray &start,
                                                           const ppm_hit *leaving, Rgb weight, int depth, double length,
                                                           int &budget, std::uint32_t pixel, Emit &&emit) {
    ppm_ray ray = start;
    SurfacePoint sp;
    for (; depth < in.settings.max_depth; ++depth) {
        if (!in.scene.intersect(ray, sp, leaving)) {
            emit(nullptr, weight * in.scene.environment(Vec3::from(ray.dir))); // lights at infinity
            return;
        }
        leaving = &sp.hit; // every ray below is spawned from this hit
        length += sp.hit.t;
        emit(nullptr, weight * sp.emitted);
        const Vec3 dir = Vec3::from(ray.dir);
        const double gather_alpha = in.settings.glossy_gather_alpha;
        if (sp.bsdf.gathers(gather_alpha)) {
            // The gathered part (diffuse, a coat's base, a rough lobe of alpha >= gather_alpha)
            // becomes a visible point; a coat's reflection is followed as a branch.
            const VisiblePoint vp = make_visible_point(in, sp, dir, weight, length);
            emit(&vp, Rgb());
            if (sp.bsdf.continue_probability(sp.wo_local, gather_alpha) <= 0) return;
            // Coat reflection: sample() with u_lobe = 0 takes the specular lobe, and
            // weight * pdf is its Fresnel factor.
            const BsdfSample s = sp.bsdf.sample(sp.wo_local, 0.0, 0.5, 0.5, TransportMode::Radiance);
            if (!s.valid() || !s.is_specular) return;
            weight *= s.weight * s.pdf;
            ray = spawn_ray(sp.hit, sp.frame.to_world(s.wi));
            continue;
        }
        const BsdfSample reflected = sp.bsdf.sample(sp.wo_local, 0.0, 0.5, 0.5, TransportMode::Radiance);
        const BsdfSample transmitted = sp.bsdf.sample(sp.wo_local, 1.0 - 0x1p-53, 0.5, 0.5, TransportMode::Radiance);
        const bool two_branches = reflected.valid() && transmitted.valid() && reflected.is_specular &&
                                  transmitted.is_specular && reflected.pdf < 1 && transmitted.pdf < 1 &&
                                  reflected.wi.z * transmitted.wi.z < 0;
        if (two_branches && budget > 0) {
            --budget;
            trace_split_path(in, spawn_ray(sp.hit, sp.frame.to_world(reflected.wi)), &sp.hit,
                             weight * reflected.weight * reflected.pdf, depth + 1, length, budget, pixel, emit);
            weight *= transmitted.weight * transmitted.pdf;
            ray = spawn_ray(sp.hit, sp.frame.to_world(transmitted.wi));
            continue;
        }
        // One branch: a mirror, total internal reflection, glass beyond the split budget, or a
        // rough lobe narrower than glossy_gather_alpha (sampled with the pixel's own random
        // numbers, fixed for the whole render: the one direction PPM's fixed points follow).
        CounterRng rng(in.settings.seed, kCameraStream, 0,
                       (std::uint64_t(pixel) << 20) | std::uint64_t(depth) << 8 |
                           static_cast<std::uint64_t>(budget & 0xFF));
        const double u_lobe = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        const BsdfSample s = sp.bsdf.sample(sp.wo_local, u_lobe, u1, u2, TransportMode::Radiance);
        if (!s.valid()) return;
        weight *= s.weight;
        ray = spawn_ray(sp.hit, sp.frame.to_world(s.wi));
    }
}

void PpmIntegrator::trace_fixed_points(const PassInputs &in, Film &film, DensityEstimator &estimator) {
    const int width = in.camera.width(), height = in.camera.height();
    // The room for one slot per pixel first, in the largest per-slot arrays (a visible point is
    // about 250 bytes): a film too large fails now, not after tracing it. The film's and the
    // estimator's arrays are made once the slot count is known.
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    visible_.reserve(pixels), fixed_emitted_.reserve(pixels);
    std::vector<SplitPaths> rows(height);
    std::vector<std::vector<std::uint32_t>> row_pixels(height);
    std::vector<std::vector<Rgb>> row_emitted(height);
    in.context.run([&] {
        tbb::parallel_for(0, height, [&](int y) {
            if (in.cancelled()) return;
            for (int x = 0; x < width; ++x) {
                const std::uint32_t pixel = static_cast<std::uint32_t>(y) * width + x;
                CounterRng rng(in.settings.seed, kCameraStream, 0, pixel);
                const ppm_ray ray = camera_ray(in.camera, pixel, rng);
                const size_t first = rows[y].points.size();
                Rgb emitted;
                int budget = kSplitBudget;
                trace_split_path(in, ray, nullptr, Rgb(1.0), 0, 0.0, budget, pixel,
                                 [&](const VisiblePoint *vp, const Rgb &e) {
                                     if (vp) rows[y].points.push_back(*vp);
                                     emitted += e;
                                 });
                if (rows[y].points.size() == first) rows[y].points.push_back(VisiblePoint{}); // no point
                for (size_t k = first; k < rows[y].points.size(); ++k) {
                    row_pixels[y].push_back(pixel);
                    row_emitted[y].push_back(k == first ? emitted : Rgb());
                }
            }
        });
    });
    std::vector<std::uint32_t> slot_pixel;
    slot_pixel.reserve(pixels);
    visible_.clear();
    fixed_emitted_.clear();
    for (int y = 0; y < height; ++y) {
        slot_pixel.insert(slot_pixel.end(), row_pixels[y].begin(), row_pixels[y].end());
        visible_.insert(visible_.end(), rows[y].points.begin(), rows[y].points.end());
        fixed_emitted_.insert(fixed_emitted_.end(), row_emitted[y].begin(), row_emitted[y].end());
    }
    bool full_lobes = false;
    for (const VisiblePoint &vp : visible_) full_lobes = full_lobes || (vp.valid && vp.bsdf.needs_full_eval());
    estimator.reset(slot_pixel.size(), in.flux_scale, full_lobes);
    film.set_slots(std::move(slot_pixel));
}

void PpmIntegrator::make_eye_slots(const PassInputs &in, Film &film, DensityEstimator &estimator) {
    // At least one slot per pixel. A failed allocation leaves no slots, so that the next pass
    // starts over.
    constexpr std::uint64_t min_slot_bytes =
        Film::kSlotBytes + DensityEstimator::kSlotBytes + sizeof(VisiblePoint) + sizeof(Rgb);
    allocate_or_fail("the first PPM pass's hit points (at least this, one per pixel of " + film.description() + ")",
                     std::uint64_t(film.pixel_count()) * min_slot_bytes, [&] {
                         try {
                             trace_fixed_points(in, film, estimator);
                         } catch (...) {
                             film.clear_slots();
                             throw;
                         }
                     });
}

std::optional<HitPointBounds> PpmIntegrator::eye_pass(const PassInputs &in, std::uint32_t pass, Film &film,
                                                      DensityEstimator &estimator) {
    if (!film.has_slots()) make_eye_slots(in, film, estimator);
    if (in.cancelled()) return std::nullopt;
    // Direct light again at the fixed points, then the points stored with this pass's radii.
    using Range = tbb::blocked_range<std::size_t>;
    in.context.run([&] {
        tbb::parallel_for(Range(0, film.slot_count(), 256), [&](const Range &range) {
            if (in.cancelled()) return;
            for (std::size_t slot = range.begin(); slot < range.end(); ++slot) {
                CounterRng rng(in.settings.seed, kDirectStream, pass, slot);
                const ppm_hit *no_hit = nullptr;
                Rgb direct = fixed_emitted_[slot];
                add_direct_light(in, &visible_[slot], &no_hit, &rng, 1, &direct);
                film.set_pass_direct(slot, direct);
            }
        });
    });
    if (in.cancelled()) return std::nullopt;
    in.context.run([&] {
        tbb::parallel_for(Range(0, visible_.size(), 4096), [&](const Range &range) {
            for (std::size_t slot = range.begin(); slot < range.end(); ++slot) {
                const VisiblePoint &vp = visible_[slot];
                estimator.store(static_cast<std::uint32_t>(slot), vp, film.radius2(slot, vp.initial_r2));
            }
        });
    });
    return std::nullopt; // measured by the estimator
}

} // namespace ppm
