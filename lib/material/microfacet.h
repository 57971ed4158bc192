// SPDX-License-Identifier: Apache-2.0
// Microfacet normal distributions, the equivalent of Mitsuba 3's MicrofacetDistribution
// (include/mitsuba/render/microfacet.h): Beckmann and GGX (Trowbridge-Reitz), anisotropic
// roughness alpha_u (along the tangent x) and alpha_v (along the bitangent y), Smith's
// separable shadowing-masking G = G1(wi, m) G1(wo, m), and sampling of the visible normals.
//
// References: Walter, Marschner, Li and Torrance 2007, "Microfacet Models for Refraction
// through Rough Surfaces" (D and G1); Heitz and d'Eon 2014, "Importance Sampling
// Microfacet-Based BSDFs using the Distribution of Visible Normals" (the visible normal
// density D_wi(m) = G1(wi, m) max(0, wi.m) D(m) / cos(wi)); Heitz 2018, "Sampling the GGX
// Distribution of Visible Normals" (JCGT 7(4)) for GGX; Jakob 2014, "An Improved Visible
// Normal Sampling Routine for the Beckmann Distribution" for Beckmann (Mitsuba's
// sample_visible_11, Newton iterations in the erf domain).
//
// One difference from Mitsuba: Beckmann's G1 is the exact Smith form
//   Lambda(a) = (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)),  G1 = 1 / (1 + Lambda),
// not Mitsuba's rational fit (< 0.35 % off). The exact form is what the visible-normal
// sampler draws from, so pdf() is exactly the density of sample() and D_wi integrates to 1.
//
// All directions are in the local frame (z = macro-surface normal); m.z > 0.
#pragma once

#include "math/vec3.h"

#include <cstdint>

namespace ppm {

enum class MicrofacetType : uint8_t { Beckmann = 0, GGX = 1 };

// Mitsuba's names: "beckmann", "ggx". Returns false for anything else.
bool parse_microfacet_type(const char *name, MicrofacetType *out);
const char *microfacet_type_name(MicrofacetType type);

class MicrofacetDistribution {
public:
    MicrofacetDistribution() = default;
    // alpha_u, alpha_v are clamped below at 1e-4 as in Mitsuba (validation is the caller's).
    MicrofacetDistribution(MicrofacetType type, double alpha_u, double alpha_v, bool sample_visible = true);

    MicrofacetType type() const { return type_; }
    double alpha_u() const { return alpha_u_; }
    double alpha_v() const { return alpha_v_; }
    bool sample_visible() const { return sample_visible_; }
    bool is_isotropic() const { return alpha_u_ == alpha_v_; }

    // D(m): the density of microfacet normals per unit solid angle, normalised so that the
    // projected area is 1: integral D(m) cos(theta_m) dm = 1.
    double eval(const Vec3 &m) const;
    // Smith's shadowing-masking for one direction v and microfacet normal m, in [0, 1]; zero
    // when v sees the back of m or lies on the other side of the macro-surface.
    double smith_g1(const Vec3 &v, const Vec3 &m) const;
    double G(const Vec3 &wi, const Vec3 &wo, const Vec3 &m) const { return smith_g1(wi, m) * smith_g1(wo, m); }

    // Density (per solid angle of m) of sample(wi, .): the visible normals D_wi(m) =
    // G1(wi, m) max(0, wi.m) D(m) / cos(wi) with sample_visible, else D(m) cos(theta_m).
    // wi.z > 0.
    double pdf(const Vec3 &wi, const Vec3 &m) const;
    // Draws m from uniform (u1, u2) in [0, 1)^2; *pdf_out = pdf(wi, m). wi.z > 0.
    Vec3 sample(const Vec3 &wi, double u1, double u2, double *pdf_out) const;

private:
    Vec3 sample_all(double u1, double u2) const;
    Vec3 sample_visible_ggx(const Vec3 &wi, double u1, double u2) const;
    Vec3 sample_visible_beckmann(const Vec3 &wi, double u1, double u2) const;

    MicrofacetType type_ = MicrofacetType::Beckmann;
    double alpha_u_ = 0.1, alpha_v_ = 0.1;
    bool sample_visible_ = true;
};

// Inverse of std::erf on (-1, 1), to double precision (a Giles 2010 initial guess refined by
// Newton steps); +-infinity at +-1.
double erf_inverse(double y);

} // namespace ppm
