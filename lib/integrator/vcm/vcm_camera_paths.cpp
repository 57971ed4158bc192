// SPDX-License-Identifier: Apache-2.0
// The bidirectional modes' camera subpaths (vcm_integrator.h): emission hit, next event,
// connection to the light subpath of the same index (mod their count) and merging, each weighted by vcm_mis.h.
#include "integrator/camera_paths.h"
#include "integrator/vcm/vcm_integrator.h"
#include "integrator/vcm/vcm_vertex.h"
#include "scene/spawn.h"
#include "shading/shading_normals.h"

#include <cmath>

namespace ppm {

namespace {

// Shadow rays stop this far short of the point they run to, so it cannot block them.
double shadow_tfar(double distance, double p_error_a, double p_error_b) {
    return distance * (1 - 1e-7) - 8 * (p_error_a + p_error_b);
}

// The radiance of light `index` seen along a camera subpath whose last direction was `ray_dir`
// at a point with emitting normal `normal` (zero for lights at infinity), weighted against
// the techniques that sample that light.
double emitter_weight(const RenderScene &scene, const SubpathMis &mis, std::size_t index, const Vec3 &normal,
                      const Vec3 &ray_dir) {
    const Light &light = scene.lights()[index];
    const double pick = scene.light_probability(index);
    const EmissionDensities d = light.emission_densities(normal, ray_dir * -1.0);
    return mis_emitter_hit(mis, d.direct * pick, d.emission * pick);
}

// One sample on a light picked by power, seen from camera vertex `sp`.
Rgb next_event(const PassInputs &in, const MisFactors &factors, const SurfacePoint &sp, const SubpathMis &mis,
               CounterRng &rng) {
    const RenderScene &scene = in.scene;
    const double u_pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    if (scene.lights().empty() || scene.total_power().is_black()) return Rgb();
    double pick = 0;
    const Light &light = scene.lights()[scene.pick_light(u_pick, &pick)];
    const LightIllumination il = light.illuminate(sp.p, u1, u2);
    if (il.radiance.is_black() || !(il.direct_pdf_w > 0) || !(pick > 0)) return Rgb();
    const Vec3 wi = sp.frame.to_local(il.direction);
    const Rgb f = sp.bsdf.eval(sp.wo_local, wi, TransportMode::Radiance);
    if (f.is_black()) return Rgb();
    const double cont = vcm_continuation(sp.bsdf), cos_camera = std::fabs(wi.z);
    // No BSDF sample reaches a delta light.
    const double fwd = light.is_delta() ? 0.0 : sp.bsdf.pdf(sp.wo_local, wi) * cont;
    const double rev = sp.bsdf.pdf(wi, sp.wo_local) * cont;
    const double w = mis_next_event(factors, mis, fwd, rev, pick, il.direct_pdf_w, il.densities.emission,
                                    il.densities.cos_light, cos_camera);
    const double tfar = std::isinf(il.distance) ? INFINITY : shadow_tfar(il.distance, sp.hit.p_error, 0);
    if (!(tfar > 0) || scene.occluded(spawn_ray(sp.hit, il.direction, tfar), &sp.hit, light)) return Rgb();
    return il.radiance * f * (w * cos_camera / (pick * il.direct_pdf_w));
}

// Camera vertex `sp` joined to light vertex `v` by a segment.
Rgb connect(const PassInputs &in, const MisFactors &factors, const SurfacePoint &sp, const SubpathMis &mis,
            const VcmLightVertex &v) {
    const Vec3 to_light = v.sp.p - sp.p;
    const double d2 = length2(to_light);
    if (!(d2 > 0)) return Rgb();
    const double d = std::sqrt(d2);
    const Vec3 dir = to_light / d;
    const Vec3 wi_camera = sp.frame.to_local(dir);
    const Rgb f_camera = sp.bsdf.eval(sp.wo_local, wi_camera, TransportMode::Radiance);
    if (f_camera.is_black()) return Rgb();
    const Vec3 wi_light = v.sp.frame.to_local(dir * -1.0);
    const Rgb f_light = v.sp.bsdf.eval(v.sp.wo_local, wi_light, TransportMode::Importance);
    if (f_light.is_black()) return Rgb();
    const double cos_camera = std::fabs(wi_camera.z), cos_light = std::fabs(wi_light.z);
    const double cont_camera = vcm_continuation(sp.bsdf), cont_light = vcm_continuation(v.sp.bsdf);
    const double camera_fwd_a = sp.bsdf.pdf(sp.wo_local, wi_camera) * cont_camera * cos_light / d2;
    const double camera_rev_w = sp.bsdf.pdf(wi_camera, sp.wo_local) * cont_camera;
    const double light_fwd_a = v.sp.bsdf.pdf(v.sp.wo_local, wi_light) * cont_light * cos_camera / d2;
    const double light_rev_w = v.sp.bsdf.pdf(wi_light, v.sp.wo_local) * cont_light;
    const double w = mis_connection(factors, mis, v.mis, camera_fwd_a, camera_rev_w, light_fwd_a, light_rev_w);
    const double tfar = shadow_tfar(d, sp.hit.p_error, v.sp.hit.p_error);
    if (!(tfar > 0) || in.scene.scene().occluded(spawn_ray(sp.hit, dir, tfar), RayHints{&sp.hit})) return Rgb();
    return f_camera * f_light * v.throughput *
           (w * cos_camera * cos_light * light_path_shading_correction(v.sp, v.sp.wo_local, wi_light) / d2);
}

} // namespace

Rgb VcmIntegrator::trace_camera_path(const PassInputs &in, const VcmPassState &state, std::uint32_t pass,
                                     std::uint32_t pixel, std::uint32_t &merge_count) const {
    const RenderScene &scene = in.scene;
    const bool merge_only = techniques_ == Techniques::MergeOnly;
    CounterRng rng(in.settings.seed, kVcmCameraStream, pass, pixel);
    double film_density = 1;
    ppm_ray ray = camera_ray(in.camera, pixel, rng, &film_density);
    // The solid-angle density of this pixel's ray: the film position's density per pixel area
    // (the pixel filter's) over the pixel's solid angle.
    const double camera_pdf_w = vcm_camera_pdf_w(in.camera, state.pixel_area, Vec3::from(ray.dir)) * film_density;
    if (!(camera_pdf_w > 0)) return Rgb();
    // Without light tracing no technique makes the camera's first vertex from the light side.
    SubpathMis mis = SubpathMis::camera_start(state.mis, state.light_tracing ? camera_pdf_w : 0.0);
    Rgb throughput(1.0), radiance;
    bool specular_path = true; // only specular scattering so far
    SurfacePoint sp;
    const ppm_hit *leaving = nullptr;
    // Emission reached by this subpath: seen directly it has no other technique; merging only
    // counts it at the end of purely specular chains (photons carry the rest).
    const auto add_emission = [&](const Rgb &emitted, std::uint32_t length, const auto &weight) {
        if (length == 1)
            radiance += throughput * emitted;
        else if (merge_only)
            radiance += specular_path ? throughput * emitted : Rgb();
        else
            radiance += throughput * emitted * weight();
    };
    for (std::uint32_t length = 1;; ++length) {
        const Vec3 ray_dir = Vec3::from(ray.dir);
        if (!scene.intersect(ray, sp, leaving, &rng)) {
            for (std::size_t index : scene.environment_lights()) {
                const Rgb seen = scene.lights()[index].environment(ray_dir);
                if (!seen.is_black())
                    add_emission(seen, length, [&] { return emitter_weight(scene, mis, index, Vec3(), ray_dir); });
            }
            break;
        }
        const double cos_here = std::fabs(sp.wo_local.z);
        if (!(cos_here > 0)) break;
        mis.arrive(sp.hit.t * sp.hit.t, cos_here);
        if (!sp.emitted.is_black()) {
            const long index = scene.light_of_geometry(sp.hit.geom_id);
            if (index >= 0)
                add_emission(sp.emitted, length, [&] {
                    return emitter_weight(scene, mis, static_cast<std::size_t>(index), sp.frame.n, ray_dir);
                });
        }
        if (static_cast<int>(length) >= state.max_length) break;
        if (vcm_connectible(sp.bsdf)) {
            if (connects()) {
                radiance += throughput * next_event(in, state.mis, sp, mis, rng);
                const std::uint32_t light_path = pixel % state.light_paths;
                for (std::uint32_t k = state.path_start[light_path]; k < state.path_start[light_path + 1]; ++k) {
                    const VcmLightVertex &v = *state.vertices[k];
                    if (static_cast<int>(v.path_length + length + 1) > state.max_length) break;
                    radiance += throughput * connect(in, state.mis, sp, mis, v);
                }
            }
            if (merges()) {
                Rgb merged;
                const double cont = vcm_continuation(sp.bsdf);
                state.grid.for_each_within(sp.p, [&](std::uint32_t k) {
                    const VcmPassState::MergeRecord &v = state.merge_records[k];
                    if (static_cast<int>(v.path_length + length) > state.max_length) return;
                    const Vec3 wi = sp.frame.to_local(v.arriving);
                    const Rgb f = sp.bsdf.eval(sp.wo_local, wi, TransportMode::Radiance);
                    if (f.is_black()) return;
                    ++merge_count;
                    SubpathMis light;
                    light.dvcm = v.dvcm;
                    light.dvm = v.dvm;
                    const double w = merge_only ? 1.0
                                                : mis_merge(state.mis, mis, light, sp.bsdf.pdf(sp.wo_local, wi) * cont,
                                                            sp.bsdf.pdf(wi, sp.wo_local) * cont);
                    merged += f * v.throughput * (w * arriving_flux_shading_factor(sp, wi, v.cos_arriving));
                });
                const double normalisation = 1.0 / (M_PI * state.radius * state.radius * state.mis.light_paths);
                radiance += throughput * merged * normalisation;
                if (merge_only) break; // the photon map estimate ends the camera subpath
            }
        }
        VcmScatter s;
        if (!vcm_scatter(sp, rng, TransportMode::Radiance, s)) break;
        mis.scatter(state.mis, s.specular, std::fabs(s.wi.z), s.pdf_fwd, s.pdf_rev);
        throughput = throughput * s.weight;
        specular_path = specular_path && s.specular;
        ray = spawn_ray(sp.hit, sp.frame.to_world(s.wi));
        leaving = &sp.hit;
    }
    return radiance;
}

} // namespace ppm
