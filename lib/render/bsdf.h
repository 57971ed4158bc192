// SPDX-License-Identifier: Apache-2.0
// Surface scattering: Lambertian diffuse, perfect mirror, smooth dielectric (glass) and a
// smooth dielectric coat over a diffuse base (glazed porcelain, Mitsuba's `plastic`).
//
// A Bsdf is a small value type (a tag plus a few numbers, no virtual calls): the integrator
// copies one per hit. Every direction is in the local shading frame (math/frame.h: z is the
// shading normal) and points AWAY from the surface.
//
// Naming follows pbrt-v4 (src/pbrt/bxdfs.h): wo is the direction the path arrived from (the
// camera side for camera paths, the light side for photons), wi the sampled continuation.
// f(wo, wi) is the BSDF value, which for camera paths scales radiance arriving along wi.
//
// Transport mode (Veach 1997, thesis ch. 5, "The sources of non-symmetric scattering", and
// pbrt-v4 TransportMode): refraction is the one non-symmetric case here. Radiance crossing
// into a medium of relative index eta' is scaled by 1/eta'^2 (it is compressed into a
// smaller solid angle), so camera paths (TransportMode::Radiance) get 1/eta'^2 on
// transmission. Photons carry flux, i.e. they follow the adjoint BSDF
// f*(wo, wi) = f(wi, wo), and the factors cancel: TransportMode::Importance has no scaling,
// so a photon's power is only split between R and T = 1 - R. Mitsuba 3's dielectric.cpp does
// the same (`factor = mode == Radiance ? eta_ti : 1`). The diffuse, mirror and coated models
// are symmetric, so eval() and pdf() take no mode.
//
// Sides: the opaque materials (diffuse, mirror, coated) are two-sided, like Mitsuba's
// `twosided` adapter: the model is evaluated on the side of wo (the shading normal is
// flipped to wo's side), and wi on the other side gets nothing. Glass uses the sign of
// cos(wo) = wo.z: wo.z > 0 is outside (ext_ior), wo.z < 0 inside (int_ior), so a glass
// surface's normal must point outwards. wo.z == 0 scatters nothing.
#pragma once

#include "math/rgb.h"
#include "math/vec3.h"

#include <cstdint>

namespace ppm {

enum class TransportMode : uint8_t {
    Radiance,   // camera paths: wo towards the camera
    Importance, // photon paths: wo towards the light (adjoint BSDF)
};

struct BsdfSample {
    Vec3 wi;        // sampled direction, local frame, unit length
    Rgb weight;     // f(wo, wi) |cos wi| / pdf: the factor for the path throughput
    double pdf = 0; // solid angle density, or the lobe's discrete probability if specular
    bool is_specular = false;
    bool valid() const { return pdf > 0; }
};

// Power reflectances of a smooth dielectric boundary for s- (perpendicular) and
// p- (parallel) polarised light; unpolarised light sees their mean.
struct FresnelTerms {
    double r_s = 1, r_p = 1;
    double cos_t = 0; // |cos| of the transmitted direction; 0 on total internal reflection
    double reflectance() const { return 0.5 * (r_s + r_p); }
};

// Exact Fresnel equations (pbrt-v4 FrDielectric) for cos_i = cos(angle to the normal) and
// eta = n_inside / n_outside; cos_i < 0 means incidence from inside (eta is inverted).
// Beyond the critical angle r_s = r_p = 1 (total internal reflection).
FresnelTerms fresnel_dielectric_terms(double cos_i, double eta);
inline double fresnel_dielectric(double cos_i, double eta) {
    return fresnel_dielectric_terms(cos_i, eta).reflectance();
}

// Hemispherical average 2 * integral_0^1 F(mu, eta) mu dmu of the Fresnel reflectance for
// light arriving from outside (eta = n_inside / n_outside), by quadrature.
double fresnel_diffuse_reflectance(double eta);

// eval() at one wo for many wi (the photons landing at a visible point), with what depends
// on wo alone computed once: eval(wo, wi) = at(wi.z) * sign-matched, see Bsdf::fixed_wo.
class FixedWoLobe {
public:
    // f(wo, wi) times `weight` (given to Bsdf::fixed_wo) for cos_wi = wi.z taken on wo's side
    // of the shading normal (wi.z * sign(wo.z)); zero when wi is on the other side.
    Rgb at(double cos_wi) const {
        if (!(cos_wi > 0)) return Rgb();
        return coat_ ? factor_ * (1.0 - fresnel_dielectric(cos_wi, eta_)) : factor_;
    }

private:
    friend class Bsdf;
    Rgb factor_; // weight f without the coat's (1 - F(cos wi)) factor
    double eta_ = 1;
    bool coat_ = false;
};

class Bsdf {
public:
    enum class Type : uint8_t { Diffuse, Mirror, Dielectric, Coated, Null };

    // Black diffuse: scatters nothing (a placeholder that needs no validation).
    Bsdf() = default;

    // Factories validate their arguments and throw ppm::Error (invalid argument):
    // reflectances must be finite and in [0, 1] per channel (energy conservation), indices
    // of refraction finite and > 0.
    static Bsdf diffuse(const Rgb &reflectance);
    static Bsdf mirror(const Rgb &specular_reflectance);
    static Bsdf dielectric(double int_ior, double ext_ior);
    // Mitsuba 3 `plastic` with nonlinear = false (src/bsdfs/plastic.cpp): specular reflection
    // F(cos wo) off the coat plus the diffuse lobe
    //   f_d(wo, wi) = R_d / (1 - Fdr) * (1 - F(cos wo)) (1 - F(cos wi)) / pi,
    // Fdr = fresnel_diffuse_reflectance(eta). The 1/(1 - Fdr) normalisation (Mitsuba writes
    // it as 1 / (eta^2 (1 - Fdr_int)), the same number since 1 - Fdr_int = (1 - Fdr)/eta^2)
    // makes the diffuse albedo exactly (1 - F(cos wo)) R_d: the light that gets through the
    // coat leaves with the base colour, the internal bounces are folded into R_d. So
    // albedo(wo) = F + (1 - F) R_d <= 1 and f is symmetric. Mitsuba approximates Fdr by a
    // fitted polynomial; we integrate it (f differs from Mitsuba 3.9.1 by 0.12 % at eta 1.5).
    static Bsdf coated(const Rgb &diffuse_reflectance, double int_ior, double ext_ior);
    // No surface: a specular lobe that passes light straight through (wi = -wo, weight 1),
    // the pass-through part of Mitsuba 3's `mask` (src/bsdfs/mask.cpp).
    static Bsdf null();

    // The same material with another base/specular colour (e.g. from a texture), without
    // revalidating or recomputing the coat's Fdr. Components must lie in [0, 1].
    Bsdf with_reflectance(const Rgb &reflectance) const;

    Type type() const { return type_; }
    // Whether eval()/pdf() can be non-zero (where photons can be gathered).
    bool has_non_specular() const { return type_ == Type::Diffuse || type_ == Type::Coated; }
    const Rgb &reflectance() const { return reflectance_; }
    double eta() const { return eta_; } // int_ior / ext_ior

    // Probability that sample() picks a specular lobe for this wo: 1 for mirror and glass,
    // 0 for diffuse, the coat's Fresnel-steered share for coated.
    double specular_probability(const Vec3 &wo) const;

    // Samples wi given wo, from uniform numbers in [0, 1): u_lobe picks the lobe, (u1, u2) the
    // direction. Returns pdf == 0 (invalid) when nothing scatters.
    BsdfSample sample(const Vec3 &wo, double u_lobe, double u1, double u2, TransportMode mode) const;
    // f(wo, wi) of the non-specular part (without the cosine), and the density with which
    // sample() produces wi through that part (including the lobe selection probability).
    Rgb eval(const Vec3 &wo, const Vec3 &wi) const;
    // weight * eval(wo, .) with wo fixed; black where eval is (specular types, wo.z == 0).
    FixedWoLobe fixed_wo(const Vec3 &wo, const Rgb &weight) const;
    double pdf(const Vec3 &wo, const Vec3 &wi) const;

private:
    double coat_specular_probability(double fresnel_o) const;

    Type type_ = Type::Diffuse;
    Rgb reflectance_;
    double eta_ = 1;
    double coat_diffuse_scale_ = 1;       // 1 / (1 - Fdr)
    double specular_sampling_weight_ = 1; // Mitsuba's s_mean / (s_mean + d_mean)
};

} // namespace ppm
