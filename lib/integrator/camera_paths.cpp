// SPDX-License-Identifier: Apache-2.0
#include "integrator/camera_paths.h"

#include "scene/spawn.h"

#include <cmath>

namespace ppm {

ppm_ray camera_ray(const Camera &camera, std::uint32_t pixel, CounterRng &rng, double *film_density) {
    const std::uint32_t width = static_cast<std::uint32_t>(camera.width()), row = pixel / width;
    const double u1 = rng.uniform(), u2 = rng.uniform();
    double x, y, density;
    camera.filter().sample(static_cast<int>(pixel - row * width), static_cast<int>(row), u1, u2, &x, &y, &density);
    if (film_density) *film_density = density;
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

double footprint_r2(const PassInputs &in, double path_length) {
    const double r = in.settings.initial_radius > 0
                         ? in.settings.initial_radius
                         : in.settings.initial_radius_pixels * path_length * in.camera.pixel_size_at_unit_distance();
    return r * r;
}

VisiblePoint make_visible_point(const PassInputs &in, const SurfacePoint &sp, const Vec3 &ray_dir, const Rgb &weight,
                                double path_length) {
    VisiblePoint vp;
    vp.valid = true;
    vp.p = sp.p;
    vp.normal = dot(sp.ng, ray_dir) <= 0 ? sp.ng : -sp.ng;
    vp.p_error = sp.hit.p_error;
    vp.frame = sp.frame;
    vp.wo_local = sp.wo_local;
    vp.bsdf = sp.bsdf;
    vp.weight = weight;
    vp.initial_r2 = footprint_r2(in, path_length);
    return vp;
}

// Light by light, every point's sample is drawn before
// any shadow ray is traced: a sample is a chain of a square root and a division, and chains
// of different points overlap instead of each waiting for its own. Each point draws its
// numbers in the same order as alone (lights in turn).
void add_direct_light(const PassInputs &in, const VisiblePoint *vps, const ppm_hit *const *at, CounterRng *rngs,
                      std::uint32_t count, Rgb *direct) {
    if (!in.settings.direct_lighting) return;
    for (const Light &light : in.scene.lights()) {
        ppm_ray shadow_rays[kMaxDirectGroup];
        Rgb contributions[kMaxDirectGroup];
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
            if (!contributions[k].is_black() && !in.scene.occluded(shadow_rays[k], at[k], light))
                direct[k] += contributions[k];
    }
}

} // namespace ppm
