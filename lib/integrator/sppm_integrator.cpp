// SPDX-License-Identifier: Apache-2.0
#include "integrator/sppm_integrator.h"

#include "core/error.h"
#include "integrator/camera_paths.h"
#include "scene/spawn.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace ppm {

namespace {

// The camera rays of this many consecutive pixels are traced as one coherent stream.
constexpr std::uint32_t kPathGroup = kMaxDirectGroup;

} // namespace

// What a group of camera paths holds while it is traced. Made once per task and reused by its
// groups: its visible points and surface points (~250 bytes each, with member initialisers)
// would otherwise be built afresh for every group, 16 KB per 32 pixels.
struct SppmIntegrator::PathGroup {
    CounterRng rngs[kPathGroup];
    ppm_ray rays[kPathGroup];
    SurfacePoint hits[kPathGroup];
    bool found[kPathGroup];
    VisiblePoint vps[kPathGroup];
    Rgb direct[kPathGroup];
    const ppm_hit *at[kPathGroup];
};

void SppmIntegrator::trace_paths(const PassInputs &in, std::uint32_t first, std::uint32_t count, std::uint32_t pass,
                                 Film &film, DensityEstimator &estimator, PathGroup &group) const {
    CounterRng *const rngs = group.rngs;
    ppm_ray *const rays = group.rays;
    SurfacePoint *const hits = group.hits;
    bool *const found = group.found;
    count = std::min(count, kPathGroup);
    for (std::uint32_t k = 0; k < count; ++k) {
        // The paths end reading their pixels' radii: fetch them early, or each path waits for
        // its 64-byte statistics record.
        __builtin_prefetch(&film.statistics(first + k));
        rngs[k] = CounterRng(in.settings.seed, kCameraStream, pass, first + k);
        rays[k] = camera_ray(in.camera, first + k, rngs[k]);
    }
    in.scene.intersect_stream(rays, count, hits, found, rngs);
    VisiblePoint *const vps = group.vps;
    Rgb *const direct = group.direct;
    const ppm_hit **const at = group.at;
    for (std::uint32_t k = 0; k < count; ++k) {
        direct[k] = follow_path(in, rngs[k], rays[k], hits[k], found[k], vps[k]);
        at[k] = &hits[k].hit; // the path ended at its visible point's hit
    }
    add_direct_light(in, vps, at, rngs, count, direct);
    for (std::uint32_t k = 0; k < count; ++k) {
        film.set_pass_direct(first + k, direct[k]);
        estimator.store(first + k, vps[k], gather_r2(film, first + k, vps[k]));
    }
}

Rgb SppmIntegrator::follow_path(const PassInputs &in, CounterRng &rng, ppm_ray ray, SurfacePoint &sp, bool found,
                                VisiblePoint &vp) {
    vp.valid = false;
    Rgb weight(1.0), direct;
    double length = 0;
    for (int depth = 0;; ++depth) {
        // A camera ray, or one after specular bounces, that leaves the scene sees the
        // environment (lights at infinity).
        if (!found) {
            direct += weight * in.scene.environment(Vec3::from(ray.dir));
            break;
        }
        length += sp.hit.t;
        direct += weight * sp.emitted;
        const double u_lobe = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        // Stop at a visible point or continue (Bsdf::continue_probability: the rule for glossy
        // lobes); sample() makes the same test, so below p_continue it takes a continued lobe.
        // Emission found after a continued bounce is added like after a specular one.
        const double p_continue = sp.bsdf.continue_probability(sp.wo_local, in.settings.glossy_gather_alpha);
        if (u_lobe >= p_continue) {
            vp = make_visible_point(in, sp, Vec3::from(ray.dir), weight / (1.0 - p_continue), length);
            break;
        }
        const BsdfSample s = sp.bsdf.sample(sp.wo_local, u_lobe, u1, u2, TransportMode::Radiance);
        if (!s.valid()) break;
        weight *= s.weight;
        if (weight.is_black()) break;
        if (depth + 1 >= in.settings.max_depth) break;
        ray = spawn_ray(sp.hit, sp.frame.to_world(s.wi));
        found = in.scene.intersect(ray, sp, &sp.hit, &rng); // leaving sp.hit
    }
    return direct;
}

void SppmIntegrator::make_eye_slots(const PassInputs &in, Film &film, DensityEstimator &estimator) {
    const std::uint32_t pixels = film.pixel_count();
    // Each slot's state: the film's and the estimator's.
    constexpr std::uint64_t slot_bytes = Film::kSlotBytes + DensityEstimator::kSlotBytes;
    allocate_or_fail(film.description(), pixels * slot_bytes, [&] {
        // the largest arrays first
        estimator.reset(pixels, in.flux_scale, in.scene.gathers_full_lobes(in.settings.glossy_gather_alpha));
        std::vector<std::uint32_t> slot_pixel(pixels);
        for (std::uint32_t p = 0; p < pixels; ++p) slot_pixel[p] = p;
        film.set_slots(std::move(slot_pixel));
    });
}

std::optional<HitPointBounds> SppmIntegrator::eye_pass(const PassInputs &in, std::uint32_t pass, Film &film,
                                                       DensityEstimator &estimator) {
    const std::uint32_t pixels = film.pixel_count();
    if (!film.has_slots()) make_eye_slots(in, film, estimator);
    // The hit points' bounds are measured as they are stored, while they are in the cache.
    using Range = tbb::blocked_range<std::uint32_t>;
    HitPointBounds eye_bounds;
    in.context.run([&] {
        eye_bounds = tbb::parallel_reduce(
            Range(0, pixels, 256), HitPointBounds{},
            [&](const Range &range, HitPointBounds bounds) {
                if (in.cancelled()) return bounds;
                PathGroup group;
                for (std::uint32_t p = range.begin(); p < range.end(); p += kPathGroup) {
                    const std::uint32_t count = std::min(kPathGroup, range.end() - p);
                    trace_paths(in, p, count, pass, film, estimator, group);
                    for (std::uint32_t k = 0; k < count; ++k) bounds.add(estimator.hit_point(p + k));
                }
                return bounds;
            },
            [](HitPointBounds a, const HitPointBounds &b) {
                a.add(b);
                return a;
            });
    });
    return eye_bounds;
}

} // namespace ppm
