// SPDX-License-Identifier: Apache-2.0
#include "shading/render_scene.h"

#include "core/error.h"
#include "scene/cylinder_geometry.h"
#include "scene/disk_geometry.h"
#include "scene/mesh_geometry.h"
#include "scene/quad_geometry.h"
#include "scene/sphere_geometry.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <typeindex>
#include <typeinfo>

namespace ppm {

namespace {

// The area light of each geometry kind that can emit: one row per kind. A kind without a row
// cannot be an area light (its emission is refused by name).
struct AreaLightMaker {
    std::type_index kind;
    Light (*make)(const Geometry &g, const Rgb &emission);
};

template <class G> const typename G::Data &data_of(const Geometry &g) { return static_cast<const G &>(g).data(); }

const AreaLightMaker kAreaLightMakers[] = {
    {typeid(QuadGeometry),
     [](const Geometry &g, const Rgb &emission) {
         const QuadGeometry::Data &d = data_of<QuadGeometry>(g);
         // Flipped: the same parallelogram with its edges swapped, so its normal reversed.
         return g.flip_normals ? Light::quad(d.origin, d.edge_v, d.edge_u, emission)
                               : Light::quad(d.origin, d.edge_u, d.edge_v, emission);
     }},
    {typeid(SphereGeometry),
     [](const Geometry &g, const Rgb &emission) {
         const SphereGeometry::Data &d = data_of<SphereGeometry>(g);
         return Light::sphere(d.center, d.radius, emission);
     }},
    {typeid(DiskGeometry),
     [](const Geometry &g, const Rgb &emission) {
         const DiskGeometry::Data &d = data_of<DiskGeometry>(g);
         return Light::disk(d.center, d.axis_u, d.axis_v, emission, g.flip_normals);
     }},
    {typeid(CylinderGeometry),
     [](const Geometry &g, const Rgb &emission) {
         const CylinderGeometry::Data &d = data_of<CylinderGeometry>(g);
         return Light::cylinder(d.p0, d.p1, d.radius, emission, g.flip_normals);
     }},
    {typeid(MeshGeometry),
     [](const Geometry &g, const Rgb &emission) {
         return Light::mesh(static_cast<const MeshGeometry &>(g).shared_world(), emission, g.flip_normals);
     }},
};

Light make_area_light(const Geometry &g, uint32_t geom_id, const Rgb &emission) {
    for (const AreaLightMaker &maker : kAreaLightMakers)
        if (maker.kind == std::type_index(typeid(g))) return maker.make(g, emission);
    invalid_argument("geometry " + std::to_string(geom_id) + " (" + g.kind() +
                     ") emits light, but only quads, spheres, disks, cylinders and triangle meshes can be area lights");
}

Light area_light(const Geometry &g, uint32_t geom_id, const Rgb &emission, double offset) {
    Light light = make_area_light(g, geom_id, emission);
    light.set_surface_offset(offset);
    light.set_geometry(geom_id);
    return light;
}

} // namespace

RenderScene::RenderScene(const Scene &scene, const SceneShading &shading) : scene_(&scene) {
    if (!scene.committed()) fail(PPM_ERROR_INVALID_OPERATION, "the scene must be committed before rendering");
    const Material grey{Bsdf::diffuse(Rgb(0.5)), {}};
    materials_ = shading.materials();
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
        geometry_light_.push_back(-1);
        if (!geometry_emission_.back().is_black()) {
            geometry_light_.back() = static_cast<long>(lights_.size());
            lights_.push_back(area_light(g, id, geometry_emission_.back(), offset));
        }
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

bool RenderScene::intersect(const ppm_ray &ray, SurfacePoint &out, const ppm_hit *leaving, CounterRng *rng) const {
    scene_->intersect(ray, out.hit, false, RayHints{leaving});
    if (out.hit.geom_id == PPM_INVALID_ID) return false;
    shade(ray, out, rng);
    return true;
}

void RenderScene::intersect_stream(const ppm_ray *rays, size_t count, SurfacePoint *out, bool *found,
                                   CounterRng *rngs) const {
    ppm_hit hits[Scene::max_stream];
    count = std::min(count, Scene::max_stream);
    scene_->intersect_stream(rays, nullptr, count, hits, false);
    for (size_t i = 0; i < count; ++i) {
        out[i].hit = hits[i];
        found[i] = hits[i].geom_id != PPM_INVALID_ID;
        if (found[i]) shade(rays[i], out[i], rngs ? &rngs[i] : nullptr);
    }
}

namespace {

std::uint64_t mix64(std::uint64_t x) { // splitmix64's finaliser
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// A uniform number in [0, 1) from the ray and the hit, for picks made without a generator.
double hash_uniform(const ppm_ray &ray, const ppm_hit &hit, int level) {
    std::uint64_t h =
        mix64(static_cast<std::uint64_t>(hit.geom_id) << 32 ^ hit.prim_id ^ 0x9e3779b97f4a7c15ull * (level + 1));
    const double values[6] = {ray.org[0], ray.org[1], ray.org[2], ray.dir[0], ray.dir[1], ray.dir[2]};
    for (double v : values) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        h = mix64(h ^ bits);
    }
    return uniform_from_bits(h);
}

} // namespace

void RenderScene::shade(const ppm_ray &ray, SurfacePoint &out, CounterRng *rng) const {
    const Geometry &g = scene_->geometry(out.hit.geom_id);
    out.p = Vec3::from(out.hit.p);
    out.ng = Vec3::from(out.hit.ng);
    out.frame = Frame::from_normal(Vec3::from(out.hit.ns));
    const Vec3 wo = normalize(Vec3::from(ray.dir)) * -1.0;
    out.wo_local = out.frame.to_local(wo);
    const Material *material = &geometry_materials_[out.hit.geom_id];
    bool have_uv = false;
    double s = 0, t = 0;
    const auto uv = [&] {
        if (!have_uv) {
            g.compute_uv(out.hit);
            g.texture_coordinates(out.hit, &s, &t);
            have_uv = true;
        }
    };
    // Blends and masks pick one component with its probability: the expected BSDF is their
    // weighted sum, for camera paths and photons alike (one uniform number per level).
    bool pass_through = false;
    for (int level = 0; material->kind != Material::Kind::Single; ++level) {
        if (material->weight_texture) uv();
        const double w = material->weight_at(s, t);
        const double u = rng ? rng->uniform() : hash_uniform(ray, out.hit, level);
        if (material->kind == Material::Kind::Mask && u >= w) {
            pass_through = true;
            break;
        }
        const uint32_t next =
            material->kind == Material::Kind::Blend && u < w ? material->parts[1] : material->parts[0];
        material = &materials_[next];
    }
    if (pass_through) {
        out.bsdf = Bsdf::null();
    } else if (material->texture) {
        uv();
        out.bsdf = material->at(s, t);
    } else {
        out.bsdf = material->bsdf;
    }
    // Emitted on the side of the shading normal, the normal a light samples with (light.h);
    // the same as the geometric one except on meshes with vertex normals.
    const Rgb &emission = geometry_emission_[out.hit.geom_id];
    out.emitted = (!emission.is_black() && out.wo_local.z > 0) ? emission : Rgb();
}

bool RenderScene::gathers_full_lobes(double gather_alpha) const {
    // Every material, as blends and masks reach their components at hits.
    for (const std::vector<Material> *list : {&geometry_materials_, &materials_})
        for (const Material &m : *list)
            if (m.bsdf.needs_full_eval() && m.bsdf.gathers(gather_alpha)) return true;
    return false;
}

} // namespace ppm
