// SPDX-License-Identifier: Apache-2.0
#include "material/bsdf.h"

#include "core/error.h"
#include "material/bsdf_helpers.h"
#include "material/fresnel.h"
#include "math/warp.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace ppm {

namespace {

using bsdf_helpers::reflect_local;
using bsdf_helpers::require_reflectance;

double require_eta(double int_ior, double ext_ior) {
    if (!(int_ior > 0 && std::isfinite(int_ior)))
        invalid_argument("int_ior must be finite and > 0, got " + format_number(int_ior));
    if (!(ext_ior > 0 && std::isfinite(ext_ior)))
        invalid_argument("ext_ior must be finite and > 0, got " + format_number(ext_ior));
    return int_ior / ext_ior;
}

Vec3 flip_z(const Vec3 &w) { return {w.x, w.y, -w.z}; }

} // namespace

FresnelTerms fresnel_dielectric_terms(double cos_i, double eta) {
    cos_i = std::clamp(cos_i, -1.0, 1.0);
    if (cos_i < 0) {
        eta = 1.0 / eta;
        cos_i = -cos_i;
    }
    const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0) return {1.0, 1.0, 0.0};
    const double cos_t = std::sqrt(1.0 - sin2_t);
    const double r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const double r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return {r_perpendicular * r_perpendicular, r_parallel * r_parallel, cos_t};
}

double fresnel_diffuse_reflectance(double eta) {
    // Below mu_c = sqrt(1 - eta^2) (only when eta < 1) everything is reflected: that part is
    // mu_c^2 exactly. Above it F has a square-root kink at mu_c, which the substitution
    // mu = mu_c + (1 - mu_c) s^2 smooths out for Simpson's rule.
    const double mu_c = eta < 1 ? std::sqrt(1.0 - eta * eta) : 0.0;
    const int n = 1024; // even
    const double h = 1.0 / n;
    double sum = 0;
    for (int k = 0; k <= n; ++k) {
        const double s = k * h;
        const double mu = mu_c + (1.0 - mu_c) * s * s;
        const double g = 2.0 * fresnel_dielectric(mu, eta) * mu * 2.0 * (1.0 - mu_c) * s;
        sum += g * (k == 0 || k == n ? 1.0 : (k % 2 ? 4.0 : 2.0));
    }
    return mu_c * mu_c + sum * h / 3.0;
}

Bsdf Bsdf::diffuse(const Rgb &reflectance) {
    require_reflectance(reflectance, "diffuse reflectance");
    Bsdf b;
    b.type_ = Type::Diffuse;
    b.reflectance_ = reflectance;
    return b;
}

Bsdf Bsdf::mirror(const Rgb &specular_reflectance) {
    require_reflectance(specular_reflectance, "mirror specular_reflectance");
    Bsdf b;
    b.type_ = Type::Mirror;
    b.reflectance_ = specular_reflectance;
    return b;
}

Bsdf Bsdf::dielectric(double int_ior, double ext_ior) {
    Bsdf b;
    b.type_ = Type::Dielectric;
    b.eta_ = require_eta(int_ior, ext_ior);
    b.reflectance_ = Rgb(1.0);
    return b;
}

Bsdf Bsdf::coated(const Rgb &diffuse_reflectance, double int_ior, double ext_ior, bool nonlinear,
                  const Rgb &specular_reflectance) {
    require_reflectance(diffuse_reflectance, "coated diffuse_reflectance");
    require_reflectance(specular_reflectance, "coated specular_reflectance");
    Bsdf b;
    b.type_ = Type::Coated;
    b.coat_specular_ = specular_reflectance;
    b.eta_ = require_eta(int_ior, ext_ior);
    const double fdr = fresnel_diffuse_reflectance(b.eta_);
    b.coat_diffuse_scale_ = 1.0 / (1.0 - fdr);
    if (nonlinear) b.nonlinear_internal_reflectance_ = 1.0 - (1.0 - fdr) / (b.eta_ * b.eta_);
    return b.with_reflectance(diffuse_reflectance);
}

Bsdf Bsdf::null() {
    Bsdf b;
    b.type_ = Type::Null;
    b.reflectance_ = Rgb(1.0);
    return b;
}

Bsdf Bsdf::with_reflectance(const Rgb &reflectance) const {
    Bsdf b = *this;
    b.reflectance_ = reflectance;
    // Mitsuba's plastic steers samples by the lobes' mean reflectances.
    const double s_mean = coat_specular_.mean(), total = s_mean + reflectance.mean();
    b.specular_sampling_weight_ = total > 0 ? s_mean / total : 0.5;
    // A nonlinear coat: R_d / (1 - R_d F) = R_d (1 - F) / (1 - R_d F) / (1 - F), so the
    // linear lobe (R / (1 - F)) gives it with R = R_d (1 - F) / (1 - R_d F), which lies in
    // [0, R_d] for R_d, F in [0, 1].
    const double f = nonlinear_internal_reflectance_;
    if (f >= 0) {
        const auto bounced = [f](double d) { return d * (1.0 - f) / (1.0 - d * f); };
        b.reflectance_ = Rgb(bounced(reflectance.r), bounced(reflectance.g), bounced(reflectance.b));
    }
    return b;
}

double Bsdf::coat_specular_probability(double fresnel_o) const {
    const double p_specular = fresnel_o * specular_sampling_weight_;
    const double p_diffuse = (1.0 - fresnel_o) * (1.0 - specular_sampling_weight_);
    const double total = p_specular + p_diffuse;
    return total > 0 ? p_specular / total : 0.0;
}

double Bsdf::specular_probability(const Vec3 &wo) const {
    switch (type_) {
    case Type::Diffuse: return 0.0;
    case Type::Mirror:
    case Type::Conductor:
    case Type::Dielectric:
    case Type::Null:
    case Type::ThinDielectric: return 1.0;
    case Type::Coated: return coat_specular_probability(fresnel_dielectric(std::fabs(wo.z), eta_));
    case Type::RoughConductor:
    case Type::RoughDielectric:
    case Type::RoughPlastic: return 0.0;
    }
    return 0.0;
}

bool Bsdf::gathers(double gather_alpha) const {
    switch (type_) {
    case Type::Diffuse:
    case Type::Coated: return true;
    case Type::RoughConductor: return std::min(distribution_.alpha_u(), distribution_.alpha_v()) >= gather_alpha;
    // Rough plastic is gathered whole, coat included, whatever its roughness: a continued coat
    // would need a visible point that evaluates the base alone (Bsdf has no such query yet).
    case Type::RoughPlastic: return true;
    case Type::Mirror:
    case Type::Conductor:
    case Type::Dielectric:
    case Type::ThinDielectric:
    case Type::Null:
    case Type::RoughDielectric: return false;
    }
    return false;
}

double Bsdf::continue_probability(const Vec3 &wo, double gather_alpha) const {
    if (!gathers(gather_alpha)) return 1.0;
    return type_ == Type::Coated ? specular_probability(wo) : 0.0;
}

BsdfSample Bsdf::sample(const Vec3 &wo, double u_lobe, double u1, double u2, TransportMode mode) const {
    BsdfSample s;
    if (wo.z == 0) return s;

    if (type_ == Type::Null) {
        s.wi = wo * -1.0;
        s.pdf = 1.0;
        s.is_specular = true;
        s.weight = Rgb(1.0);
        return s;
    }
    if (type_ == Type::Dielectric) {
        const FresnelTerms fresnel = fresnel_dielectric_terms(wo.z, eta_);
        const double r = fresnel.reflectance();
        s.is_specular = true;
        s.weight = Rgb(1.0); // f |cos| / pdf = R / R
        if (u_lobe < r) {
            s.wi = reflect_local(wo);
            s.pdf = r;
            return s;
        }
        // pbrt-v4 Refract(): the transmitted direction in the frame of the interface.
        const double eta_t = wo.z > 0 ? eta_ : 1.0 / eta_; // n(wi side) / n(wo side)
        s.wi = {-wo.x / eta_t, -wo.y / eta_t, std::copysign(fresnel.cos_t, -wo.z)};
        s.pdf = 1.0 - r;
        if (mode == TransportMode::Radiance) s.weight = Rgb(1.0 / (eta_t * eta_t));
        return s;
    }
    if (type_ == Type::ThinDielectric) return sample_thin_dielectric(wo, u_lobe);
    if (type_ == Type::RoughDielectric) return sample_rough_dielectric(wo, u_lobe, u1, u2, mode);

    // Opaque: work on the side of wo, flip back at the end.
    const bool back = wo.z < 0;
    const Vec3 w = back ? flip_z(wo) : wo;
    switch (type_) {
    case Type::Diffuse:
        s.wi = square_to_cosine_hemisphere(u1, u2);
        s.pdf = square_to_cosine_hemisphere_pdf(s.wi);
        s.weight = reflectance_; // (R / pi) cos / (cos / pi)
        break;
    case Type::Mirror:
        s.wi = reflect_local(w);
        s.pdf = 1.0;
        s.is_specular = true;
        s.weight = reflectance_;
        break;
    case Type::Conductor:
        s.wi = reflect_local(w);
        s.pdf = 1.0;
        s.is_specular = true;
        s.weight = reflectance_ * fresnel_conductor(w.z, conductor_eta_, conductor_k_);
        break;
    case Type::RoughConductor: s = sample_rough_conductor(w, u1, u2); break;
    case Type::Coated: {
        const double fresnel_o = fresnel_dielectric(w.z, eta_);
        const double p_specular = coat_specular_probability(fresnel_o);
        if (u_lobe < p_specular) {
            s.wi = reflect_local(w);
            s.pdf = p_specular;
            s.is_specular = true;
            s.weight = coat_specular_ * (fresnel_o / p_specular);
        } else {
            s.wi = square_to_cosine_hemisphere(u1, u2);
            const double p_diffuse = 1.0 - p_specular;
            s.pdf = p_diffuse * square_to_cosine_hemisphere_pdf(s.wi);
            const double fresnel_i = fresnel_dielectric(s.wi.z, eta_);
            s.weight = reflectance_ * (coat_diffuse_scale_ * (1.0 - fresnel_o) * (1.0 - fresnel_i) / p_diffuse);
        }
        break;
    }
    case Type::RoughPlastic: s = sample_rough_plastic(w, u_lobe, u1, u2); break;
    case Type::Dielectric:
    case Type::ThinDielectric:
    case Type::Null:
    case Type::RoughDielectric: break;
    }
    if (!(s.pdf > 0)) return BsdfSample{};
    if (back) s.wi = flip_z(s.wi);
    return s;
}

Rgb Bsdf::eval(const Vec3 &wo, const Vec3 &wi, TransportMode mode) const {
    if (type_ == Type::RoughDielectric) return eval_rough_dielectric(wo, wi, mode);
    if (!(wo.z * wi.z > 0)) return Rgb();
    switch (type_) {
    case Type::Diffuse: return reflectance_ * kInvPi;
    case Type::Coated: {
        const double fresnel_o = fresnel_dielectric(std::fabs(wo.z), eta_);
        const double fresnel_i = fresnel_dielectric(std::fabs(wi.z), eta_);
        return reflectance_ * (coat_diffuse_scale_ * (1.0 - fresnel_o) * (1.0 - fresnel_i) * kInvPi);
    }
    case Type::RoughConductor:
        return wo.z > 0 ? eval_rough_conductor(wo, wi) : eval_rough_conductor(flip_z(wo), flip_z(wi));
    case Type::RoughPlastic: return wo.z > 0 ? eval_rough_plastic(wo, wi) : eval_rough_plastic(flip_z(wo), flip_z(wi));
    case Type::Mirror:
    case Type::Conductor:
    case Type::Dielectric:
    case Type::ThinDielectric:
    case Type::Null:
    case Type::RoughDielectric: break;
    }
    return Rgb();
}

FixedWoLobe Bsdf::fixed_wo(const Vec3 &wo, const Rgb &weight) const {
    FixedWoLobe lobe;
    if (wo.z == 0 || !std::isfinite(wo.z)) return lobe;
    switch (type_) {
    case Type::Diffuse: lobe.factor_ = weight * (reflectance_ * kInvPi); break;
    case Type::Coated:
        lobe.factor_ = weight * (reflectance_ *
                                 (coat_diffuse_scale_ * (1.0 - fresnel_dielectric(std::fabs(wo.z), eta_)) * kInvPi));
        lobe.eta_ = eta_;
        lobe.coat_ = true;
        break;
    case Type::RoughConductor:
    case Type::RoughPlastic:
        lobe.factor_ = weight;
        lobe.full_ = true;
        break;
    case Type::Mirror:
    case Type::Conductor:
    case Type::Dielectric:
    case Type::ThinDielectric:
    case Type::Null:
    case Type::RoughDielectric: break;
    }
    return lobe;
}

double Bsdf::pdf(const Vec3 &wo, const Vec3 &wi) const {
    if (type_ == Type::RoughDielectric) return pdf_rough_dielectric(wo, wi);
    if (!(wo.z * wi.z > 0)) return 0.0;
    const double cosine_pdf = std::fabs(wi.z) * kInvPi;
    switch (type_) {
    case Type::Diffuse: return cosine_pdf;
    case Type::Coated: return (1.0 - coat_specular_probability(fresnel_dielectric(std::fabs(wo.z), eta_))) * cosine_pdf;
    case Type::RoughConductor:
        return wo.z > 0 ? pdf_rough_conductor(wo, wi) : pdf_rough_conductor(flip_z(wo), flip_z(wi));
    case Type::RoughPlastic: return wo.z > 0 ? pdf_rough_plastic(wo, wi) : pdf_rough_plastic(flip_z(wo), flip_z(wi));
    case Type::Mirror:
    case Type::Conductor:
    case Type::Dielectric:
    case Type::ThinDielectric:
    case Type::Null:
    case Type::RoughDielectric: break;
    }
    return 0.0;
}

} // namespace ppm
