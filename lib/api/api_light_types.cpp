// SPDX-License-Identifier: Apache-2.0
// ppm_scene_add_light: one function per light type that is not a shape, each reading its
// parameters with Mitsuba 3's names and defaults (src/emitters/*.cpp). A new type is a
// function and a row of kLightTypes.
#include <ppm/ppm.h>

#include "api/api_params.h"
#include "api/api_support.h"
#include "api/api_type_tables.h"
#include "material/texture.h"

#include <string>

namespace {

using ppm::Rgb;
using ppm::Vec3;
using ppm::api::Params;

// An intensity, radiance or irradiance: a colour no larger than the emission limit.
Rgb emission(Params &p, const char *name, const Rgb &fallback) {
    const Rgb c = p.color(name, fallback);
    if (c.max() > ppm::kEmissionLimit)
        p.fail(name, "exceeds the limit " + ppm::format_number(ppm::kEmissionLimit) + " of light values");
    return c;
}

Vec3 scene_point(Params &p, const char *name, const Vec3 &v) {
    if (!ppm::within_coordinate_limit(v))
        p.fail(name, "has a coordinate beyond +-" + ppm::format_number(ppm::kCoordinateLimit) +
                         " (the limit of scene coordinates)");
    return v;
}

// Placed by `position` or, as Mitsuba also allows, by where `to_world` takes the origin.
uint32_t add_point(ppm_scene_t &scene, Params &p) {
    if (p.has("position") && p.has("to_world")) p.fail("position", "and 'to_world' cannot both be given");
    const Vec3 position =
        p.has("to_world") ? p.transform("to_world", {}).point({0, 0, 0}) : p.vec3("position", {0, 0, 0});
    const Rgb intensity = emission(p, "intensity", Rgb(1));
    p.finish();
    return scene.shading.add_light(ppm::Light::point(scene_point(p, "position", position), intensity));
}

// Mitsuba's spot shines along +z of `to_world`.
uint32_t add_spot(ppm_scene_t &scene, Params &p) {
    const ppm::Affine to_world = p.transform("to_world", {});
    const Rgb intensity = emission(p, "intensity", Rgb(1));
    const double cutoff = p.number_in("cutoff_angle", 0, 180, 20);
    const double beam = p.number_in("beam_width", 0, cutoff, cutoff * 0.75);
    p.finish();
    const Vec3 position = scene_point(p, "to_world", to_world.point({0, 0, 0}));
    const Vec3 target = scene_point(p, "to_world", to_world.point({0, 0, 1}));
    return scene.shading.add_light(ppm::Light::spot(position, target, intensity, cutoff, beam));
}

// Mitsuba's `constant` (src/emitters/constant.cpp): uniform `radiance`, default 1.
uint32_t add_constant(ppm_scene_t &scene, Params &p) {
    const Rgb radiance = emission(p, "radiance", Rgb(1));
    p.finish();
    return scene.shading.add_light(ppm::Light::constant(radiance));
}

// Mitsuba's `envmap` (src/emitters/envmap.cpp): a lat-long image file times `scale`, turned by
// the linear part of `to_world`. The file's pixels are checked as it loads (NaN, infinite or
// negative values and absurd sizes refused, naming the file).
uint32_t add_envmap(ppm_scene_t &scene, Params &p) {
    const std::string filename = p.string("filename", "");
    if (filename.empty()) p.fail("filename", "is required (a latitude-longitude image)");
    const double scale = p.positive("scale", 1.0);
    const ppm::Affine to_world = p.transform("to_world", {});
    p.finish();
    const Vec3 columns[3] = {to_world.vector({1, 0, 0}), to_world.vector({0, 1, 0}), to_world.vector({0, 0, 1})};
    return scene.shading.add_light(ppm::Light::envmap(ppm::Texture::load(filename), scale, columns));
}

// Mitsuba's `directional` (src/emitters/directional.cpp): light travelling along `direction`,
// or along +z of `to_world` (not both); `irradiance` on a surface facing it, default 1.
uint32_t add_directional(ppm_scene_t &scene, Params &p) {
    if (p.has("direction") && p.has("to_world")) p.fail("direction", "and 'to_world' cannot both be given");
    const Vec3 direction =
        p.has("to_world") ? p.transform("to_world", {}).vector({0, 0, 1}) : p.vec3("direction", {0, 0, 1});
    if (!(ppm::length2(direction) > 0)) p.fail(p.has("to_world") ? "to_world" : "direction", "must not be zero");
    const Rgb irradiance = emission(p, "irradiance", Rgb(1));
    p.finish();
    return scene.shading.add_light(ppm::Light::directional(direction, irradiance));
}

struct LightType {
    const char *name;
    uint32_t (*add)(ppm_scene_t &, Params &);
};

const LightType kLightTypes[] = {
    {"point", add_point},
    {"spot", add_spot},
    {"constant", add_constant},
    {"envmap", add_envmap},
    {"directional", add_directional},
};

} // namespace

namespace ppm::api {

std::vector<const char *> light_type_names() { return type_names(kLightTypes); }

} // namespace ppm::api

extern "C" ppm_status ppm_scene_add_light(ppm_scene scene, const char *type, const ppm_param *params,
                                          size_t param_count, uint32_t *out_light_id) {
    return ppm::api::scene_call(scene, [&](ppm_scene_t &s) {
        const LightType &t = ppm::api::find_type(kLightTypes, "light", type);
        Params p(std::string(t.name) + " light", params, param_count);
        ppm::api::write_id(out_light_id, t.add(s, p));
    });
}
