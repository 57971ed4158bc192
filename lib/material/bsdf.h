// SPDX-License-Identifier: Apache-2.0
// Surface scattering: Lambertian diffuse, perfect mirror, smooth dielectric (glass), a
// smooth dielectric coat over a diffuse base (glazed porcelain, Mitsuba's `plastic`),
// smooth and rough conductors (metals with a complex index of refraction, Mitsuba's
// `conductor` and `roughconductor`; the rough one's math in bsdf_conductor.cpp), and the
// rest of Mitsuba's dielectric family (bsdf_dielectric.cpp): a thin sheet of glass
// (`thindielectric`), a rough interface (`roughdielectric`) and a rough coat over a diffuse
// base (`roughplastic`), the rough ones on a microfacet distribution (material/microfacet.h).
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
// the same (`factor = mode == Radiance ? eta_ti : 1`), and so does the rough interface
// (roughdielectric.cpp, eval() and sample()): its transmission lobe has the 1/eta'^2 in
// Radiance mode only, so that f_Importance(wo, wi) = f_Radiance(wi, wo). The other models are
// symmetric; eval() without a mode is the Radiance one (what camera paths need), pdf() does not
// depend on the mode.
//
// Sides: the opaque materials (diffuse, mirror, coated) are two-sided, like Mitsuba's
// `twosided` adapter: the model is evaluated on the side of wo (the shading normal is
// flipped to wo's side), and wi on the other side gets nothing. The conductors are two-sided
// the same way (Mitsuba's are one-sided; wrap them in `twosided` there to compare). Glass uses the sign of
// cos(wo) = wo.z: wo.z > 0 is outside (ext_ior), wo.z < 0 inside (int_ior), so a glass
// surface's normal must point outwards; the rough interface likewise. The thin sheet is
// symmetric (both faces alike). Rough plastic is two-sided like the coated model (Mitsuba's is
// one-sided: compare it inside `twosided`). wo.z == 0 scatters nothing.
#pragma once

#include "material/microfacet.h"
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
// on wo alone computed once. The diffuse and coated lobes depend on cos(wi) only and are
// evaluated by at(); lobes that depend on the whole of wi (rough conductors) are marked
// needs_full_eval() and the caller evaluates weight * Bsdf::eval(wo, wi) itself (the density
// estimator keeps the Bsdf, frame and wo of such points aside).
class FixedWoLobe {
public:
    // f(wo, wi) times `weight` (given to Bsdf::fixed_wo) for cos_wi = wi.z taken on wo's side
    // of the shading normal (wi.z * sign(wo.z)); zero when wi is on the other side. Not for
    // needs_full_eval() lobes.
    Rgb at(double cos_wi) const {
        if (!(cos_wi > 0)) return Rgb();
        return coat_ ? factor_ * (1.0 - fresnel_dielectric(cos_wi, eta_)) : factor_;
    }
    // Lobes that depend on the whole of wi (rough conductor, rough plastic): the caller
    // evaluates weight * Bsdf::eval(wo, wi) itself; at() is not for them.
    bool needs_full_eval() const { return full_; }
    // The weight given to Bsdf::fixed_wo, for needs_full_eval() lobes.
    const Rgb &weight() const { return factor_; }

private:
    friend class Bsdf;
    Rgb factor_; // weight f without the coat's (1 - F(cos wi)) factor
    double eta_ = 1;
    bool coat_ = false;
    bool full_ = false;
};

struct RoughCoatTable; // bsdf_dielectric.cpp

class Bsdf {
public:
    enum class Type : uint8_t {
        Diffuse,
        Mirror,
        Dielectric,
        Coated,
        Conductor,
        RoughConductor,
        ThinDielectric,
        RoughDielectric,
        RoughPlastic,
        Null,
    };

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
    //
    // nonlinear = true (Mitsuba's `nonlinear`): the internal bounces darken and saturate the
    // base as a real coated surface does, R_d / (1 - R_d Fdr_int) in place of
    // R_d / (1 - Fdr_int), Fdr_int = 1 - (1 - Fdr) / eta^2 the coat's internal diffuse
    // reflectance; per channel and per texel.
    static Bsdf coated(const Rgb &diffuse_reflectance, double int_ior, double ext_ior, bool nonlinear = false,
                       const Rgb &specular_reflectance = Rgb(1.0));
    // Mitsuba 3 `conductor` (src/bsdfs/conductor.cpp): a smooth metal reflecting
    // specular_reflectance * F(cos wo) with F the unpolarised Fresnel reflectance of the
    // complex index eta + i k (material/fresnel.h). eta, k finite and >= 0 per channel. (With
    // Mitsuba's default material "none", eta 0 and k 1, F = 1: use mirror().)
    static Bsdf conductor(const Rgb &eta, const Rgb &k, const Rgb &specular_reflectance);
    // Mitsuba 3 `roughconductor` (src/bsdfs/roughconductor.cpp): the Torrance-Sparrow
    // microfacet model f = R F(wo.h) D(h) G(wo, wi, h) / (4 cos wo cos wi), h the half
    // vector, sampled through the distribution of visible normals (or all normals with
    // sample_visible = false). alpha_u, alpha_v finite and > 0.
    static Bsdf rough_conductor(MicrofacetType distribution, double alpha_u, double alpha_v, const Rgb &eta,
                                const Rgb &k, const Rgb &specular_reflectance, bool sample_visible = true);
    // Mitsuba 3 `thindielectric`: a thin sheet of glass (a window pane) reflecting
    // R' = R + T^2 R / (1 - R^2) = 2R / (1 + R) (R = F(|cos wo|), T = 1 - R: the sum over the
    // internal bounces) and letting 1 - R' straight through (wi = -wo). Both lobes specular, the
    // same in both transport modes. int_ior != ext_ior (Mitsuba: 1.5046 and 1.000277).
    static Bsdf thin_dielectric(double int_ior, double ext_ior);
    // Mitsuba 3 `roughdielectric` (Walter et al. 2007): reflection F D G / (4 |cos wo cos wi|)
    // and refraction (1 - F) D G eta'^2 |wo.m wi.m| / (|cos wo cos wi| (wo.m + eta' wi.m)^2)
    // about the generalised half vector m ~ wo + eta' wi (eta' = n(wi side) / n(wo side)),
    // times 1/eta'^2 in Radiance mode. Sampled through the visible normals (or, with
    // sample_visible false, all normals of a distribution widened at grazing angles, as
    // Mitsuba). alpha_u, alpha_v finite and > 0 (Mitsuba default 0.1, beckmann).
    static Bsdf rough_dielectric(MicrofacetType distribution, double alpha_u, double alpha_v, double int_ior,
                                 double ext_ior, bool sample_visible = true);
    // Mitsuba 3 `roughplastic` with nonlinear = false: the rough coat's reflection
    // F D G / (4 cos wo cos wi) plus the base R_d / (eta^2 (1 - R_int)) T(cos wo) T(cos wi) / pi,
    // T the coat's transmittance and R_int its internal diffuse reflectance, tabulated at
    // creation as Mitsuba does (its Gauss-Legendre quadrature and its 64-point table, so f
    // matches Mitsuba's). Isotropic; Mitsuba defaults beckmann, alpha 0.1, int_ior 1.49
    // (polypropylene), ext_ior 1.000277, diffuse_reflectance 0.5.
    // nonlinear = true: R_d / (1 - R_d R_int) in place of R_d / (1 - R_int), as coated().
    static Bsdf rough_plastic(const Rgb &diffuse_reflectance, MicrofacetType distribution, double alpha, double int_ior,
                              double ext_ior, bool sample_visible = true, bool nonlinear = false,
                              const Rgb &specular_reflectance = Rgb(1.0));
    // No surface: a specular lobe that passes light straight through (wi = -wo, weight 1),
    // the pass-through part of Mitsuba 3's `mask` (src/bsdfs/mask.cpp).
    static Bsdf null();

    // The same material with another base/specular colour (e.g. from a texture), without
    // revalidating or recomputing the coat's Fdr. Components must lie in [0, 1]. For a
    // nonlinear coat the stored reflectance (reflectance()) is the base colour with the
    // internal bounces applied, which the linear formulas then use as they are.
    Bsdf with_reflectance(const Rgb &reflectance) const;

    Type type() const { return type_; }
    // Whether eval()/pdf() can be non-zero and visible points may be stored. Not the rough
    // interface, although its eval() is: it is always continued by sampling, never gathered
    // (photons refracted through it arrive from behind the visible point's surface, which the
    // density estimate rejects, and its lobes are as narrow as its roughness), in both modes.
    bool has_non_specular() const {
        return type_ == Type::Diffuse || type_ == Type::Coated || type_ == Type::RoughConductor ||
               type_ == Type::RoughPlastic;
    }
    const Rgb &reflectance() const { return reflectance_; }
    double eta() const { return eta_; } // int_ior / ext_ior
    const Rgb &conductor_eta() const { return conductor_eta_; }
    const Rgb &conductor_k() const { return conductor_k_; }
    const MicrofacetDistribution &distribution() const { return distribution_; }
    // Rough plastic's coat: its tabulated transmittance for light from outside at cos_theta,
    // and its internal diffuse reflectance (1 and 0 for other types).
    double rough_coat_transmittance(double cos_theta) const;
    double rough_coat_internal_reflectance() const;
    // The thin sheet's total reflectance 2R / (1 + R) at cos(wo).
    double thin_dielectric_reflectance(double cos_wo) const;

    // Probability that sample() picks a specular lobe for this wo: 1 for mirror, glass and
    // the smooth conductor, 0 for diffuse and the rough conductor, the coat's Fresnel-steered
    // share for coated.
    double specular_probability(const Vec3 &wo) const;

    // Visible points (density estimation) versus continued paths. A camera path that meets
    // this BSDF either stops and stores a visible point, where photons are gathered with
    // eval() (fixed_wo()), or continues by sampling, like at a mirror. The rule, per lobe:
    // specular lobes continue; diffuse lobes are gathered; a microfacet lobe of roughness
    // min(alpha_u, alpha_v) >= gather_alpha (the render setting glossy_gather_alpha) is
    // gathered, a smoother one continues. Why: the photon estimate at a visible point
    // averages photons over a disc of radius r, which blurs the reflected image by about
    // r / distance and adds variance inversely proportional to the lobe's solid angle; both
    // vanish as r -> 0 (the estimate is consistent) but for a narrow lobe they dominate,
    // while continuing the path costs one more segment and is unbiased. Emission found after
    // a continued bounce is counted as after a specular one (no light sampling there).
    //
    // Whether visible points (and photons) can be stored at this material at all.
    bool gathers(double gather_alpha) const;
    // Whether a visible point here evaluates the whole BSDF per photon (its fixed_wo() lobe
    // needs_full_eval): a rough lobe depends on all of wi, not on cos(wi) alone.
    bool needs_full_eval() const { return type_ == Type::RoughConductor || type_ == Type::RoughPlastic; }
    // The probability of stopping at a visible point for this wo, and its complement, the
    // probability of continuing: the integrator stops when u_lobe >= continue_probability
    // and otherwise calls sample() with the same u_lobe, which then picks a continued lobe
    // (the coat's reflection, or the one rough lobe of a narrow conductor). The visible
    // point's weight is divided by gather_probability; sample()'s weight already accounts for
    // its lobe choice.
    double gather_probability(const Vec3 &wo, double gather_alpha) const {
        return 1.0 - continue_probability(wo, gather_alpha);
    }
    double continue_probability(const Vec3 &wo, double gather_alpha) const;

    // Samples wi given wo, from uniform numbers in [0, 1): u_lobe picks the lobe, (u1, u2) the
    // direction. Returns pdf == 0 (invalid) when nothing scatters.
    BsdfSample sample(const Vec3 &wo, double u_lobe, double u1, double u2, TransportMode mode) const;
    // f(wo, wi) of the non-specular part (without the cosine), and the density with which
    // sample() produces wi through that part (including the lobe selection probability).
    Rgb eval(const Vec3 &wo, const Vec3 &wi) const { return eval(wo, wi, TransportMode::Radiance); }
    Rgb eval(const Vec3 &wo, const Vec3 &wi, TransportMode mode) const;
    // weight * eval(wo, .) with wo fixed; black where eval is (specular types, wo.z == 0).
    FixedWoLobe fixed_wo(const Vec3 &wo, const Rgb &weight) const;
    double pdf(const Vec3 &wo, const Vec3 &wi) const;

private:
    double coat_specular_probability(double fresnel_o) const;
    // The conductors' parts (bsdf_conductor.cpp); w on the side of the shading normal.
    BsdfSample sample_rough_conductor(const Vec3 &w, double u1, double u2) const;
    Rgb eval_rough_conductor(const Vec3 &w, const Vec3 &wi) const;
    double pdf_rough_conductor(const Vec3 &w, const Vec3 &wi) const;
    // The dielectric family's parts (bsdf_dielectric.cpp). The rough plastic's take w on the
    // side of the shading normal.
    BsdfSample sample_thin_dielectric(const Vec3 &wo, double u_lobe) const;
    MicrofacetDistribution rough_sampling_distribution(double cos_wo) const;
    BsdfSample sample_rough_dielectric(const Vec3 &wo, double u_lobe, double u1, double u2, TransportMode mode) const;
    Rgb eval_rough_dielectric(const Vec3 &wo, const Vec3 &wi, TransportMode mode) const;
    double pdf_rough_dielectric(const Vec3 &wo, const Vec3 &wi) const;
    double rough_plastic_coat_probability(double cos_o) const;
    BsdfSample sample_rough_plastic(const Vec3 &w, double u_lobe, double u1, double u2) const;
    Rgb eval_rough_plastic(const Vec3 &w, const Vec3 &wi) const;
    double pdf_rough_plastic(const Vec3 &w, const Vec3 &wi) const;

    Type type_ = Type::Diffuse;
    Rgb reflectance_;
    double eta_ = 1;
    double coat_diffuse_scale_ = 1;              // 1 / (1 - Fdr); rough plastic 1 / (eta^2 (1 - R_int))
    double specular_sampling_weight_ = 1;        // Mitsuba's s_mean / (s_mean + d_mean)
    double nonlinear_internal_reflectance_ = -1; // a nonlinear coat's Fdr_int or R_int; < 0: linear
    Rgb conductor_eta_, conductor_k_;            // complex index of refraction (conductors)
    Rgb coat_specular_ = Rgb(1.0);               // the coats' specular_reflectance (plastic, rough plastic)
    MicrofacetDistribution distribution_;        // rough conductor, rough dielectric, rough plastic
    const RoughCoatTable *coat_table_ = nullptr; // rough plastic (interned, immortal)
};

} // namespace ppm
