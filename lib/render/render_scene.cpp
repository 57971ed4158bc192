// SPDX-License-Identifier: Apache-2.0
#include "render/render_scene.h"

#include "core/error.h"
#include "scene/quad_geometry.h"
#include "scene/sphere_geometry.h"

#include <algorithm>

namespace ppm {

namespace {

Light area_light(const Geometry &g, uint32_t geom_id, const Rgb &emission, double offset) {
    if (auto *quad = dynamic_cast<const QuadGeometry *>(&g)) {
        const QuadGeometry::Data &d = quad->data();
        Light light = Light::quad(d.origin, d.edge_u, d.edge_v, emission);
        light.set_surface_offset(offset);
        light.set_geometry(geom_id);
        return light;
    }
    if (auto *sphere = dynamic_cast<const SphereGeometry *>(&g)) {
        const SphereGeometry::Data &d = sphere->data();
        Light light = Light::sphere(d.center, d.radius, emission);
        light.set_surface_offset(offset);
        light.set_geometry(geom_id);
        return light;
    }
    invalid_argument("geometry " + std::to_string(geom_id) + " (" + g.kind() +
                     ") emits light, but only quads and spheres can be area lights");
}

} // namespace

RenderScene::RenderScene(const Scene &scene, const SceneShading &shading) : scene_(&scene) {
    if (!scene.committed()) fail(PPM_ERROR_INVALID_OPERATION, "the scene must be committed before rendering");
    const Material grey{Bsdf::diffuse(Rgb(0.5)), nullptr, {}};
    // Photons leave area lights a little more than a hit's error bound off the surface.
    const double offset =
        4 * scene.absolute_tolerance() + 1e-12 * max_abs_component(scene.bounds().upper - scene.bounds().lower);
    lights_ = shading.lights();
    for (uint32_t id = 0; id < scene.geometry_count(); ++id) {
        const Geometry &g = scene.geometry(id);
        if (shading.materials().empty()) {
            geometry_materials_.push_back(grey);
        } else if (g.material < shading.materials().size()) {
            geometry_materials_.push_back(shading.materials()[g.material]);
        } else {
            invalid_argument("geometry " + std::to_string(id) + " (" + g.kind() + ") has material id " +
                             std::to_string(g.material) + ", but the scene has only " +
                             std::to_string(shading.materials().size()) + " materials");
        }
        geometry_emission_.push_back(shading.emission(id));
        if (!geometry_emission_.back().is_black())
            lights_.push_back(area_light(g, id, geometry_emission_.back(), offset));
    }
    // Lights at infinity aim their photons at the committed scene's bounding sphere, a little
    // enlarged (as Mitsuba's set_scene) so that they start outside every surface.
    const Box3 &bounds = scene.bounds();
    const Vec3 center = bounds.empty() ? Vec3{0, 0, 0} : bounds.center();
    const double radius = bounds.empty() ? 1e-4 : std::max(1e-4, 0.5 * bounds.diagonal() * (1 + 1e-4) + offset);
    for (size_t i = 0; i < lights_.size(); ++i) {
        lights_[i].set_scene_sphere(center, radius);
        if (lights_[i].is_environment()) environment_lights_.push_back(i);
    }
    double sum = 0;
    for (const Light &light : lights_) {
        total_power_ += light.power();
        sum += light.power().mean();
        light_cdf_.push_back(sum);
    }
    for (double &c : light_cdf_) c = sum > 0 ? c / sum : 0;
}

size_t RenderScene::pick_light(double u, double *probability) const {
    const size_t i = std::min<size_t>(std::upper_bound(light_cdf_.begin(), light_cdf_.end(), u) - light_cdf_.begin(),
                                      lights_.size() - 1);
    *probability = light_cdf_[i] - (i > 0 ? light_cdf_[i - 1] : 0.0);
    return i;
}

Rgb RenderScene::environment(const Vec3 &direction) const {
    Rgb sum;
    if (environment_lights_.empty()) return sum;
    const Vec3 d = normalize(direction);
    for (size_t i : environment_lights_) sum += lights_[i].environment(d);
    return sum;
}

bool RenderScene::intersect(const ppm_ray &ray, SurfacePoint &out, const ppm_hit *leaving) const {
    scene_->intersect(ray, out.hit, false, RayHints{leaving});
    if (out.hit.geom_id == PPM_INVALID_ID) return false;
    shade(ray, out);
    return true;
}

void RenderScene::intersect_stream(const ppm_ray *rays, size_t count, SurfacePoint *out, bool *found) const {
    ppm_hit hits[Scene::max_stream];
    count = std::min(count, Scene::max_stream);
    scene_->intersect_stream(rays, nullptr, count, hits, false);
    for (size_t i = 0; i < count; ++i) {
        out[i].hit = hits[i];
        found[i] = hits[i].geom_id != PPM_INVALID_ID;
        if (found[i]) shade(rays[i], out[i]);
    }
}

void RenderScene::shade(const ppm_ray &ray, SurfacePoint &out) const {
    const Geometry &g = scene_->geometry(out.hit.geom_id);
    out.p = Vec3::from(out.hit.p);
    out.ng = Vec3::from(out.hit.ng);
    out.frame = Frame::from_normal(Vec3::from(out.hit.ns));
    const Vec3 wo = normalize(Vec3::from(ray.dir)) * -1.0;
    out.wo_local = out.frame.to_local(wo);
    const Material &material = geometry_materials_[out.hit.geom_id];
    if (material.texture) {
        g.compute_uv(out.hit);
        double s, t;
        g.texture_coordinates(out.hit, &s, &t);
        out.bsdf = material.at(s, t);
    } else {
        out.bsdf = material.bsdf;
    }
    const Rgb &emission = geometry_emission_[out.hit.geom_id];
    out.emitted = (!emission.is_black() && dot(out.ng, wo) > 0) ? emission : Rgb();
}

} // namespace ppm
