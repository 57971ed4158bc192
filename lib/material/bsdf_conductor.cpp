// SPDX-License-Identifier: Apache-2.0
// Conductors: Mitsuba 3's `conductor` and `roughconductor` (src/bsdfs/conductor.cpp,
// src/bsdfs/roughconductor.cpp). The rough model is Torrance-Sparrow with Walter et al.'s
// normalisation,
//   f(wo, wi) = R F(wo.h) D(h) G(wo, wi, h) / (4 cos wo cos wi),  h = (wo + wi) / |wo + wi|,
// sampled by drawing h from the visible normals D_wo(h) = G1(wo, h) (wo.h) D(h) / cos wo and
// reflecting wo about it; the Jacobian of the reflection is 1 / (4 wo.h), so
//   pdf(wi) = G1(wo, h) D(h) / (4 cos wo),   weight = f cos wi / pdf = R F G1(wi, h).
// Without visible sampling h follows D(h) cos(h), pdf = D(h) cos(h) / (4 wo.h) and the weight
// is R F G (wo.h) / (cos wo cos h). f is symmetric in wo and wi, and independent of mode.
#include "material/bsdf.h"

#include "core/error.h"
#include "material/bsdf_helpers.h"
#include "material/fresnel.h"

#include <cmath>
#include <string>

namespace ppm {

namespace {

using bsdf_helpers::require_alpha;
using bsdf_helpers::require_reflectance;

void require_index(const Rgb &c, const char *what) {
    if (!(c.is_finite() && c.min() >= 0))
        invalid_argument(std::string(what) + " must be finite and >= 0 per channel, got (" + format_number(c.r) + ", " +
                         format_number(c.g) + ", " + format_number(c.b) + ")");
}

} // namespace

Bsdf Bsdf::conductor(const Rgb &eta, const Rgb &k, const Rgb &specular_reflectance) {
    require_index(eta, "conductor eta");
    require_index(k, "conductor k");
    require_reflectance(specular_reflectance, "conductor specular_reflectance");
    Bsdf b;
    b.type_ = Type::Conductor;
    b.conductor_eta_ = eta;
    b.conductor_k_ = k;
    b.reflectance_ = specular_reflectance;
    return b;
}

Bsdf Bsdf::rough_conductor(MicrofacetType distribution, double alpha_u, double alpha_v, const Rgb &eta, const Rgb &k,
                           const Rgb &specular_reflectance, bool sample_visible) {
    require_alpha(alpha_u, "roughconductor alpha_u");
    require_alpha(alpha_v, "roughconductor alpha_v");
    require_index(eta, "roughconductor eta");
    require_index(k, "roughconductor k");
    require_reflectance(specular_reflectance, "roughconductor specular_reflectance");
    Bsdf b;
    b.type_ = Type::RoughConductor;
    b.conductor_eta_ = eta;
    b.conductor_k_ = k;
    b.reflectance_ = specular_reflectance;
    b.distribution_ = MicrofacetDistribution(distribution, alpha_u, alpha_v, sample_visible);
    return b;
}

BsdfSample Bsdf::sample_rough_conductor(const Vec3 &w, double u1, double u2) const {
    BsdfSample s;
    double pdf_m = 0;
    const Vec3 m = distribution_.sample(w, u1, u2, &pdf_m);
    const double w_dot_m = dot(w, m);
    if (!(pdf_m > 0) || !(w_dot_m > 0)) return s;
    s.wi = normalize(2.0 * w_dot_m * m - w);
    if (!(s.wi.z > 0)) return s;
    s.pdf = pdf_m / (4.0 * w_dot_m);
    const double g = distribution_.sample_visible() ? distribution_.smith_g1(s.wi, m)
                                                    : distribution_.G(w, s.wi, m) * w_dot_m / (w.z * m.z);
    s.weight = reflectance_ * fresnel_conductor(w_dot_m, conductor_eta_, conductor_k_) * g;
    return s;
}

Rgb Bsdf::eval_rough_conductor(const Vec3 &w, const Vec3 &wi) const {
    if (!(w.z > 0 && wi.z > 0)) return Rgb();
    const Vec3 h = normalize(w + wi);
    const double d = distribution_.eval(h);
    if (!(d > 0)) return Rgb();
    const double g = distribution_.G(w, wi, h);
    return reflectance_ * fresnel_conductor(dot(w, h), conductor_eta_, conductor_k_) * (d * g / (4.0 * w.z * wi.z));
}

double Bsdf::pdf_rough_conductor(const Vec3 &w, const Vec3 &wi) const {
    if (!(w.z > 0 && wi.z > 0)) return 0.0;
    const Vec3 h = normalize(w + wi);
    if (distribution_.sample_visible()) return distribution_.eval(h) * distribution_.smith_g1(w, h) / (4.0 * w.z);
    return distribution_.eval(h) * h.z / (4.0 * dot(wi, h));
}

} // namespace ppm
