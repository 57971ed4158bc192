// SPDX-License-Identifier: Apache-2.0
// ppm_scene_add_material: one function per material type, each reading its parameters with
// Mitsuba 3's names and defaults (src/bsdfs/*.cpp). A new type is a function and a row of
// kMaterialTypes.
#include <ppm/ppm.h>

#include "api/api_params.h"
#include "api/api_support.h"
#include "api/api_type_tables.h"
#include "core/suggest.h"
#include "material/conductor_table.h"

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

// The complex index of refraction of a conductor, as Mitsuba's conductor.cpp reads it: a
// named `material` (Mitsuba's table, material/conductor_table.h) or `eta` and `k`; "none" (the
// default) is eta 0, k 1: F = 1, a perfect mirror. Giving both is an error, as in Mitsuba.
struct ConductorIndex {
    Rgb eta, k;
    bool perfect = false; // material "none" without eta/k: the exact mirror
};

ConductorIndex conductor_index(Params &p) {
    const std::string material = p.string("material", "none");
    if (material != "none") {
        if (p.has("eta") || p.has("k")) p.fail("material", "and eta/k cannot both be given (give one or the other)");
        p.color("eta", Rgb(0)), p.color("k", Rgb(1)); // read, so that finish() knows them
        const ppm::ConductorIor *c = ppm::find_conductor(material.c_str());
        if (!c)
            p.fail("material", "'" + material + "' is not a known conductor" +
                                   ppm::did_you_mean(material, ppm::conductor_names()) +
                                   " (Mitsuba 3's names, e.g. Ag, Al, Au, Cr, Cu, or \"none\")");
        return {c->eta, c->k, false};
    }
    const bool given = p.has("eta") || p.has("k");
    const Rgb eta = p.color("eta", Rgb(0)), k = p.color("k", Rgb(1));
    return {eta, k, !given};
}

uint32_t add_conductor(ppm_scene_t &scene, Params &p) {
    const ColorOrTexture c = reflectance_or_texture(scene, p, "specular_reflectance", Rgb(1));
    const ConductorIndex ior = conductor_index(p);
    p.finish();
    return add(scene, ior.perfect ? Bsdf::mirror(c.value) : Bsdf::conductor(ior.eta, ior.k, c.value), c);
}

// Mitsuba's roughconductor (src/bsdfs/roughconductor.cpp and MicrofacetDistribution's
// constructor): distribution "beckmann" (default) or "ggx", `alpha` (0.1) or both `alpha_u`
// and `alpha_v`, `sample_visible` (true).
uint32_t add_roughconductor(ppm_scene_t &scene, Params &p) {
    const ColorOrTexture c = reflectance_or_texture(scene, p, "specular_reflectance", Rgb(1));
    const ConductorIndex ior = conductor_index(p);
    const std::string distribution = p.choice("distribution", {"beckmann", "ggx"}, "beckmann");
    double alpha_u = 0.1, alpha_v = 0.1;
    if (p.has("alpha_u") || p.has("alpha_v")) {
        if (p.has("alpha")) p.fail("alpha", "and alpha_u/alpha_v cannot both be given");
        if (!p.has("alpha_u") || !p.has("alpha_v"))
            p.fail(p.has("alpha_u") ? "alpha_v" : "alpha_u", "is needed too: give both alpha_u and alpha_v");
        alpha_u = p.positive("alpha_u", 0.1);
        alpha_v = p.positive("alpha_v", 0.1);
        p.number("alpha", 0.1);
    } else {
        alpha_u = alpha_v = p.positive("alpha", 0.1);
        p.number("alpha_u", 0.1), p.number("alpha_v", 0.1);
    }
    const bool sample_visible = p.boolean("sample_visible", true);
    p.finish();
    ppm::MicrofacetType type = ppm::MicrofacetType::Beckmann;
    ppm::parse_microfacet_type(distribution.c_str(), &type);
    return add(scene, Bsdf::rough_conductor(type, alpha_u, alpha_v, ior.eta, ior.k, c.value, sample_visible), c);
}

uint32_t add_dielectric(ppm_scene_t &scene, Params &p) {
    const double int_ior = p.positive("int_ior", kGlassIor), ext_ior = p.positive("ext_ior", kAirIor);
    p.finish();
    return add(scene, Bsdf::dielectric(int_ior, ext_ior));
}

uint32_t add_plastic(ppm_scene_t &scene, Params &p) {
    const ColorOrTexture c = reflectance_or_texture(scene, p, "diffuse_reflectance", Rgb(0.5));
    const double int_ior = p.positive("int_ior", kPolypropyleneIor), ext_ior = p.positive("ext_ior", kAirIor);
    const bool nonlinear = p.boolean("nonlinear", false);
    const Rgb specular = p.reflectance("specular_reflectance", Rgb(1.0));
    p.finish();
    return add(scene, Bsdf::coated(c.value, int_ior, ext_ior, nonlinear, specular), c);
}

uint32_t add_thindielectric(ppm_scene_t &scene, Params &p) {
    const double int_ior = p.positive("int_ior", kGlassIor), ext_ior = p.positive("ext_ior", kAirIor);
    p.finish();
    return add(scene, Bsdf::thin_dielectric(int_ior, ext_ior));
}

// Mitsuba's MicrofacetDistribution(props): `distribution`, then `alpha` for both directions or
// `alpha_u` and `alpha_v` (not both forms), and `sample_visible`.
struct Roughness {
    ppm::MicrofacetType type = ppm::MicrofacetType::Beckmann;
    double alpha_u = 0.1, alpha_v = 0.1;
    bool sample_visible = true;
};

Roughness read_roughness(Params &p, bool anisotropic) {
    Roughness r;
    const std::string name = p.choice("distribution", {"beckmann", "ggx"}, "beckmann");
    ppm::parse_microfacet_type(name.c_str(), &r.type);
    if (anisotropic && (p.has("alpha_u") || p.has("alpha_v"))) {
        if (p.has("alpha")) p.fail("alpha", "give either alpha or alpha_u and alpha_v, not both");
        if (!p.has("alpha_u") || !p.has("alpha_v"))
            p.fail(p.has("alpha_u") ? "alpha_v" : "alpha_u", "is needed with the other of alpha_u and alpha_v");
        r.alpha_u = p.positive("alpha_u", 0.1);
        r.alpha_v = p.positive("alpha_v", 0.1);
    } else {
        r.alpha_u = r.alpha_v = p.positive("alpha", 0.1);
    }
    r.sample_visible = p.boolean("sample_visible", true);
    return r;
}

uint32_t add_roughdielectric(ppm_scene_t &scene, Params &p) {
    const Roughness r = read_roughness(p, true);
    const double int_ior = p.positive("int_ior", kGlassIor), ext_ior = p.positive("ext_ior", kAirIor);
    p.finish();
    return add(scene, Bsdf::rough_dielectric(r.type, r.alpha_u, r.alpha_v, int_ior, ext_ior, r.sample_visible));
}

// Mitsuba's roughplastic is isotropic (it refuses alpha_u != alpha_v): only `alpha`.
uint32_t add_roughplastic(ppm_scene_t &scene, Params &p) {
    const ColorOrTexture c = reflectance_or_texture(scene, p, "diffuse_reflectance", Rgb(0.5));
    const Roughness r = read_roughness(p, false);
    const double int_ior = p.positive("int_ior", kPolypropyleneIor), ext_ior = p.positive("ext_ior", kAirIor);
    const bool nonlinear = p.boolean("nonlinear", false);
    const Rgb specular = p.reflectance("specular_reflectance", Rgb(1.0));
    p.finish();
    return add(scene,
               Bsdf::rough_plastic(c.value, r.type, r.alpha_u, int_ior, ext_ior, r.sample_visible, nonlinear, specular),
               c);
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
    if (p.has(name)) {
        const std::vector<double> numbers = p.number_list(name);
        if (numbers.size() == 3) {
            // A colour, as Mitsuba's RGB variants read one where a float is wanted (its srgb
            // texture's eval_1 is the channels' mean, which mask and blendbsdf clip to [0, 1]).
            *value = std::clamp((numbers[0] + numbers[1] + numbers[2]) / 3.0, 0.0, 1.0);
            return {};
        }
        if (numbers.size() != 1)
            p.fail(name, "must be a number or 3 numbers (r, g, b), not " + std::to_string(numbers.size()) + " numbers");
        if (!(numbers[0] >= 0 && numbers[0] <= 1))
            p.fail(name, "must lie in [0, 1], not " + ppm::format_number(numbers[0]));
        *value = numbers[0];
        return {};
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

// Mitsuba 3 src/bsdfs/null.cpp: no surface at all; light passes straight through (the
// boundary of an index-matched medium, or a shape that only holds an emitter).
uint32_t add_null(ppm_scene_t &scene, Params &p) {
    p.finish();
    return add(scene, Bsdf::null());
}

struct MaterialType {
    const char *name;
    uint32_t (*add)(ppm_scene_t &, Params &);
};

const MaterialType kMaterialTypes[] = {
    {"diffuse", add_diffuse},
    {"conductor", add_conductor},
    {"roughconductor", add_roughconductor},
    {"dielectric", add_dielectric},
    {"plastic", add_plastic},
    {"twosided", add_twosided},
    {"thindielectric", add_thindielectric},
    {"roughdielectric", add_roughdielectric},
    {"roughplastic", add_roughplastic},
    {"blendbsdf", add_blendbsdf},
    {"mask", add_mask},
    {"null", add_null},
};

} // namespace

namespace ppm::api {

std::vector<const char *> material_type_names() { return type_names(kMaterialTypes); }

} // namespace ppm::api

extern "C" ppm_status ppm_scene_add_material(ppm_scene scene, const char *type, const ppm_param *params,
                                             size_t param_count, uint32_t *out_material_id) {
    return ppm::api::scene_call(scene, [&](ppm_scene_t &s) {
        const MaterialType &t = ppm::api::find_type(kMaterialTypes, "material", type);
        Params p(std::string(t.name) + " material", params, param_count);
        ppm::api::write_id(out_material_id, t.add(s, p));
    });
}
