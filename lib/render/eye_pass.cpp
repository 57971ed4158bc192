// Camera paths: from the lens through mirrors and glass to the first surface that is not
// purely specular, where a visible point is stored and its direct light estimated.
#include "render/renderer.h"

#include "core/error.h"
#include "scene/scene.h"
#include "scene/spawn.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <cmath>

namespace ppm {

namespace {

constexpr std::uint8_t kCameraStream = 0;
constexpr std::uint8_t kDirectStream = 2; // PPM: direct light at the fixed points
// PPM splits a pixel's path at glass at most this many times; further glass is sampled.
constexpr int kSplitBudget = 16;
// SPPM traces the camera rays of this many consecutive pixels as one coherent stream.
constexpr std::uint32_t kPathGroup = static_cast<std::uint32_t>(Scene::max_stream);

ppm_ray camera_ray(const Camera &camera, std::uint32_t pixel, CounterRng &rng) {
    const std::uint32_t width = static_cast<std::uint32_t>(camera.width()), row = pixel / width;
    const double x = (pixel - row * width) + rng.uniform();
    const double y = row + rng.uniform();
    // A pinhole draws no lens sample (one counter block less per pixel).
    double lens_u = 0.5, lens_v = 0.5;
    if (camera.is_thin_lens()) {
        lens_u = rng.uniform();
        lens_v = rng.uniform();
    }
    const CameraRay cr = camera.generate_ray(x, y, lens_u, lens_v);
    ppm_ray ray;
    cr.origin.store(ray.org);
    cr.direction.store(ray.dir);
    ray.tnear = cr.tnear;
    ray.tfar = INFINITY;
    return ray;
}

} // namespace

double Renderer::footprint_r2(double path_length) const {
    const double r = settings_.initial_radius > 0
                         ? settings_.initial_radius
                         : settings_.initial_radius_pixels * path_length * camera_.pixel_size_at_unit_distance();
    return r * r;
}

VisiblePoint Renderer::make_visible_point(const SurfacePoint &sp, const Vec3 &ray_dir, const Rgb &weight,
                                          double path_length) const {
    VisiblePoint vp;
    vp.valid = true;
    vp.p = sp.p;
    vp.normal = dot(sp.ng, ray_dir) <= 0 ? sp.ng : -sp.ng;
    vp.p_error = sp.hit.p_error;
    vp.frame = sp.frame;
    vp.wo_local = sp.wo_local;
    vp.bsdf = sp.bsdf;
    vp.weight = weight;
    vp.initial_r2 = footprint_r2(path_length);
    return vp;
}

// One sample on every light, with a shadow ray each, for `count` (at most kPathGroup) visible
// points, added to direct[k]; invalid points get nothing. at[k]: point k's hit, if kept (the
// shadow rays leave it: Scene::occluded). Light by light, every point's sample is drawn before
// any shadow ray is traced: a sample is a chain of a square root and a division, and chains
// of different points overlap instead of each waiting for its own. Each point draws its
// numbers in the same order as alone (lights in turn).
void Renderer::add_direct_light(const VisiblePoint *vps, const ppm_hit *const *at, CounterRng *rngs,
                                std::uint32_t count, Rgb *direct) const {
    if (!settings_.direct_lighting) return;
    for (const Light &light : render_scene_.lights()) {
        ppm_ray shadow_rays[kPathGroup];
        Rgb contributions[kPathGroup];
        for (std::uint32_t k = 0; k < count; ++k) {
            const VisiblePoint &vp = vps[k];
            if (!vp.valid) continue;
            const double u1 = rngs[k].uniform(), u2 = rngs[k].uniform();
            const DirectLightSample ls = light.sample_direct(vp.p, u1, u2);
            if (ls.radiance_over_pdf.is_black()) continue;
            const Vec3 wi_local = vp.frame.to_local(ls.direction);
            const Rgb f = vp.bsdf.eval(vp.wo_local, wi_local);
            if (f.is_black()) continue;
            // Stop short of the light's own surface (area lights are geometry too).
            const double tfar = ls.distance * (1 - 1e-7) - 8 * vp.p_error;
            if (tfar <= 0) continue;
            shadow_rays[k] = spawn_ray(vp.p, vp.normal, vp.p_error, ls.direction, tfar);
            contributions[k] = vp.weight * f * ls.radiance_over_pdf * std::fabs(wi_local.z);
        }
        for (std::uint32_t k = 0; k < count; ++k)
            if (!contributions[k].is_black() && !render_scene_.occluded(shadow_rays[k], at[k], light))
                direct[k] += contributions[k];
    }
}

// What a group of camera paths holds while it is traced. Made once per task and reused by its
// groups: its visible points and surface points (~250 bytes each, with member initialisers)
// would otherwise be built afresh for every group, 16 KB per 32 pixels.
struct Renderer::PathGroup {
    CounterRng rngs[kPathGroup];
    ppm_ray rays[kPathGroup];
    SurfacePoint hits[kPathGroup];
    bool found[kPathGroup];
    VisiblePoint vps[kPathGroup];
    Rgb direct[kPathGroup];
    const ppm_hit *at[kPathGroup];
};

void Renderer::trace_sppm_paths(std::uint32_t first, std::uint32_t count, std::uint32_t pass, PathGroup &group) {
    CounterRng *const rngs = group.rngs;
    ppm_ray *const rays = group.rays;
    SurfacePoint *const hits = group.hits;
    bool *const found = group.found;
    count = std::min(count, kPathGroup);
    for (std::uint32_t k = 0; k < count; ++k) {
        // The paths end reading their pixels' radii: fetch them early, or each path waits for
        // its 64-byte statistics record.
        __builtin_prefetch(&stats_[first + k]);
        rngs[k] = CounterRng(settings_.seed, kCameraStream, pass, first + k);
        rays[k] = camera_ray(camera_, first + k, rngs[k]);
    }
    render_scene_.intersect_stream(rays, count, hits, found);
    VisiblePoint *const vps = group.vps;
    Rgb *const direct = group.direct;
    const ppm_hit **const at = group.at;
    for (std::uint32_t k = 0; k < count; ++k) {
        direct[k] = follow_sppm_path(rngs[k], rays[k], hits[k], found[k], vps[k]);
        at[k] = &hits[k].hit; // the path ended at its visible point's hit
    }
    add_direct_light(vps, at, rngs, count, direct);
    for (std::uint32_t k = 0; k < count; ++k) {
        pass_direct_[first + k] = direct[k];
        store_hit_point(first + k, vps[k]);
    }
}

Rgb Renderer::follow_sppm_path(CounterRng &rng, ppm_ray ray, SurfacePoint &sp, bool found, VisiblePoint &vp) const {
    vp.valid = false;
    Rgb weight(1.0), direct;
    double length = 0;
    for (int depth = 0; found; ++depth) {
        length += sp.hit.t;
        direct += weight * sp.emitted;
        const double u_lobe = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        if (sp.bsdf.has_non_specular()) {
            // The same test sample() makes: below p_specular it reflects off the coat.
            const double p_specular = sp.bsdf.specular_probability(sp.wo_local);
            if (u_lobe >= p_specular) {
                vp = make_visible_point(sp, Vec3::from(ray.dir), weight / (1.0 - p_specular), length);
                break;
            }
        }
        const BsdfSample s = sp.bsdf.sample(sp.wo_local, u_lobe, u1, u2, TransportMode::Radiance);
        if (!s.valid()) break;
        weight *= s.weight;
        if (weight.is_black()) break;
        if (depth + 1 >= settings_.max_depth) break;
        ray = spawn_ray(sp.hit, sp.frame.to_world(s.wi));
        found = render_scene_.intersect(ray, sp, &sp.hit); // leaving sp.hit
    }
    return direct;
}

// The visible points of one pixel's path in PPM mode, splitting at glass (both branches,
// Fresnel-weighted) and at coats (a visible point for the diffuse base and a branch for the
// reflection), and the emission seen along the way.
struct SplitPaths {
    std::vector<VisiblePoint> points;
    Rgb emitted;
};

template <class Emit> void Renderer::trace_split_path(const ppm_ray &start, const ppm_hit *leaving, Rgb weight,
                                                      int depth, double length, int &budget, std::uint32_t pixel,
                                                      Emit &&emit) {
    ppm_ray ray = start;
    SurfacePoint sp;
    for (; depth < settings_.max_depth; ++depth) {
        if (!render_scene_.intersect(ray, sp, leaving)) return;
        leaving = &sp.hit; // every ray below is spawned from this hit
        length += sp.hit.t;
        emit(nullptr, weight * sp.emitted);
        const Vec3 dir = Vec3::from(ray.dir);
        if (sp.bsdf.has_non_specular()) {
            const VisiblePoint vp = make_visible_point(sp, dir, weight, length);
            emit(&vp, Rgb());
            if (sp.bsdf.specular_probability(sp.wo_local) <= 0) return;
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
        const bool two_branches = reflected.valid() && transmitted.valid() && reflected.pdf < 1 &&
                                  transmitted.pdf < 1 && reflected.wi.z * transmitted.wi.z < 0;
        if (two_branches && budget > 0) {
            --budget;
            trace_split_path(spawn_ray(sp.hit, sp.frame.to_world(reflected.wi)), &sp.hit,
                             weight * reflected.weight * reflected.pdf, depth + 1, length, budget, pixel, emit);
            weight *= transmitted.weight * transmitted.pdf;
            ray = spawn_ray(sp.hit, sp.frame.to_world(transmitted.wi));
            continue;
        }
        // One branch: a mirror, total internal reflection, or glass beyond the split budget
        // (sampled with the pixel's own random numbers, fixed for the whole render).
        CounterRng rng(settings_.seed, kCameraStream, 0,
                       (std::uint64_t(pixel) << 20) | std::uint64_t(depth) << 8 |
                           static_cast<std::uint64_t>(budget & 0xFF));
        const BsdfSample s = sp.bsdf.sample(sp.wo_local, rng.uniform(), 0.5, 0.5, TransportMode::Radiance);
        if (!s.valid()) return;
        weight *= s.weight;
        ray = spawn_ray(sp.hit, sp.frame.to_world(s.wi));
    }
}

double Renderer::flux_scale() const {
    // Without any light (or only black ones) no photon is traced and the image is black; the
    // accumulator still needs a valid scale.
    const double power = render_scene_.total_power().max();
    return power > 0 ? power : 1.0;
}

void Renderer::init_pixel_slots() {
    const std::uint32_t pixels = static_cast<std::uint32_t>(camera_.width()) * camera_.height();
    // Each slot's state: pixel index, statistics, hit point, gather point, direct light and
    // the flux accumulator's cache line.
    constexpr std::uint64_t slot_bytes =
        sizeof(std::uint32_t) + sizeof(PixelStatistics) + DensityEstimator::kSlotBytes + sizeof(Rgb);
    // Built aside and moved in, so that a failed allocation leaves the renderer as it was;
    // the largest arrays first, so that a film too large fails before any memory is filled.
    allocate_or_fail(film_description(), pixels * slot_bytes, [&] {
        estimator_.reset(pixels, flux_scale()); // the largest arrays first
        std::vector<PixelStatistics> stats(pixels, PixelStatistics{});
        std::vector<Rgb> pass_direct(pixels, Rgb());
        std::vector<std::uint32_t> slot_pixel(pixels);
        for (std::uint32_t p = 0; p < pixels; ++p) slot_pixel[p] = p;
        visible_.clear();
        slot_pixel_ = std::move(slot_pixel);
        stats_ = std::move(stats);
        pass_direct_ = std::move(pass_direct);
    });
}

std::string Renderer::film_description() const {
    return "the film of " + std::to_string(camera_.width()) + " x " + std::to_string(camera_.height()) + " pixels";
}

std::optional<HitPointBounds> Renderer::eye_pass(std::uint32_t pass) {
    const std::uint32_t pixels = static_cast<std::uint32_t>(camera_.width()) * camera_.height();
    if (settings_.mode == RenderSettings::Mode::Sppm) {
        if (slot_pixel_.empty()) init_pixel_slots();
        // The hit points' bounds are measured as they are stored, while they are in the cache.
        using Range = tbb::blocked_range<std::uint32_t>;
        HitPointBounds eye_bounds;
        scene_->context().run([&] {
            eye_bounds = tbb::parallel_reduce(
                Range(0, pixels, 256), HitPointBounds{},
                [&](const Range &range, HitPointBounds bounds) {
                    if (cancelled()) return bounds;
                    PathGroup group;
                    for (std::uint32_t p = range.begin(); p < range.end(); p += kPathGroup) {
                        const std::uint32_t count = std::min(kPathGroup, range.end() - p);
                        trace_sppm_paths(p, count, pass, group);
                        for (std::uint32_t k = 0; k < count; ++k) bounds.add(estimator_.hit_point(p + k));
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

    // PPM: the first pass fixes the slots, at least one per pixel. A failed allocation leaves
    // no slots, so that the next pass starts over.
    constexpr std::uint64_t min_slot_bytes = sizeof(std::uint32_t) + sizeof(VisiblePoint) + sizeof(PixelStatistics) +
                                             DensityEstimator::kSlotBytes + 2 * sizeof(Rgb);
    allocate_or_fail("the first PPM pass's hit points (at least this, one per pixel of " + film_description() + ")",
                     std::uint64_t(pixels) * min_slot_bytes, [&] {
                         try {
                             init_ppm_slots();
                         } catch (...) {
                             slot_pixel_.clear();
                             throw;
                         }
                     });
    return std::nullopt; // the fixed points are stored and measured by build_search()
}

// Rows are traced in parallel into their own lists, joined in row order so slot numbers do not
// depend on scheduling.
void Renderer::init_ppm_slots() {
    const int width = camera_.width(), height = camera_.height();
    // The room for one slot per pixel first: a film too large fails now, not after tracing it.
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    slot_pixel_.reserve(pixels), visible_.reserve(pixels), fixed_emitted_.reserve(pixels);
    stats_.reserve(pixels), pass_direct_.reserve(pixels), estimator_.reserve(pixels);
    std::vector<SplitPaths> rows(height);
    std::vector<std::vector<std::uint32_t>> row_pixels(height);
    std::vector<std::vector<Rgb>> row_emitted(height);
    scene_->context().run([&] {
        tbb::parallel_for(0, height, [&](int y) {
            if (cancelled()) return;
            for (int x = 0; x < width; ++x) {
                const std::uint32_t pixel = static_cast<std::uint32_t>(y) * width + x;
                CounterRng rng(settings_.seed, kCameraStream, 0, pixel);
                const ppm_ray ray = camera_ray(camera_, pixel, rng);
                const size_t first = rows[y].points.size();
                Rgb emitted;
                int budget = kSplitBudget;
                trace_split_path(ray, nullptr, Rgb(1.0), 0, 0.0, budget, pixel,
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
    slot_pixel_.clear();
    visible_.clear();
    fixed_emitted_.clear();
    for (int y = 0; y < height; ++y) {
        slot_pixel_.insert(slot_pixel_.end(), row_pixels[y].begin(), row_pixels[y].end());
        visible_.insert(visible_.end(), rows[y].points.begin(), rows[y].points.end());
        fixed_emitted_.insert(fixed_emitted_.end(), row_emitted[y].begin(), row_emitted[y].end());
    }
    stats_.assign(slot_pixel_.size(), PixelStatistics{});
    pass_direct_.assign(slot_pixel_.size(), Rgb());
    estimator_.reset(slot_pixel_.size(), flux_scale());
}

void Renderer::direct_pass(std::uint32_t pass) {
    scene_->context().run([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slot_pixel_.size(), 256), [&](const auto &range) {
            if (cancelled()) return;
            for (std::size_t slot = range.begin(); slot < range.end(); ++slot) {
                CounterRng rng(settings_.seed, kDirectStream, pass, slot);
                const ppm_hit *no_hit = nullptr;
                Rgb direct = fixed_emitted_[slot];
                add_direct_light(&visible_[slot], &no_hit, &rng, 1, &direct);
                pass_direct_[slot] = direct;
            }
        });
    });
}

} // namespace ppm
