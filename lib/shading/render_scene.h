// SPDX-License-Identifier: Apache-2.0
// What the renderer reads of a committed scene, gathered once when a renderer is created:
// the lights (point, spot and lights at infinity, plus one area light per emitting geometry;
// lights at infinity are given the scene's bounding sphere) with
// the probabilities photons pick them by, and a material for every geometry.
#pragma once

#include <ppm/ppm.h>

#include "light/light.h"
#include "material/bsdf.h"
#include "material/material.h"
#include "photon/random.h"
#include "scene/scene.h"
#include "shading/scene_shading.h"

#include <vector>

namespace ppm {

// A surface point as the integrator sees it: the hit, its BSDF (texture applied) and the
// shading frame. Directions in `frame` are local; `wo` points back along the arriving ray.
struct SurfacePoint {
    ppm_hit hit;
    Vec3 p, ng;    // ng as stored (not flipped)
    Frame frame;   // z = shading normal
    Vec3 wo_local; // unit
    Bsdf bsdf;
    Rgb emitted; // radiance the surface emits towards wo (area lights, front side)
};

class RenderScene {
public:
    // Throws ppm::Error: INVALID_OPERATION if the scene is not committed, INVALID_ARGUMENT
    // for a geometry whose material id names no material (when the scene has materials; a
    // scene without any renders everything diffuse grey 0.5) or emission on a kind other
    // than quad and sphere.
    RenderScene(const Scene &scene, const SceneShading &shading);

    const Scene &scene() const { return *scene_; }
    const std::vector<Light> &lights() const { return lights_; }
    Rgb total_power() const { return total_power_; }

    // Index of the light a photon starts from, chosen in proportion to mean power, and that
    // probability. Requires total_power() to be non-zero.
    size_t pick_light(double u, double *probability) const;
    // The probability pick_light picks light `index` with.
    double light_probability(size_t index) const {
        return light_cdf_[index] - (index > 0 ? light_cdf_[index - 1] : 0.0);
    }
    // Index into lights() of the area light a geometry is, or -1 when it emits nothing.
    long light_of_geometry(uint32_t geom_id) const { return geometry_light_[geom_id]; }
    // Indices into lights() of the environment lights (constant, envmap).
    const std::vector<size_t> &environment_lights() const { return environment_lights_; }

    // Closest hit along ray, described; false on a miss. `leaving`: the hit the ray was
    // spawned from, if any (RayHints::leaving); it may be &out.hit. `rng`: the path's
    // generator, drawn from (once per level) only where a blend or mask material picks its
    // component; without one the pick comes from a hash of the ray and the hit, which is as
    // deterministic.
    bool intersect(const ppm_ray &ray, SurfacePoint &out, const ppm_hit *leaving = nullptr,
                   CounterRng *rng = nullptr) const;
    // The same for up to Scene::max_stream rays from no surface (a camera's), traced as a
    // coherent stream: found[i] and out[i] as intersect(rays[i], out[i], nullptr, &rngs[i])
    // gives (rngs may be null).
    void intersect_stream(const ppm_ray *rays, size_t count, SurfacePoint *out, bool *found,
                          CounterRng *rngs = nullptr) const;
    // Whether anything blocks a shadow ray leaving `leaving` (may be null) that stops short of
    // `light`'s surface, so that the light's own geometry cannot block it.
    bool occluded(const ppm_ray &ray, const ppm_hit *leaving, const Light &light) const {
        return scene_->occluded(ray, RayHints{leaving, light.geometry()});
    }
    // Whether any material stores visible points that evaluate the whole BSDF per photon
    // (Bsdf::needs_full_eval and gathers(gather_alpha)): DensityEstimator::reset's full_lobes.
    bool gathers_full_lobes(double gather_alpha) const;
    // Radiance arriving from the environment lights (constant, envmap) along `direction`
    // (any length), which a ray that leaves the scene sees; black without such lights.
    Rgb environment(const Vec3 &direction) const;
    bool has_environment() const { return !environment_lights_.empty(); }
    // Area light radiance of a geometry (black for most).
    const Rgb &emission(uint32_t geom_id) const { return geometry_emission_[geom_id]; }

private:
    // Fills `out` from its described hit, seen along `ray`.
    void shade(const ppm_ray &ray, SurfacePoint &out, CounterRng *rng) const;

    const Scene *scene_;
    std::vector<Material> geometry_materials_; // one per geometry
    std::vector<Material> materials_;          // the scene's: the components of blends and masks
    std::vector<Rgb> geometry_emission_;       // one per geometry
    std::vector<long> geometry_light_;         // one per geometry: index into lights_, or -1
    std::vector<Light> lights_;
    std::vector<size_t> environment_lights_; // indices into lights_
    std::vector<double> light_cdf_;          // cumulative selection probabilities
    Rgb total_power_;
};

} // namespace ppm
