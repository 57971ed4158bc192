// SPDX-License-Identifier: Apache-2.0
// The dielectric family beyond the smooth interface: Mitsuba 3's `thindielectric`,
// `roughdielectric` and `roughplastic` (src/bsdfs/*.cpp), written from their formulas (Walter,
// Marschner, Li and Torrance 2007 for the rough interface) with this library's conventions:
// wo is Mitsuba's si.wi, wi Mitsuba's wo, and f excludes the cosine that Mitsuba's eval() folds
// in.
#include "material/bsdf.h"

#include "core/error.h"
#include "material/bsdf_helpers.h"
#include "math/warp.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

namespace ppm {

namespace {

using bsdf_helpers::reflect_local;
using bsdf_helpers::require_alpha;
using bsdf_helpers::require_reflectance;
using bsdf_helpers::sqr;

Vec3 mulsign_z(const Vec3 &w, double s) { return s < 0 ? -w : w; }
Vec3 reflect_about(const Vec3 &w, const Vec3 &m) { return 2.0 * dot(w, m) * m - w; }

// Mitsuba's fresnel(cos_i, eta): the reflectance, the SIGNED cosine of the transmitted
// direction (opposite in sign to cos_i) and the relative indices eta_it = n_t / n_i and
// eta_ti = 1 / eta_it, for incidence from outside (cos_i > 0) or inside.
struct Interface {
    double reflectance, cos_t, eta_it, eta_ti;
};
Interface interface_at(double cos_i, double eta) {
    const FresnelTerms terms = fresnel_dielectric_terms(cos_i, eta);
    const double eta_it = cos_i >= 0 ? eta : 1.0 / eta;
    return {terms.reflectance(), -std::copysign(terms.cos_t, cos_i), eta_it, 1.0 / eta_it};
}
// Refraction of w about the microfacet normal m (Mitsuba's refract(wi, m, cos_t, eta_ti)).
Vec3 refract_about(const Vec3 &w, const Vec3 &m, double cos_t, double eta_ti) {
    return (dot(w, m) * eta_ti + cos_t) * m - eta_ti * w;
}

double require_distinct_eta(double int_ior, double ext_ior, const char *type) {
    if (!(int_ior > 0 && std::isfinite(int_ior)))
        invalid_argument(std::string(type) + " int_ior must be finite and > 0, got " + format_number(int_ior));
    if (!(ext_ior > 0 && std::isfinite(ext_ior)))
        invalid_argument(std::string(type) + " ext_ior must be finite and > 0, got " + format_number(ext_ior));
    if (int_ior == ext_ior)
        invalid_argument(std::string(type) + " int_ior and ext_ior must differ, both are " + format_number(int_ior));
    return int_ior / ext_ior;
}

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n from Chebyshev guesses).
void gauss_legendre(int n, std::vector<double> &nodes, std::vector<double> &weights) {
    nodes.assign(n, 0.0), weights.assign(n, 0.0);
    for (int i = 0; i < n; ++i) {
        double x = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1, p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1);
            const double step = p1 / dp;
            x -= step;
            if (std::fabs(step) < 1e-16) break;
        }
        nodes[i] = x;
        weights[i] = 2.0 / ((1 - x * x) * dp * dp);
    }
}

// Mitsuba's eval_reflectance / eval_transmittance (include/mitsuba/render/microfacet.h): the
// albedo of the rough interface's reflection (or refraction) for light arriving along w
// (w.z > 0) through a medium of relative index eta on the other side, integrated over the
// visible-normal sampler's unit square with a res x res Gauss-Legendre rule.
double rough_interface_albedo(const MicrofacetDistribution &distr, const Vec3 &w, double eta, bool transmitted,
                              const std::vector<double> &nodes, const std::vector<double> &weights) {
    double accum = 0;
    const std::size_t n = nodes.size();
    for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = 0; b < n; ++b) {
            double pdf;
            const Vec3 m = distr.sample(w, 0.5 * nodes[a] + 0.5, 0.5 * nodes[b] + 0.5, &pdf);
            const Interface f = interface_at(dot(w, m), eta);
            double value;
            if (transmitted) {
                const Vec3 out = refract_about(w, m, f.cos_t, f.eta_ti);
                value = out.z * w.z < 0 ? distr.smith_g1(out, m) * (1.0 - f.reflectance) : 0.0;
            } else {
                const Vec3 out = reflect_about(w, m);
                value = out.z > 0 ? distr.smith_g1(out, m) * f.reflectance : 0.0;
            }
            accum += value * weights[a] * weights[b];
        }
    return 0.25 * accum;
}

} // namespace

// The rough coat's tables, as Mitsuba's roughplastic precomputes them: the transmittance
// 1 - (reflected albedo) of the coat for light from outside at 64 cosines in [0, 1], and the
// internal diffuse reflectance 2 * mean(mu R_int(mu)) over the same cosines (Mitsuba's sum,
// not an exact integral: matched so that f equals Mitsuba's). They depend only on the
// distribution and eta, are interned process-wide and never freed (one per distinct coat).
struct RoughCoatTable {
    static constexpr int kResolution = 64; // Mitsuba's MI_ROUGH_TRANSMITTANCE_RES
    double transmittance[kResolution];
    double internal_reflectance = 0;

    // Mitsuba's lerp_gather: linear interpolation on the uniform grid of cosines.
    double transmittance_at(double cos_theta) const {
        const double x = std::clamp(cos_theta, 0.0, 1.0) * (kResolution - 1);
        const int index = std::min(static_cast<int>(x), kResolution - 2);
        const double w1 = x - index;
        return (1.0 - w1) * transmittance[index] + w1 * transmittance[index + 1];
    }

    static const RoughCoatTable *get(MicrofacetType type, double alpha, double eta) {
        static std::mutex mutex;
        static std::map<std::tuple<int, double, double>, std::unique_ptr<RoughCoatTable>> tables;
        const std::lock_guard<std::mutex> lock(mutex);
        std::unique_ptr<RoughCoatTable> &slot = tables[{static_cast<int>(type), alpha, eta}];
        if (!slot) {
            auto table = std::make_unique<RoughCoatTable>();
            const MicrofacetDistribution distr(type, alpha, alpha, true);
            std::vector<double> nodes, weights;
            // Mitsuba: 128 nodes per side, 32 when eta > 1.
            gauss_legendre(eta > 1 ? 32 : 128, nodes, weights);
            std::vector<double> nodes_int, weights_int;
            gauss_legendre(1.0 / eta > 1 ? 32 : 128, nodes_int, weights_int);
            double internal = 0;
            for (int i = 0; i < kResolution; ++i) {
                const double mu = std::max(1e-6, static_cast<double>(i) / (kResolution - 1));
                const Vec3 w{std::sqrt(1 - mu * mu), 0.0, mu};
                table->transmittance[i] = rough_interface_albedo(distr, w, eta, true, nodes, weights);
                internal += mu * rough_interface_albedo(distr, w, 1.0 / eta, false, nodes_int, weights_int);
            }
            table->internal_reflectance = 2.0 * internal / kResolution;
            slot = std::move(table);
        }
        return slot.get();
    }
};

double Bsdf::rough_coat_internal_reflectance() const {
    return type_ == Type::RoughPlastic ? coat_table_->internal_reflectance : 0.0;
}
double Bsdf::rough_coat_transmittance(double cos_theta) const {
    return type_ == Type::RoughPlastic ? coat_table_->transmittance_at(cos_theta) : 1.0;
}

Bsdf Bsdf::thin_dielectric(double int_ior, double ext_ior) {
    Bsdf b;
    b.type_ = Type::ThinDielectric;
    b.eta_ = require_distinct_eta(int_ior, ext_ior, "thindielectric");
    b.reflectance_ = Rgb(1.0);
    return b;
}

Bsdf Bsdf::rough_dielectric(MicrofacetType distribution, double alpha_u, double alpha_v, double int_ior, double ext_ior,
                            bool sample_visible) {
    require_alpha(alpha_u, "roughdielectric alpha_u");
    require_alpha(alpha_v, "roughdielectric alpha_v");
    Bsdf b;
    b.type_ = Type::RoughDielectric;
    b.eta_ = require_distinct_eta(int_ior, ext_ior, "roughdielectric");
    b.reflectance_ = Rgb(1.0);
    b.distribution_ = MicrofacetDistribution(distribution, alpha_u, alpha_v, sample_visible);
    return b;
}

Bsdf Bsdf::rough_plastic(const Rgb &diffuse_reflectance, MicrofacetType distribution, double alpha, double int_ior,
                         double ext_ior, bool sample_visible, bool nonlinear, const Rgb &specular_reflectance) {
    require_reflectance(diffuse_reflectance, "roughplastic diffuse_reflectance");
    require_reflectance(specular_reflectance, "roughplastic specular_reflectance");
    require_alpha(alpha, "roughplastic alpha");
    Bsdf b;
    b.type_ = Type::RoughPlastic;
    b.coat_specular_ = specular_reflectance;
    b.eta_ = require_distinct_eta(int_ior, ext_ior, "roughplastic");
    b.distribution_ = MicrofacetDistribution(distribution, alpha, alpha, sample_visible);
    // The distribution clamps alpha at 1e-4; the table is made for the clamped value.
    b.coat_table_ = RoughCoatTable::get(distribution, b.distribution_.alpha_u(), b.eta_);
    // 1 / eta^2 / (1 - R_int): Mitsuba's m_inv_eta_2 over its linear normalisation.
    b.coat_diffuse_scale_ = 1.0 / (b.eta_ * b.eta_ * (1.0 - b.coat_table_->internal_reflectance));
    if (nonlinear) b.nonlinear_internal_reflectance_ = b.coat_table_->internal_reflectance;
    return b.with_reflectance(diffuse_reflectance);
}

// Thin dielectric (Mitsuba thindielectric.cpp): a sheet whose two parallel faces reflect R
// each; the internal bounces sum to R' = R + T^2 R / (1 - R^2) = 2 R / (1 + R), and the rest
// passes straight through (wi = -wo, no net refraction). Symmetric: no mode.
BsdfSample Bsdf::sample_thin_dielectric(const Vec3 &wo, double u_lobe) const {
    BsdfSample s;
    const double r = fresnel_dielectric(std::fabs(wo.z), eta_);
    const double r_total = 2.0 * r / (1.0 + r);
    s.is_specular = true;
    s.weight = Rgb(1.0);
    if (u_lobe < r_total) {
        s.wi = reflect_local(wo);
        s.pdf = r_total;
    } else {
        s.wi = -wo;
        s.pdf = 1.0 - r_total;
    }
    if (!(s.pdf > 0)) return BsdfSample{};
    return s;
}

double Bsdf::thin_dielectric_reflectance(double cos_wo) const {
    const double r = fresnel_dielectric(std::fabs(cos_wo), eta_);
    return 2.0 * r / (1.0 + r);
}

MicrofacetDistribution Bsdf::rough_sampling_distribution(double cos_wo) const {
    if (distribution_.sample_visible()) return distribution_;
    // Walter et al. 2007, sec. 5.3 (and Mitsuba): a slightly wider distribution reduces the
    // weights' variance at grazing angles when all normals are sampled.
    const double scale = 1.2 - 0.2 * std::sqrt(std::fabs(cos_wo));
    return MicrofacetDistribution(distribution_.type(), distribution_.alpha_u() * scale,
                                  distribution_.alpha_v() * scale, false);
}

BsdfSample Bsdf::sample_rough_dielectric(const Vec3 &wo, double u_lobe, double u1, double u2,
                                         TransportMode mode) const {
    BsdfSample s;
    const double cos_o = wo.z;
    const MicrofacetDistribution sample_distr = rough_sampling_distribution(cos_o);
    double pdf_m;
    // The microfacet normal is drawn on the macro-normal's side (m.z > 0) as seen from wo
    // mirrored to the outside; reflecting or refracting about it works from either side.
    const Vec3 m = sample_distr.sample(mulsign_z(wo, cos_o), u1, u2, &pdf_m);
    // All-normal sampling also draws facets that wo sees from behind: they scatter nothing
    // (G1 = 0), and pdf() gives them no density.
    if (!(pdf_m > 0) || !(dot(wo, m) * cos_o > 0)) return s;
    const Interface f = interface_at(dot(wo, m), eta_);
    double dwh_dwi;
    double weight = 1.0;
    if (u_lobe < f.reflectance) {
        s.wi = reflect_about(wo, m);
        if (!(s.wi.z * cos_o > 0)) return BsdfSample{};
        s.pdf = pdf_m * f.reflectance;
        dwh_dwi = 1.0 / (4.0 * dot(s.wi, m));
    } else {
        s.wi = refract_about(wo, m, f.cos_t, f.eta_ti);
        if (!(s.wi.z * cos_o < 0)) return BsdfSample{};
        s.pdf = pdf_m * (1.0 - f.reflectance);
        // Radiance is compressed into the smaller solid angle of the denser side.
        if (mode == TransportMode::Radiance) weight = f.eta_ti * f.eta_ti;
        dwh_dwi = sqr(f.eta_it) * dot(s.wi, m) / sqr(dot(wo, m) + f.eta_it * dot(s.wi, m));
    }
    // f |cos wi| / pdf: with visible normals G1(wi, m); else G dot(wo, m) / (cos wo cos m) times
    // D / D_sample for the widened sampling distribution (Walter et al. 2007, eq. 41).
    if (distribution_.sample_visible())
        weight *= distribution_.smith_g1(s.wi, m);
    else
        weight *=
            distribution_.G(wo, s.wi, m) * dot(wo, m) / (cos_o * m.z) * distribution_.eval(m) / sample_distr.eval(m);
    s.pdf *= std::fabs(dwh_dwi);
    s.weight = Rgb(std::fabs(weight));
    if (!(s.pdf > 0) || !std::isfinite(s.pdf)) return BsdfSample{};
    return s;
}

namespace {

// The generalised half vector of Walter et al. 2007 (eq. 16), on the macro-normal's side, and
// the relative index across the boundary as seen from wo.
struct HalfVector {
    Vec3 m;
    double eta; // n(wi side) / n(wo side) on transmission, 1 on reflection
    bool reflect;
};
HalfVector half_vector(const Vec3 &wo, const Vec3 &wi, double eta) {
    HalfVector h;
    h.reflect = wo.z * wi.z > 0;
    h.eta = h.reflect ? 1.0 : (wo.z > 0 ? eta : 1.0 / eta);
    h.m = normalize(wo + wi * h.eta);
    if (h.m.z < 0) h.m = -h.m;
    return h;
}

} // namespace

Rgb Bsdf::eval_rough_dielectric(const Vec3 &wo, const Vec3 &wi, TransportMode mode) const {
    const double cos_o = wo.z, cos_i = wi.z;
    if (cos_o == 0 || cos_i == 0) return Rgb();
    const HalfVector h = half_vector(wo, wi, eta_);
    if (!std::isfinite(h.m.z)) return Rgb();
    const double d = distribution_.eval(h.m);
    if (d == 0) return Rgb();
    const double fr = fresnel_dielectric(dot(wo, h.m), eta_);
    const double g = distribution_.G(wo, wi, h.m); // zero where a side does not agree with m
    if (g == 0) return Rgb();
    if (h.reflect) return Rgb(fr * d * g / (4.0 * std::fabs(cos_o * cos_i)));
    const double wo_m = dot(wo, h.m), wi_m = dot(wi, h.m);
    double value = (1.0 - fr) * d * g * h.eta * h.eta * wo_m * wi_m / (cos_o * cos_i * sqr(wo_m + h.eta * wi_m));
    // The 1/eta'^2 of radiance crossing into a medium of relative index eta' (see bsdf.h).
    if (mode == TransportMode::Radiance) value /= h.eta * h.eta;
    return Rgb(std::fabs(value));
}

double Bsdf::pdf_rough_dielectric(const Vec3 &wo, const Vec3 &wi) const {
    const double cos_o = wo.z, cos_i = wi.z;
    if (cos_o == 0 || cos_i == 0) return 0.0;
    const HalfVector h = half_vector(wo, wi, eta_);
    if (!std::isfinite(h.m.z)) return 0.0;
    const double wo_m = dot(wo, h.m), wi_m = dot(wi, h.m);
    if (!(wo_m * cos_o > 0 && wi_m * cos_i > 0)) return 0.0;
    const double dwh_dwi = h.reflect ? 1.0 / (4.0 * wi_m) : h.eta * h.eta * wi_m / sqr(wo_m + h.eta * wi_m);
    const double fr = fresnel_dielectric(wo_m, eta_);
    const double prob = rough_sampling_distribution(cos_o).pdf(mulsign_z(wo, cos_o), h.m) * (h.reflect ? fr : 1.0 - fr);
    return std::fabs(prob * dwh_dwi);
}

// Rough plastic (Mitsuba roughplastic.cpp, nonlinear = false), on wo's side (w.z > 0):
//   f = S F(w.h) D(h) G / (4 cos_o cos_i)                              (the rough coat)
//     + R_d / (eta^2 (1 - R_int)) T(cos_o) T(cos_i) / pi               (the base)
// with S the specular_reflectance, T the coat's tabulated transmittance and R_int its internal
// diffuse reflectance. The
// coat is picked with Mitsuba's probability (1 - T(cos_o)) s / ((1 - T(cos_o)) s + T(cos_o) (1 - s)),
// s = specular_sampling_weight_, and a sample's weight is f cos / pdf of the whole mixture.
double Bsdf::rough_plastic_coat_probability(double cos_o) const {
    const double t_o = coat_table_->transmittance_at(cos_o);
    const double p_specular = (1.0 - t_o) * specular_sampling_weight_;
    const double p_diffuse = t_o * (1.0 - specular_sampling_weight_);
    const double total = p_specular + p_diffuse;
    return total > 0 ? p_specular / total : 0.0;
}

Rgb Bsdf::eval_rough_plastic(const Vec3 &w, const Vec3 &wi) const {
    if (!(w.z > 0 && wi.z > 0)) return Rgb();
    const Vec3 h = normalize(w + wi);
    const double coat =
        fresnel_dielectric(dot(w, h), eta_) * distribution_.eval(h) * distribution_.G(w, wi, h) / (4.0 * w.z * wi.z);
    const double base =
        coat_diffuse_scale_ * coat_table_->transmittance_at(w.z) * coat_table_->transmittance_at(wi.z) * kInvPi;
    return coat_specular_ * coat + reflectance_ * base;
}

double Bsdf::pdf_rough_plastic(const Vec3 &w, const Vec3 &wi) const {
    if (!(w.z > 0 && wi.z > 0)) return 0.0;
    const double p_specular = rough_plastic_coat_probability(w.z);
    const Vec3 h = normalize(w + wi);
    const double coat_pdf = distribution_.sample_visible()
                                ? distribution_.eval(h) * distribution_.smith_g1(w, h) / (4.0 * w.z)
                                : distribution_.pdf(w, h) / (4.0 * dot(wi, h));
    return p_specular * coat_pdf + (1.0 - p_specular) * wi.z * kInvPi;
}

BsdfSample Bsdf::sample_rough_plastic(const Vec3 &w, double u_lobe, double u1, double u2) const {
    BsdfSample s;
    if (u_lobe < rough_plastic_coat_probability(w.z)) {
        double pdf_m;
        const Vec3 m = distribution_.sample(w, u1, u2, &pdf_m);
        if (!(pdf_m > 0)) return s;
        s.wi = reflect_about(w, m);
    } else {
        s.wi = square_to_cosine_hemisphere(u1, u2);
    }
    if (!(s.wi.z > 0)) return BsdfSample{};
    s.pdf = pdf_rough_plastic(w, s.wi);
    if (!(s.pdf > 0) || !std::isfinite(s.pdf)) return BsdfSample{};
    s.weight = eval_rough_plastic(w, s.wi) * (s.wi.z / s.pdf);
    return s;
}

} // namespace ppm
