// SPDX-License-Identifier: Apache-2.0
#include "material/microfacet.h"

#include "material/bsdf_helpers.h"
#include "math/warp.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace ppm {

namespace {

using bsdf_helpers::sqr;

constexpr double kInvSqrtPi = 0.56418958354775628695;

} // namespace

bool parse_microfacet_type(const char *name, MicrofacetType *out) {
    if (!name) return false;
    if (std::strcmp(name, "beckmann") == 0) {
        *out = MicrofacetType::Beckmann;
        return true;
    }
    if (std::strcmp(name, "ggx") == 0) {
        *out = MicrofacetType::GGX;
        return true;
    }
    return false;
}

const char *microfacet_type_name(MicrofacetType type) { return type == MicrofacetType::GGX ? "ggx" : "beckmann"; }

double erf_inverse(double y) {
    if (!(y > -1)) return y == -1 ? -std::numeric_limits<double>::infinity() : std::nan("");
    if (!(y < 1)) return y == 1 ? std::numeric_limits<double>::infinity() : std::nan("");
    // Giles 2010, "Approximating the erfinv function" (single-precision branch) as the start.
    double w = -std::log((1.0 - y) * (1.0 + y)), p;
    if (w < 5.0) {
        w -= 2.5;
        p = 2.81022636e-08;
        p = 3.43273939e-07 + p * w;
        p = -3.5233877e-06 + p * w;
        p = -4.39150654e-06 + p * w;
        p = 0.00021858087 + p * w;
        p = -0.00125372503 + p * w;
        p = -0.00417768164 + p * w;
        p = 0.246640727 + p * w;
        p = 1.50140941 + p * w;
    } else {
        w = std::sqrt(w) - 3.0;
        p = -0.000200214257;
        p = 0.000100950558 + p * w;
        p = 0.00134934322 + p * w;
        p = -0.00367342844 + p * w;
        p = 0.00573950773 + p * w;
        p = -0.0076224613 + p * w;
        p = 0.00943887047 + p * w;
        p = 1.00167406 + p * w;
        p = 2.83297682 + p * w;
    }
    double x = p * y;
    // Newton on erf(x) - y; erf'(x) = 2/sqrt(pi) exp(-x^2). In the tails the residual is taken
    // with erfc against 1 - |y| (exact by Sterbenz's lemma), which avoids the cancellation.
    for (int i = 0; i < 8; ++i) {
        const double d = 2.0 * kInvSqrtPi * std::exp(-x * x);
        if (!(d > 0)) break;
        double residual;
        if (y > 0.5)
            residual = (1.0 - y) - std::erfc(x);
        else if (y < -0.5)
            residual = std::erfc(-x) - (1.0 + y);
        else
            residual = std::erf(x) - y;
        const double step = residual / d;
        x -= step;
        if (!(std::fabs(step) > 1e-15 * std::fabs(x))) break;
    }
    return x;
}

MicrofacetDistribution::MicrofacetDistribution(MicrofacetType type, double alpha_u, double alpha_v, bool sample_visible)
    : type_(type), alpha_u_(std::max(alpha_u, 1e-4)), alpha_v_(std::max(alpha_v, 1e-4)),
      sample_visible_(sample_visible) {}

double MicrofacetDistribution::eval(const Vec3 &m) const {
    const double cos2 = m.z * m.z;
    if (!(m.z > 0)) return 0.0;
    double result;
    if (type_ == MicrofacetType::Beckmann) {
        result =
            std::exp(-(sqr(m.x / alpha_u_) + sqr(m.y / alpha_v_)) / cos2) / (kPi * alpha_u_ * alpha_v_ * cos2 * cos2);
    } else {
        result = 1.0 / (kPi * alpha_u_ * alpha_v_ * sqr(sqr(m.x / alpha_u_) + sqr(m.y / alpha_v_) + cos2));
    }
    // As Mitsuba: flush vanishing values, which only cause trouble later.
    return result * m.z > 1e-20 ? result : 0.0;
}

double MicrofacetDistribution::smith_g1(const Vec3 &v, const Vec3 &m) const {
    // Consistent orientation: the back of a microfacet is never seen from the front.
    if (dot(v, m) * v.z <= 0) return 0.0;
    const double xy_alpha_2 = sqr(alpha_u_ * v.x) + sqr(alpha_v_ * v.y);
    if (xy_alpha_2 == 0) return 1.0; // perpendicular incidence: no shadowing
    const double tan_theta_alpha_2 = xy_alpha_2 / sqr(v.z);
    if (type_ == MicrofacetType::Beckmann) {
        const double a = 1.0 / std::sqrt(tan_theta_alpha_2);
        const double lambda = 0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) * (0.5 * kInvSqrtPi) / a;
        return 1.0 / (1.0 + lambda);
    }
    return 2.0 / (1.0 + std::sqrt(1.0 + tan_theta_alpha_2));
}

double MicrofacetDistribution::pdf(const Vec3 &wi, const Vec3 &m) const {
    const double d = eval(m);
    if (sample_visible_) {
        if (!(wi.z > 0)) return 0.0;
        return d * smith_g1(wi, m) * std::fabs(dot(wi, m)) / wi.z;
    }
    return d * m.z;
}

Vec3 MicrofacetDistribution::sample(const Vec3 &wi, double u1, double u2, double *pdf_out) const {
    Vec3 m;
    if (!sample_visible_)
        m = sample_all(u1, u2);
    else if (type_ == MicrofacetType::GGX)
        m = sample_visible_ggx(wi, u1, u2);
    else
        m = sample_visible_beckmann(wi, u1, u2);
    *pdf_out = pdf(wi, m);
    return m;
}

// D(m) cos(theta_m), by inverting the CDFs in phi and theta (Walter et al. 2007; Mitsuba's
// non-visible branch).
Vec3 MicrofacetDistribution::sample_all(double u1, double u2) const {
    double sin_phi, cos_phi, alpha_2;
    if (is_isotropic()) {
        sin_phi = std::sin(2.0 * kPi * u2);
        cos_phi = std::cos(2.0 * kPi * u2);
        alpha_2 = alpha_u_ * alpha_u_;
    } else {
        const double tmp = (alpha_v_ / alpha_u_) * std::tan(2.0 * kPi * u2);
        cos_phi = std::copysign(1.0 / std::sqrt(tmp * tmp + 1.0), std::fabs(u2 - 0.5) - 0.25);
        sin_phi = cos_phi * tmp;
        alpha_2 = 1.0 / (sqr(cos_phi / alpha_u_) + sqr(sin_phi / alpha_v_));
    }
    double cos_theta;
    if (type_ == MicrofacetType::Beckmann)
        cos_theta = 1.0 / std::sqrt(1.0 - alpha_2 * std::log1p(-u1));
    else
        cos_theta = 1.0 / std::sqrt(1.0 + alpha_2 * u1 / (1.0 - u1));
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return {cos_phi * sin_theta, sin_phi * sin_theta, cos_theta};
}

// Heitz 2018, listing 1: stretch wi to the alpha = 1 configuration, sample the projected
// half disk, unstretch.
Vec3 MicrofacetDistribution::sample_visible_ggx(const Vec3 &wi, double u1, double u2) const {
    const Vec3 vh = normalize(Vec3{alpha_u_ * wi.x, alpha_v_ * wi.y, wi.z});
    const double lensq = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = lensq > 0 ? Vec3{-vh.y, vh.x, 0.0} / std::sqrt(lensq) : Vec3{1.0, 0.0, 0.0};
    const Vec3 t2 = cross(vh, t1);
    const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
    const double p1 = r * std::cos(phi);
    double p2 = r * std::sin(phi);
    const double s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * p2;
    const Vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return normalize(Vec3{alpha_u_ * nh.x, alpha_v_ * nh.y, std::max(1e-12, nh.z)});
}

// Jakob 2014 / Mitsuba's sample_visible_11 for Beckmann: stretch, draw the slopes of the
// alpha = 1 distribution seen from theta_i (x by Newton's method on its CDF in the erf
// domain, y from a Gaussian), rotate back to wi's azimuth and unstretch.
Vec3 MicrofacetDistribution::sample_visible_beckmann(const Vec3 &wi, double u1, double u2) const {
    const Vec3 wp = normalize(Vec3{alpha_u_ * wi.x, alpha_v_ * wi.y, wi.z});
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - wp.z * wp.z));
    const double cos_phi = sin_theta > 0 ? std::clamp(wp.x / sin_theta, -1.0, 1.0) : 1.0;
    const double sin_phi = sin_theta > 0 ? std::clamp(wp.y / sin_theta, -1.0, 1.0) : 0.0;

    const double cos_theta_i = wp.z;
    const double tan_theta_i = sin_theta / cos_theta_i;
    const double cot_theta_i = 1.0 / tan_theta_i; // +inf at normal incidence
    const double maxval = std::erf(cot_theta_i);
    u1 = std::clamp(u1, 1e-9, 1.0 - 1e-9);
    u2 = std::clamp(u2, 1e-9, 1.0 - 1e-9);
    // Initial guess: the analytic solution for theta_i = pi/2.
    double x = std::clamp(maxval - (maxval + 1.0) * std::erf(std::sqrt(-std::log(u1))), -1.0 + 1e-15,
                          std::min(maxval, 1.0 - 1e-15));
    const double tail = tan_theta_i > 0 ? kInvSqrtPi * tan_theta_i * std::exp(-cot_theta_i * cot_theta_i) : 0.0;
    const double target = u1 * (1.0 + maxval + tail); // the CDF's normalisation
    const double x_max = std::min(maxval, 1.0 - 1e-15);
    for (int i = 0; i < 8; ++i) {
        const double slope = erf_inverse(x);
        const double tail_x = tan_theta_i > 0 ? kInvSqrtPi * tan_theta_i * std::exp(-slope * slope) : 0.0;
        const double value = 1.0 + x + tail_x - target;
        const double derivative = 1.0 - slope * tan_theta_i;
        if (!(derivative > 0)) break;
        const double step = value / derivative;
        x = std::clamp(x - step, -1.0 + 1e-15, x_max);
        if (std::fabs(step) < 1e-14) break;
    }
    double slope_x = erf_inverse(x), slope_y = erf_inverse(2.0 * u2 - 1.0);
    const double sx = (cos_phi * slope_x - sin_phi * slope_y) * alpha_u_;
    const double sy = (sin_phi * slope_x + cos_phi * slope_y) * alpha_v_;
    return normalize(Vec3{-sx, -sy, 1.0});
}

} // namespace ppm
