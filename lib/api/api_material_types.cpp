// SPDX-License-Identifier: Apache-2.0
// ppm_scene_add_material: one function per material type, each reading its parameters with
// Mitsuba 3's names and defaults (src/bsdfs/*.cpp). A new type is a function and a row of
// kMaterialTypes.
#include <ppm/ppm.h>

#include "api/api_params.h"
#include "api/api_support.h"

#include <string>
#include <vector>

namespace {

using ppm::Bsdf;
using ppm::Material;
using ppm::Rgb;
using ppm::api::Params;

// Mitsuba's default indices of refraction: bk7 glass and air (src/bsdfs/dielectric.cpp).
constexpr double kGlassIor = 1.5046, kAirIor = 1.000277;
// Mitsuba's plastic defaults to polypropylene (src/bsdfs/plastic.cpp).
constexpr double kPolypropyleneIor = 1.49;

// A colour parameter that a texture may replace: the constant, or the texture's image set on
// the material (which then replaces the BSDF's colour at every lookup).
struct ColorOrTexture {
    Rgb value;
    const ppm::TextureRef *texture = nullptr;
};

ColorOrTexture reflectance_or_texture(ppm_scene_t &scene, Params &p, const char *name, const Rgb &fallback) {
    if (p.is_texture(name)) return {fallback, &scene.shading.texture(p.texture(name))};
    return {p.reflectance(name, fallback), nullptr};
}

uint32_t add(ppm_scene_t &scene, const Bsdf &bsdf, const ColorOrTexture &color = {}) {
    Material material{bsdf, {}};
    if (color.texture) material.texture = *color.texture;
    return scene.shading.add_material(std::move(material));
}

uint32_t add_diffuse(ppm_scene_t &scene, Params &p) {
    const ColorOrTexture c = reflectance_or_texture(scene, p, "reflectance", Rgb(0.5));
    p.finish();
    return add(scene, Bsdf::diffuse(c.value), c);
}

uint32_t add_conductor(ppm_scene_t &scene, Params &p) {
    const ColorOrTexture c = reflectance_or_texture(scene, p, "specular_reflectance", Rgb(1));
    p.choice("material", {"none"}, "none");
    p.finish();
    return add(scene, Bsdf::mirror(c.value), c);
}

uint32_t add_dielectric(ppm_scene_t &scene, Params &p) {
    const double int_ior = p.positive("int_ior", kGlassIor), ext_ior = p.positive("ext_ior", kAirIor);
    p.finish();
    return add(scene, Bsdf::dielectric(int_ior, ext_ior));
}

uint32_t add_plastic(ppm_scene_t &scene, Params &p) {
    const ColorOrTexture c = reflectance_or_texture(scene, p, "diffuse_reflectance", Rgb(0.5));
    const double int_ior = p.positive("int_ior", kPolypropyleneIor), ext_ior = p.positive("ext_ior", kAirIor);
    if (p.boolean("nonlinear", false)) p.fail("nonlinear", "true is not supported (only false)");
    p.finish();
    return add(scene, Bsdf::coated(c.value, int_ior, ext_ior), c);
}

// Mitsuba's `twosided` makes a one-sided BSDF two-sided. libppm's opaque materials already
// are, so the nested material is copied under a new id.
uint32_t add_twosided(ppm_scene_t &scene, Params &p) {
    const uint32_t inner = p.material("bsdf");
    p.finish();
    Material copy = scene.shading.material(inner);
    return scene.shading.add_material(std::move(copy));
}

// A float in [0, 1] that a texture may replace (its luminance, clamped to [0, 1] at lookups).
ppm::TextureRef unit_float_or_texture(ppm_scene_t &scene, Params &p, const char *name, double fallback, double *value) {
    if (p.is_texture(name)) {
        *value = fallback;
        return scene.shading.texture(p.texture(name));
    }
    *value = p.number_in(name, 0, 1, fallback);
    return {};
}

// Mitsuba 3 src/bsdfs/blendbsdf.cpp: (1 - weight) bsdf_0 + weight bsdf_1, weight 0.5 by
// default. The renderer picks one of the two at each hit with these probabilities.
uint32_t add_blendbsdf(ppm_scene_t &scene, Params &p) {
    double weight = 0.5;
    const ppm::TextureRef weight_texture = unit_float_or_texture(scene, p, "weight", 0.5, &weight);
    const uint32_t bsdf_0 = p.material("bsdf_0"), bsdf_1 = p.material("bsdf_1");
    scene.shading.material(bsdf_0); // both must exist (throws naming the id)
    scene.shading.material(bsdf_1);
    p.finish();
    return scene.shading.add_material(Material::blend(bsdf_0, bsdf_1, weight, weight_texture));
}

// Mitsuba 3 src/bsdfs/mask.cpp: the nested bsdf with probability `opacity` (default 0.5),
// else no surface at all (light passes straight through).
uint32_t add_mask(ppm_scene_t &scene, Params &p) {
    double opacity = 0.5;
    const ppm::TextureRef opacity_texture = unit_float_or_texture(scene, p, "opacity", 0.5, &opacity);
    const uint32_t inner = p.material("bsdf");
    scene.shading.material(inner);
    p.finish();
    return scene.shading.add_material(Material::mask(inner, opacity, opacity_texture));
}

struct MaterialType {
    const char *name;
    uint32_t (*add)(ppm_scene_t &, Params &);
};

const MaterialType kMaterialTypes[] = {
    {"diffuse", add_diffuse}, {"conductor", add_conductor}, {"dielectric", add_dielectric},
    {"plastic", add_plastic}, {"twosided", add_twosided},   {"blendbsdf", add_blendbsdf},
    {"mask", add_mask},
};

} // namespace

extern "C" ppm_status ppm_scene_add_material(ppm_scene scene, const char *type, const ppm_param *params,
                                             size_t param_count, uint32_t *out_material_id) {
    return ppm::api::scene_call(scene, [&](ppm_scene_t &s) {
        const MaterialType &t = ppm::api::find_type(kMaterialTypes, "material", type);
        Params p(std::string(t.name) + " material", params, param_count);
        ppm::api::write_id(out_material_id, t.add(s, p));
    });
}
