// SPDX-License-Identifier: Apache-2.0
// BSDFs against closed forms: the Fresnel equations (normal incidence, Brewster's angle,
// total internal reflection, energy balance), the Lambert pdf, sampled albedos against the
// analytic ones, reciprocity, and the radiance/importance asymmetry of refraction.
#include "core/error.h"
#include "material/bsdf.h"
#include "math/sin_cos.h"
#include "math/warp.h"

#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <vector>

using namespace ppm;

namespace {

const double kPi = 3.14159265358979323846;
const double kDeg = kPi / 180.0;

// Unit direction at polar angle theta (from +z) and azimuth phi.
Vec3 direction(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

Vec3 flip(const Vec3 &w) { return {w.x, w.y, -w.z}; }

Vec3 random_upper(test_rng *rng) {
    const double z = test_rng_uniform(rng), phi = 2 * kPi * test_rng_uniform(rng);
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// Mean and standard error of a stream of per-channel samples.
struct Estimate {
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    long n = 0;
    void add(const Rgb &c) {
        const double v[3] = {c.r, c.g, c.b};
        for (int i = 0; i < 3; ++i) {
            sum[i] += v[i];
            sum2[i] += v[i] * v[i];
        }
        ++n;
    }
    double mean(int i) const { return sum[i] / n; }
    double standard_error(int i) const {
        const double m = mean(i);
        return std::sqrt(std::max(0.0, sum2[i] / n - m * m) / n);
    }
};

// Mean of the sampled weight f cos / pdf, i.e. the directional albedo, from 200k samples.
Estimate sampled_albedo(const Bsdf &bsdf, const Vec3 &wo, TransportMode mode, uint64_t seed) {
    test_rng rng{seed};
    Estimate e;
    for (int k = 0; k < 200000; ++k) {
        const double a = test_rng_uniform(&rng), b = test_rng_uniform(&rng), c = test_rng_uniform(&rng);
        const BsdfSample s = bsdf.sample(wo, a, b, c, mode);
        e.add(s.valid() ? s.weight : Rgb());
    }
    return e;
}

// Radiance-mode refraction out of a denser medium legitimately gains radiance (1/eta_t^2 > 1),
// so the <= 1 bound is optional.
void assert_albedo(const Estimate &e, const Rgb &expected, bool at_most_one = true) {
    const double want[3] = {expected.r, expected.g, expected.b};
    for (int i = 0; i < 3; ++i) {
        const double tolerance = 3 * e.standard_error(i) + 1e-12;
        if (at_most_one) assert_true(e.mean(i) <= 1 + tolerance);
        assert_close(e.mean(i), want[i], tolerance);
    }
}

Rgb base_of_texel() { return {0.7, 0.35, 0.05}; }

void expect_invalid_argument(void (*make)()) {
    try {
        make();
    } catch (const Error &e) {
        assert_int_equal(e.status(), PPM_ERROR_INVALID_ARGUMENT);
        return;
    }
    fail_msg("invalid material parameters were accepted");
}

void fresnel_at_normal_incidence(void **) {
    for (double eta : {1.0, 1.33, 1.5, 2.4, 0.7}) {
        const double expected = std::pow((1 - eta) / (1 + eta), 2);
        assert_close(fresnel_dielectric(1.0, eta), expected, 1e-16);
        assert_close(fresnel_dielectric(-1.0, eta), expected, 1e-16); // from inside
        const FresnelTerms t = fresnel_dielectric_terms(1.0, eta);
        assert_close(t.r_s, t.r_p, 1e-16);
        assert_close(t.cos_t, 1.0, 1e-16);
    }
    assert_close(fresnel_dielectric(1.0, 1.5), 0.04, 1e-16);
}

// Fresnel's sine and tangent laws: r_s = sin^2(i - t) / sin^2(i + t),
// r_p = tan^2(i - t) / tan^2(i + t), with Snell's law sin i = eta sin t.
void fresnel_matches_the_sine_and_tangent_laws(void **) {
    for (double eta : {1.33, 1.5, 2.4}) {
        for (double deg = 5; deg < 90; deg += 7) {
            const double i = deg * kDeg, t = std::asin(std::sin(i) / eta);
            const FresnelTerms f = fresnel_dielectric_terms(std::cos(i), eta);
            assert_close(f.r_s, std::pow(std::sin(i - t) / std::sin(i + t), 2), 1e-14);
            assert_close(f.r_p, std::pow(std::tan(i - t) / std::tan(i + t), 2), 1e-14);
            assert_close(f.cos_t, std::cos(t), 1e-14);
            // The same pair of angles seen from inside has the same reflectance.
            // (Near the critical angle cos t is ill-conditioned, hence the looser bound.)
            assert_close(fresnel_dielectric(-std::cos(t), eta), f.reflectance(), 1e-12);
        }
    }
}

// At Brewster's angle tan(i) = eta the p-polarised reflectance vanishes and i + t = 90
// degrees, so unpolarised R = r_s / 2 = sin^2(i - t) / 2 = cos^2(2 i) / 2.
void brewster_angle_reflects_only_s_polarisation(void **) {
    for (double eta : {1.33, 1.5, 2.4, 1 / 1.5}) {
        const double i = std::atan(eta);
        const FresnelTerms f = fresnel_dielectric_terms(std::cos(i), eta);
        assert_close(f.r_p, 0.0, 1e-15);
        assert_close(f.reflectance(), 0.5 * std::pow(std::cos(2 * i), 2), 1e-14);
        // r_p changes sign in amplitude there: it is positive on both sides.
        assert_true(fresnel_dielectric_terms(std::cos(i - 0.05), eta).r_p > 1e-6);
        assert_true(fresnel_dielectric_terms(std::cos(i + 0.05), eta).r_p > 1e-6);
    }
}

void total_internal_reflection_beyond_the_critical_angle(void **) {
    const double eta = 1.5; // glass in air; from inside the critical angle is asin(1/1.5)
    const double critical = std::asin(1 / eta);
    for (double d : {1e-9, 1e-3, 0.1, 0.5}) {
        const FresnelTerms f = fresnel_dielectric_terms(-std::cos(critical + d), eta);
        assert_true(f.r_s == 1 && f.r_p == 1 && f.cos_t == 0);
    }
    assert_true(fresnel_dielectric(-std::cos(critical - 1e-3), eta) < 1);
    assert_true(fresnel_dielectric(-std::cos(critical - 1e-8), eta) > 0.99); // continuous
    // Never from outside into the denser medium.
    assert_true(fresnel_dielectric(std::cos(89.9 * kDeg), eta) < 1);
    // A glass sample beyond the critical angle always reflects, with weight 1.
    const Bsdf glass = Bsdf::dielectric(1.5, 1.0);
    const Vec3 wo = direction(kPi - (critical + 0.01), 0.3);
    for (double u : {0.0, 0.5, 0.999999}) {
        const BsdfSample s = glass.sample(wo, u, 0.5, 0.5, TransportMode::Radiance);
        assert_true(s.valid() && s.is_specular);
        assert_close(s.pdf, 1.0, 0);
        assert_close(s.wi.z, wo.z, 1e-15);
        assert_close(s.weight.g, 1.0, 0);
    }
}

// Energy at the boundary from the transmission amplitudes t_s = 2 cos i / (cos i + eta cos t),
// t_p = 2 cos i / (eta cos i + cos t): T = eta cos t / cos i * t^2 and R + T = 1 per
// polarisation.
void fresnel_conserves_energy(void **) {
    for (double eta : {1.33, 1.5, 2.4, 0.8}) {
        for (double deg = 0; deg < 90; deg += 3) {
            const double ci = std::cos(deg * kDeg);
            const FresnelTerms f = fresnel_dielectric_terms(ci, eta);
            if (f.cos_t == 0) continue; // total internal reflection (eta < 1)
            const double ts = 2 * ci / (ci + eta * f.cos_t), tp = 2 * ci / (eta * ci + f.cos_t);
            const double ratio = eta * f.cos_t / ci;
            assert_close(f.r_s + ratio * ts * ts, 1.0, 1e-14);
            assert_close(f.r_p + ratio * tp * tp, 1.0, 1e-14);
        }
    }
}

// Hemispherical Fresnel averages: brute-force midpoint sums, and the reciprocity identity
// 1 - Fdr(1/eta) = (1 - Fdr(eta)) / eta^2 between the two sides of a boundary.
void diffuse_fresnel_reflectance_is_consistent(void **) {
    for (double eta : {1.33, 1.5, 2.4}) {
        const double outside = fresnel_diffuse_reflectance(eta);
        const double inside = fresnel_diffuse_reflectance(1 / eta);
        assert_close(1 - inside, (1 - outside) / (eta * eta), 2e-9);
        for (double e : {eta, 1 / eta}) {
            const int n = 200000;
            double sum = 0;
            for (int k = 0; k < n; ++k) {
                const double mu = (k + 0.5) / n;
                sum += 2 * fresnel_dielectric(mu, e) * mu / n;
            }
            assert_close(fresnel_diffuse_reflectance(e), sum, 1e-7);
        }
    }
    assert_close(fresnel_diffuse_reflectance(1.0), 0.0, 1e-15);
    // Glass: about 9.2 % of diffuse light is reflected from outside, 60 % from inside.
    assert_close(fresnel_diffuse_reflectance(1.5), 0.0918, 5e-4);
    assert_close(fresnel_diffuse_reflectance(1 / 1.5), 0.596, 1e-3);
}

// The Lambert pdf integrates to one over the hemisphere (uniform-sampling estimate), and
// the coated base's to its lobe probability.
void non_specular_pdfs_integrate_to_their_lobe_probability(void **) {
    const Bsdf lambert = Bsdf::diffuse({0.2, 0.5, 0.9});
    const Bsdf coated = Bsdf::coated({0.8, 0.7, 0.6}, 1.5, 1.0);
    test_rng rng{3};
    const Vec3 wo = direction(40 * kDeg, 1.0);
    const int n = 200000;
    double sum_l = 0, sum2_l = 0, sum_c = 0;
    for (int k = 0; k < n; ++k) {
        const Vec3 wi = random_upper(&rng);
        const double pl = lambert.pdf(wo, wi) * 2 * kPi; // / uniform pdf 1/(2 pi)
        sum_l += pl;
        sum2_l += pl * pl;
        sum_c += coated.pdf(wo, wi) * 2 * kPi;
        assert_close(lambert.pdf(wo, -wi), 0.0, 0);
    }
    const double mean_l = sum_l / n, se = std::sqrt((sum2_l / n - mean_l * mean_l) / n);
    assert_close(mean_l, 1.0, 3 * se);
    // Sampling the coated base: the fraction of diffuse samples is its lobe probability.
    int diffuse_samples = 0;
    for (int k = 0; k < n; ++k) {
        const BsdfSample s = coated.sample(wo, test_rng_uniform(&rng), 0.3, 0.6, TransportMode::Radiance);
        diffuse_samples += s.is_specular ? 0 : 1;
    }
    const double p = double(diffuse_samples) / n;
    assert_close(sum_c / n, p, 3 * std::sqrt(p * (1 - p) / n) + 3 * se);
    assert_true(p > 0.5 && p < 1);
}

// A non-specular sample reports the same pdf as pdf() and weight = f cos / pdf.
void samples_agree_with_eval_and_pdf(void **) {
    const Bsdf materials[] = {Bsdf::diffuse({0.2, 0.5, 0.9}), Bsdf::coated({0.8, 0.7, 0.1}, 1.5, 1.0),
                              Bsdf::coated({0.3, 0.3, 0.3}, 1.33, 1.1)};
    test_rng rng{5};
    for (const Bsdf &bsdf : materials) {
        int checked = 0;
        for (int k = 0; k < 20000; ++k) {
            Vec3 wo = random_upper(&rng);
            if (k % 2) wo.z = -wo.z; // both sides
            const BsdfSample s = bsdf.sample(wo, test_rng_uniform(&rng), test_rng_uniform(&rng), test_rng_uniform(&rng),
                                             TransportMode::Radiance);
            assert_true(s.valid());
            assert_true(s.wi.z * wo.z > 0); // reflection stays on wo's side
            assert_close(length(s.wi), 1.0, 1e-14);
            if (s.is_specular) {
                assert_close(s.wi.z, wo.z, 0);
                assert_close(s.wi.x, -wo.x, 0);
                continue;
            }
            ++checked;
            assert_close(s.pdf, bsdf.pdf(wo, s.wi), 1e-12 * s.pdf);
            const Rgb expected = bsdf.eval(wo, s.wi) * (std::fabs(s.wi.z) / s.pdf);
            assert_close(s.weight.r, expected.r, 1e-12);
            assert_close(s.weight.g, expected.g, 1e-12);
            assert_close(s.weight.b, expected.b, 1e-12);
        }
        assert_true(checked > 10000);
    }
}

const double kCosines[] = {1.0, 0.7, 0.3, 0.05};

void diffuse_and_mirror_albedo_is_their_reflectance(void **) {
    const Rgb reflectance{0.25, 0.5, 1.0};
    const Bsdf diffuse = Bsdf::diffuse(reflectance), mirror = Bsdf::mirror(reflectance);
    for (double c : kCosines) {
        for (double side : {1.0, -1.0}) {
            const Vec3 wo{std::sqrt(1 - c * c), 0, side * c};
            assert_albedo(sampled_albedo(diffuse, wo, TransportMode::Radiance, 1), reflectance);
            assert_albedo(sampled_albedo(mirror, wo, TransportMode::Importance, 2), reflectance);
        }
    }
}

// Coat over a diffuse base: albedo F + (1 - F) R_d (see material/bsdf.h).
void coated_albedo_is_fresnel_plus_transmitted_base(void **) {
    for (double eta : {1.5, 1.33}) {
        const Rgb base{0.9, 0.5, 0.0};
        const Bsdf coated = Bsdf::coated(base, eta, 1.0);
        for (double c : kCosines) {
            for (double side : {1.0, -1.0}) {
                const Vec3 wo{0, std::sqrt(1 - c * c), side * c};
                const double f = fresnel_dielectric(c, eta);
                const Rgb expected = Rgb(f) + base * (1 - f);
                assert_albedo(sampled_albedo(coated, wo, TransportMode::Radiance, 3), expected);
                assert_albedo(sampled_albedo(coated, wo, TransportMode::Importance, 4), expected);
            }
        }
    }
    // A white base conserves all energy, a black one keeps only the coat's reflection.
    const Vec3 wo = direction(60 * kDeg, 0);
    assert_albedo(sampled_albedo(Bsdf::coated(Rgb(1.0), 1.5, 1.0), wo, TransportMode::Radiance, 5), Rgb(1.0));
    const double f = fresnel_dielectric(wo.z, 1.5);
    assert_albedo(sampled_albedo(Bsdf::coated(Rgb(0.0), 1.5, 1.0), wo, TransportMode::Radiance, 6), Rgb(f));
}

// A nonlinear coat (Mitsuba's nonlinear = true): light that entered bounces between the base
// and the coat's inside, leaving with 1 - Fdr_int each time, so the diffuse albedo is the
// geometric series (1 - F) R_d (1 - Fdr_int) sum (R_d Fdr_int)^k, Fdr_int the internal
// diffuse reflectance (Fdr at 1 / eta).
void nonlinear_coated_albedo_sums_the_internal_bounces(void **) {
    for (double eta : {1.5, 1.33}) {
        const Rgb base{0.9, 0.5, 0.1};
        const Bsdf coated = Bsdf::coated(base, eta, 1.0, true);
        const double inside = fresnel_diffuse_reflectance(1 / eta);
        for (double c : kCosines) {
            const Vec3 wo{0, std::sqrt(1 - c * c), c};
            const double f = fresnel_dielectric(c, eta);
            const auto diffuse = [&](double d) { return (1 - f) * d * (1 - inside) / (1 - d * inside); };
            const Rgb expected(f + diffuse(base.r), f + diffuse(base.g), f + diffuse(base.b));
            assert_albedo(sampled_albedo(coated, wo, TransportMode::Radiance, 8), expected);
            assert_albedo(sampled_albedo(coated, wo, TransportMode::Importance, 9), expected);
        }
    }
    // A white base is the same either way; a texel goes through the same bounces.
    const Vec3 wo = direction(40 * kDeg, 0), wi = direction(20 * kDeg, 1);
    assert_close(Bsdf::coated(Rgb(1.0), 1.5, 1.0, true).eval(wo, wi).g, Bsdf::coated(Rgb(1.0), 1.5, 1.0).eval(wo, wi).g,
                 1e-12);
    const Bsdf textured = Bsdf::coated(Rgb(0.2), 1.5, 1.0, true).with_reflectance(base_of_texel());
    assert_close(textured.eval(wo, wi).r, Bsdf::coated(base_of_texel(), 1.5, 1.0, true).eval(wo, wi).r, 1e-15);
    // Rough plastic: the base lobe scales by (1 - R_int) / (1 - R_d R_int), R_int its table's.
    const double d = 0.6;
    const Bsdf rough = Bsdf::rough_plastic(Rgb(d), MicrofacetType::Beckmann, 0.3, 1.5, 1.0, true, true);
    const Bsdf linear = Bsdf::rough_plastic(Rgb(d), MicrofacetType::Beckmann, 0.3, 1.5, 1.0, true, false);
    const Bsdf black = Bsdf::rough_plastic(Rgb(0.0), MicrofacetType::Beckmann, 0.3, 1.5, 1.0, true, false);
    const double r_int = linear.rough_coat_internal_reflectance();
    const double coat = black.eval(wo, wi).b;
    assert_close(rough.eval(wo, wi).b - coat, (linear.eval(wo, wi).b - coat) * (1 - r_int) / (1 - d * r_int), 1e-12);
}

// specular_reflectance S scales the coats' reflection (Mitsuba's plastic and roughplastic):
// over a black base the albedo is S F (smooth coat) and S times the coat's albedo (rough),
// per channel, and the base lobe does not change; sampling steers by mean(S) against the
// base's mean, so a grey S = 0 never samples the coat.
void specular_reflectance_scales_the_coat(void **) {
    const Rgb s{0.2, 0.5, 0.9};
    for (double c : kCosines) {
        const Vec3 wo{0, std::sqrt(1 - c * c), c};
        const double f = fresnel_dielectric(c, 1.5);
        // Over a black base every sample takes the coat: the weight is S F exactly.
        const Estimate smooth =
            sampled_albedo(Bsdf::coated(Rgb(0.0), 1.5, 1.0, false, s), wo, TransportMode::Radiance, 11);
        for (int i = 0; i < 3; ++i) assert_close(smooth.mean(i), (i == 0 ? s.r : i == 1 ? s.g : s.b) * f, 1e-9);
        // The same samples (the coat is always picked over a black base): exactly S times.
        const Estimate white =
            sampled_albedo(Bsdf::rough_plastic(Rgb(0.0), MicrofacetType::GGX, 0.3, 1.5, 1.0, true, false), wo,
                           TransportMode::Radiance, 12);
        const Rgb rough_white(white.mean(0), white.mean(1), white.mean(2));
        assert_albedo(sampled_albedo(Bsdf::rough_plastic(Rgb(0.0), MicrofacetType::GGX, 0.3, 1.5, 1.0, true, false, s),
                                     wo, TransportMode::Radiance, 12),
                      Rgb(s.r * rough_white.r, s.g * rough_white.g, s.b * rough_white.b));
    }
    const Vec3 wo = direction(40 * kDeg, 0), wi = direction(20 * kDeg, 1);
    const Bsdf plain = Bsdf::rough_plastic(Rgb(0.4), MicrofacetType::Beckmann, 0.3, 1.5, 1.0);
    const Bsdf tinted = Bsdf::rough_plastic(Rgb(0.4), MicrofacetType::Beckmann, 0.3, 1.5, 1.0, true, false, s);
    const Bsdf black = Bsdf::rough_plastic(Rgb(0.0), MicrofacetType::Beckmann, 0.3, 1.5, 1.0);
    const double coat = black.eval(wo, wi).g;
    assert_close(tinted.eval(wo, wi).g, plain.eval(wo, wi).g - coat + s.g * coat, 1e-12);
    const Bsdf matte = Bsdf::coated(Rgb(0.5), 1.5, 1.0, false, Rgb(0.0));
    for (double u : {0.0, 0.3, 0.999}) assert_false(matte.sample(wo, u, 0.4, 0.6, TransportMode::Radiance).is_specular);
    expect_invalid_argument([] { Bsdf::coated(Rgb(0.5), 1.5, 1.0, false, Rgb(1.5)); });
}

// Glass: in importance (photon) mode every sample carries weight 1, so R + T = 1 and the
// reflected fraction is R; in radiance mode transmission is scaled by 1/eta_t^2.
void glass_conserves_energy_in_importance_mode(void **) {
    for (double eta : {1.5, 1.33, 2.4}) {
        const Bsdf glass = Bsdf::dielectric(eta, 1.0);
        for (double c : kCosines) {
            for (double side : {1.0, -1.0}) {
                const Vec3 wo{std::sqrt(1 - c * c), 0, side * c};
                const double r = fresnel_dielectric(wo.z, eta);
                assert_albedo(sampled_albedo(glass, wo, TransportMode::Importance, 7), Rgb(1.0));
                const double eta_t = side > 0 ? eta : 1 / eta;
                assert_albedo(sampled_albedo(glass, wo, TransportMode::Radiance, 8), Rgb(r + (1 - r) / (eta_t * eta_t)),
                              false);
                // Reflected fraction against R (binomial 3 sigma).
                test_rng rng{9};
                const int n = 100000;
                int reflected = 0;
                for (int k = 0; k < n; ++k) {
                    const BsdfSample s = glass.sample(wo, test_rng_uniform(&rng), 0, 0, TransportMode::Importance);
                    reflected += s.wi.z * wo.z > 0 ? 1 : 0;
                }
                assert_close(double(reflected) / n, r, 3 * std::sqrt(r * (1 - r) / n) + 1e-12);
            }
        }
    }
}

// Refracted directions obey Snell's law, stay in the plane of incidence, and the two modes
// differ exactly by eta_t^2 on transmission.
void glass_refraction_follows_snell(void **) {
    const double eta = 1.5;
    const Bsdf glass = Bsdf::dielectric(eta, 1.0);
    for (double deg = 0; deg < 90; deg += 10) {
        for (double side : {1.0, -1.0}) {
            Vec3 wo = direction(deg * kDeg, 0.7);
            wo.z *= side;
            const double eta_t = side > 0 ? eta : 1 / eta;
            if (std::sin(deg * kDeg) / eta_t >= 1) continue; // total internal reflection
            const double r = fresnel_dielectric(wo.z, eta);
            const BsdfSample rad = glass.sample(wo, 0.999999, 0, 0, TransportMode::Radiance);
            const BsdfSample imp = glass.sample(wo, 0.999999, 0, 0, TransportMode::Importance);
            assert_true(rad.is_specular && rad.wi.z * wo.z < 0);
            assert_close(length(rad.wi), 1.0, 1e-15);
            const double sin_i = std::hypot(wo.x, wo.y), sin_t = std::hypot(rad.wi.x, rad.wi.y);
            assert_close(sin_i, eta_t * sin_t, 1e-14);
            assert_close(rad.wi.x * wo.y - rad.wi.y * wo.x, 0.0, 1e-15); // same plane
            assert_true(rad.wi.x * wo.x + rad.wi.y * wo.y <= 0);         // continues across
            assert_close(rad.pdf, 1 - r, 1e-15);
            assert_close(rad.weight.r * eta_t * eta_t, imp.weight.r, 1e-15);
            assert_close(imp.weight.r, 1.0, 0);
            assert_close(glass.eval(wo, rad.wi).g, 0.0, 0); // delta lobes only
            assert_close(glass.pdf(wo, rad.wi), 0.0, 0);
        }
    }
    // Index matched: light passes straight through.
    const Vec3 wo = direction(0.6, 2.0);
    const BsdfSample s = Bsdf::dielectric(1.2, 1.2).sample(wo, 0.3, 0, 0, TransportMode::Radiance);
    assert_close(s.wi.x, -wo.x, 1e-15);
    assert_close(s.wi.y, -wo.y, 1e-15);
    assert_close(s.wi.z, -wo.z, 1e-15);
    assert_close(s.weight.r, 1.0, 1e-15);
}

void non_specular_parts_are_reciprocal(void **) {
    const Bsdf materials[] = {Bsdf::diffuse({0.2, 0.5, 0.9}), Bsdf::coated({0.8, 0.7, 0.1}, 1.5, 1.0),
                              Bsdf::coated({0.4, 0.4, 0.4}, 1.33, 1.1)};
    test_rng rng{13};
    for (const Bsdf &bsdf : materials) {
        for (int k = 0; k < 5000; ++k) {
            Vec3 a = random_upper(&rng), b = random_upper(&rng);
            if (k % 2) {
                a.z = -a.z;
                b.z = -b.z;
            }
            const Rgb ab = bsdf.eval(a, b), ba = bsdf.eval(b, a);
            assert_true(ab.min() > 0);
            assert_close(ab.r, ba.r, 1e-15 * ab.max());
            assert_close(ab.g, ba.g, 1e-15 * ab.max());
            assert_close(ab.b, ba.b, 1e-15 * ab.max());
            // Opposite sides never connect through an opaque surface.
            assert_true(bsdf.eval(a, flip(b)).is_black());
        }
    }
}

// The photon pass evaluates each visible point's BSDF through fixed_wo(): it must agree with
// eval() (times the weight) for every type, side and wi, and be black where eval is.
void fixed_wo_lobe_matches_eval(void **) {
    const Bsdf materials[] = {Bsdf::diffuse({0.2, 0.5, 0.9}), Bsdf::coated({0.8, 0.7, 0.1}, 1.5, 1.0),
                              Bsdf::coated({0.4, 0.4, 0.4}, 1.0 / 1.33, 1.0), Bsdf::mirror(Rgb(0.9)),
                              Bsdf::dielectric(1.5, 1.0)};
    const Rgb weight{0.5, 2.0, 1.25};
    test_rng rng{17};
    for (const Bsdf &bsdf : materials) {
        for (int k = 0; k < 5000; ++k) {
            Vec3 wo = random_upper(&rng), wi = random_upper(&rng);
            if (k % 2) wo = flip(wo);
            if (k % 3 == 0) wi = flip(wi);
            const FixedWoLobe lobe = bsdf.fixed_wo(wo, weight);
            const Rgb expected = weight * bsdf.eval(wo, wi);
            const Rgb actual = lobe.at(wo.z > 0 ? wi.z : -wi.z);
            assert_close(actual.r, expected.r, 1e-15 * (1 + expected.max()));
            assert_close(actual.g, expected.g, 1e-15 * (1 + expected.max()));
            assert_close(actual.b, expected.b, 1e-15 * (1 + expected.max()));
            assert_true(actual.is_black() == expected.is_black());
        }
        assert_true(bsdf.fixed_wo({1, 0, 0}, weight).at(0.5).is_black()); // grazing wo
    }
}

void back_side_of_opaque_materials_mirrors_the_front(void **) {
    const Bsdf coated = Bsdf::coated({0.5, 0.6, 0.7}, 1.5, 1.0);
    const Vec3 wo = direction(30 * kDeg, 0.4), wi = direction(70 * kDeg, 2.5);
    const Vec3 wo_back{wo.x, wo.y, -wo.z}, wi_back{wi.x, wi.y, -wi.z};
    assert_close(coated.eval(wo_back, wi_back).g, coated.eval(wo, wi).g, 0);
    assert_close(coated.pdf(wo_back, wi_back), coated.pdf(wo, wi), 0);
    const BsdfSample front = coated.sample(wo, 0.9, 0.2, 0.7, TransportMode::Radiance);
    const BsdfSample back = coated.sample(wo_back, 0.9, 0.2, 0.7, TransportMode::Radiance);
    assert_close(back.wi.z, -front.wi.z, 0);
    assert_close(back.weight.b, front.weight.b, 0);
    // Grazing wo (cos = 0) scatters nothing.
    for (const Bsdf &b : {coated, Bsdf::diffuse(Rgb(0.5)), Bsdf::mirror(Rgb(1.0)), Bsdf::dielectric(1.5, 1)})
        assert_false(b.sample({1, 0, 0}, 0.5, 0.5, 0.5, TransportMode::Radiance).valid());
}

void with_reflectance_keeps_the_coat(void **) {
    const Bsdf a = Bsdf::coated({0.1, 0.2, 0.3}, 1.5, 1.0);
    const Bsdf b = a.with_reflectance({0.6, 0.6, 0.6});
    const Bsdf c = Bsdf::coated({0.6, 0.6, 0.6}, 1.5, 1.0);
    const Vec3 wo = direction(0.5, 0), wi = direction(1.0, 2);
    assert_close(b.eval(wo, wi).r, c.eval(wo, wi).r, 0);
    assert_close(b.pdf(wo, wi), c.pdf(wo, wi), 0);
    assert_true(a.has_non_specular() && !Bsdf::mirror(Rgb(1)).has_non_specular() &&
                !Bsdf::dielectric(1.5, 1).has_non_specular());
}

// The warps' sine and cosine (math/sin_cos.h) against libm, on a dense sweep and at the octant
// boundaries where the reduction switches branches. For 2 pi u the reference angle is itself
// rounded (half an ulp of 2 pi is 4.4e-16), which the second bound allows for.
void warp_sine_and_cosine_match_libm(void **) {
    const auto difference = [](double angle, double s, double c) {
        return std::max(std::fabs(s - std::sin(angle)), std::fabs(c - std::cos(angle)));
    };
    double worst_quarter = 0, worst_turn = 0;
    for (int i = 0; i <= 200000; ++i) {
        const double x = (i / 100000.0 - 1.0) * (kPi / 4);
        double s, c;
        sin_cos_quarter(x, &s, &c);
        worst_quarter = std::max(worst_quarter, difference(x, s, c));
    }
    std::vector<double> us;
    for (int i = 0; i < 400000; ++i) us.push_back(i / 400000.0 + 0.3e-6);
    for (int k = 0; k <= 8; ++k) {
        us.push_back(std::nextafter(k / 8.0, 0.0));
        us.push_back(k / 8.0);
        us.push_back(std::nextafter(k / 8.0, 1.0));
    }
    for (double u : us) {
        if (!(u >= 0 && u < 1)) continue;
        double s, c;
        sin_cos_2pi(u, &s, &c);
        worst_turn = std::max(worst_turn, difference(2 * kPi * u, s, c));
    }
    print_message("largest difference from libm: %.3g within pi/4, %.3g for 2 pi u\n", worst_quarter, worst_turn);
    assert_true(worst_quarter < 2.5e-16);
    assert_true(worst_turn < 1e-15);
}

void invalid_parameters_are_rejected(void **) {
    expect_invalid_argument([] { Bsdf::diffuse({0.5, -0.1, 0.5}); });
    expect_invalid_argument([] { Bsdf::diffuse({0.5, 1.2, 0.5}); });
    expect_invalid_argument([] { Bsdf::diffuse({std::nan(""), 0.5, 0.5}); });
    expect_invalid_argument([] { Bsdf::mirror({0.5, 0.5, INFINITY}); });
    expect_invalid_argument([] { Bsdf::dielectric(0.0, 1.0); });
    expect_invalid_argument([] { Bsdf::dielectric(1.5, -1.0); });
    expect_invalid_argument([] { Bsdf::dielectric(std::nan(""), 1.0); });
    expect_invalid_argument([] { Bsdf::dielectric(INFINITY, 1.0); });
    expect_invalid_argument([] { Bsdf::coated(Rgb(0.5), 1.5, 0.0); });
    expect_invalid_argument([] { Bsdf::coated(Rgb(2.0), 1.5, 1.0); });
}

} // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(fresnel_at_normal_incidence),
        cmocka_unit_test(fresnel_matches_the_sine_and_tangent_laws),
        cmocka_unit_test(brewster_angle_reflects_only_s_polarisation),
        cmocka_unit_test(total_internal_reflection_beyond_the_critical_angle),
        cmocka_unit_test(fresnel_conserves_energy),
        cmocka_unit_test(diffuse_fresnel_reflectance_is_consistent),
        cmocka_unit_test(non_specular_pdfs_integrate_to_their_lobe_probability),
        cmocka_unit_test(samples_agree_with_eval_and_pdf),
        cmocka_unit_test(diffuse_and_mirror_albedo_is_their_reflectance),
        cmocka_unit_test(coated_albedo_is_fresnel_plus_transmitted_base),
        cmocka_unit_test(glass_conserves_energy_in_importance_mode),
        cmocka_unit_test(glass_refraction_follows_snell),
        cmocka_unit_test(non_specular_parts_are_reciprocal),
        cmocka_unit_test(fixed_wo_lobe_matches_eval),
        cmocka_unit_test(back_side_of_opaque_materials_mirrors_the_front),
        cmocka_unit_test(with_reflectance_keeps_the_coat),
        cmocka_unit_test(nonlinear_coated_albedo_sums_the_internal_bounces),
        cmocka_unit_test(specular_reflectance_scales_the_coat),
        cmocka_unit_test(warp_sine_and_cosine_match_libm),
        cmocka_unit_test(invalid_parameters_are_rejected),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
