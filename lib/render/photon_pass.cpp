// Photon paths: emitted by lights in proportion to power, scattered with the adjoint BSDFs
// and Russian roulette, gathered at every visible point whose radius holds them.
#include "render/renderer.h"

#include "scene/scene.h"
#include "scene/spawn.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace ppm {

namespace {
constexpr std::uint8_t kPhotonStream = 1;
}

void Renderer::deposit(const Vec3 &position, const Vec3 &direction, const Rgb &flux) {
    const auto visit = [&](std::uint32_t index, double) {
        const HitPoint &hp = hit_points_[index];
        // A photon arriving from behind the visible point's surface (the far side of a thin
        // wall, the inside of a closed object) does not light it.
        if (dot(hp.normal, direction) >= 0) return;
        const VisiblePoint &vp = visible_[hp.pixel];
        const Rgb f = vp.bsdf.eval(vp.wo_local, vp.frame.to_local(-direction));
        flux_->add(hp.pixel, flux * f * vp.weight);
    };
    if (settings_.search == RenderSettings::Search::Grid)
        grid_.query(position, visit);
    else
        tree_.query(position, visit);
}

void Renderer::trace_photon(std::uint64_t index, std::uint32_t pass) {
    CounterRng rng(settings_.seed, kPhotonStream, pass, index);
    double light_probability = 0;
    const Light &light = render_scene_.lights()[render_scene_.pick_light(rng.uniform(), &light_probability)];
    const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform(), u4 = rng.uniform();
    const EmittedPhoton emitted = light.emit(u1, u2, u3, u4);
    Rgb flux = emitted.flux / light_probability;
    if (flux.is_black()) return;
    ppm_ray ray;
    emitted.origin.store(ray.org);
    emitted.direction.store(ray.dir);
    ray.tnear = 0;
    ray.tfar = INFINITY;
    SurfacePoint sp;
    for (int depth = 0; depth < settings_.max_depth; ++depth) {
        if (!render_scene_.intersect(ray, sp)) return;
        const Vec3 direction = Vec3::from(ray.dir);
        // Depth 0 is direct light, which the eye pass estimates by itself (unless told not to).
        if ((depth > 0 || !settings_.direct_lighting) && sp.bsdf.has_non_specular())
            deposit(sp.p, direction, flux);
        const double u_lobe = rng.uniform(), v1 = rng.uniform(), v2 = rng.uniform();
        const BsdfSample s = sp.bsdf.sample(sp.wo_local, u_lobe, v1, v2, TransportMode::Importance);
        if (!s.valid()) return;
        const Rgb scattered = flux * s.weight;
        // Russian roulette on the throughput's drop (pbrt-v3 SPPM): paths that lose power
        // end more often and survivors carry the difference, so the estimate stays unbiased.
        const double survive = std::min(1.0, scattered.max() / flux.max());
        if (!(survive > 0) || rng.uniform() >= survive) return;
        flux = scattered / survive;
        ray = spawn_ray(sp.hit, sp.frame.to_world(s.wi));
    }
}

void Renderer::photon_pass(std::uint32_t pass) {
    if (render_scene_.lights().empty() || render_scene_.total_power().is_black() || hit_points_.empty()) return;
    const std::uint64_t count = settings_.photons_per_pass;
    scene_->context().run([&] {
        tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, count, 1024), [&](const auto &range) {
            if (cancelled()) return;
            for (std::uint64_t i = range.begin(); i < range.end(); ++i) trace_photon(i, pass);
        });
    });
}

} // namespace ppm
