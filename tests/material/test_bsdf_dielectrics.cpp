// SPDX-License-Identifier: Apache-2.0
// The dielectric family (thin sheet, rough interface, rough plastic) against closed forms and
// against itself: the thin sheet's R' = 2R / (1 + R) and R' + T' = 1, white-furnace albedos
// (<= 1, near 1 for a smooth-ish interface in Importance mode), sampled albedos against a
// quadrature of f cos (eval and sample agree), chi-square fits of sample() to pdf(), the
// adjoint and generalised reciprocity of refraction, and the rough coat's tables.
#include "core/error.h"
#include "material/bsdf.h"
#include "material/microfacet.h"

#include "chi2.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace ppm;

namespace {

const double kPi = 3.14159265358979323846;
const double kIntIor = 1.5046, kExtIor = 1.000277; // Mitsuba's defaults for glass

Vec3 direction(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

struct Estimate {
    double sum = 0, sum2 = 0;
    long n = 0;
    void add(double x) { sum += x, sum2 += x * x, ++n; }
    double mean() const { return sum / n; }
    double error() const { return std::sqrt(std::max(0.0, sum2 / n - mean() * mean()) / n); }
};

// Mean of sample() weights (channel r) over n samples: the albedo at wo.
Estimate sampled_albedo(const Bsdf &b, const Vec3 &wo, TransportMode mode, long n, uint64_t seed) {
    test_rng rng{seed};
    Estimate e;
    for (long k = 0; k < n; ++k) {
        const double u0 = test_rng_uniform(&rng), u1 = test_rng_uniform(&rng), u2 = test_rng_uniform(&rng);
        const BsdfSample s = b.sample(wo, u0, u1, u2, mode);
        e.add(s.valid() ? s.weight.r : 0.0);
    }
    return e;
}

// Midpoint rule over (theta, phi) on the whole sphere of g(w) dw.
template <class F> double sphere_integral(int nt, int np, F &&g) {
    double sum = 0;
    const double dt = kPi / nt, dp = 2 * kPi / np;
    for (int i = 0; i < nt; ++i) {
        const double t = (i + 0.5) * dt, st = std::sin(t);
        for (int j = 0; j < np; ++j) sum += g(direction(t, (j + 0.5) * dp)) * st;
    }
    return sum * dt * dp;
}

void expect_invalid_argument(void (*make)()) {
    try {
        make();
    } catch (const Error &e) {
        assert_int_equal(e.status(), PPM_ERROR_INVALID_ARGUMENT);
        return;
    }
    fail_msg("invalid material parameters were accepted");
}

// ---- thindielectric ---------------------------------------------------------------------

void thin_dielectric_sums_the_internal_bounces(void **) {
    const Bsdf b = Bsdf::thin_dielectric(kIntIor, kExtIor);
    for (double theta : {0.0, 0.3, 0.8, 1.2, 1.5})
        for (double side : {1.0, -1.0}) {
            Vec3 wo = direction(theta, 0.7);
            wo.z *= side;
            const double r = fresnel_dielectric(std::fabs(wo.z), kIntIor / kExtIor), t = 1 - r;
            const double expected = r + t * t * r / (1 - r * r);
            assert_true(std::fabs(b.thin_dielectric_reflectance(wo.z) - expected) < 1e-14);
            for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                const BsdfSample refl = b.sample(wo, 0.0, 0.5, 0.5, mode);
                const BsdfSample trans = b.sample(wo, 1.0 - 1e-16, 0.5, 0.5, mode);
                assert_true(refl.valid() && trans.valid() && refl.is_specular && trans.is_specular);
                // White furnace: the lobes' probabilities are their energies and sum to 1 exactly.
                assert_true(refl.weight.r == 1.0 && trans.weight.r == 1.0);
                assert_true(std::fabs(refl.pdf - expected) < 1e-14);
                assert_true(refl.pdf + trans.pdf == 1.0);
                assert_true(refl.wi.x == -wo.x && refl.wi.y == -wo.y && refl.wi.z == wo.z);
                assert_true(trans.wi.x == -wo.x && trans.wi.y == -wo.y && trans.wi.z == -wo.z); // straight through
            }
            assert_true(b.eval(wo, -wo).is_black() && b.pdf(wo, -wo) == 0);
        }
    // Normal incidence closed form: R0 = ((n - 1) / (n + 1))^2.
    const double n = kIntIor / kExtIor, r0 = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
    assert_true(std::fabs(b.thin_dielectric_reflectance(1.0) - 2 * r0 / (1 + r0)) < 1e-14);
    assert_false(b.has_non_specular());
    assert_true(b.specular_probability({0, 0, 1}) == 1.0);
}

// ---- roughdielectric --------------------------------------------------------------------

struct RoughConfig {
    MicrofacetType type;
    double alpha_u, alpha_v;
    bool visible;
};
const RoughConfig kRough[] = {
    {MicrofacetType::Beckmann, 0.2, 0.2, true},  {MicrofacetType::GGX, 0.2, 0.2, true},
    {MicrofacetType::Beckmann, 0.5, 0.5, true},  {MicrofacetType::GGX, 0.3, 0.6, true},
    {MicrofacetType::Beckmann, 0.3, 0.3, false}, {MicrofacetType::GGX, 0.4, 0.2, false},
};

void rough_dielectric_albedo_is_at_most_one(void **) {
    for (MicrofacetType type : {MicrofacetType::Beckmann, MicrofacetType::GGX})
        for (double alpha : {0.02, 0.1, 0.5})
            for (double theta : {0.0, 0.5, 1.0, 1.3})
                for (double side : {1.0, -1.0}) {
                    const Bsdf b = Bsdf::rough_dielectric(type, alpha, alpha, kIntIor, kExtIor);
                    Vec3 wo = direction(theta, 0.3);
                    wo.z *= side;
                    const Estimate e = sampled_albedo(b, wo, TransportMode::Importance, 100000, 3);
                    printf("%s alpha %.2f theta %.1f side %+.0f: albedo %.4f +- %.4f\n", microfacet_type_name(type),
                           alpha, theta, side, e.mean(), e.error());
                    assert_true(e.mean() <= 1 + 4 * e.error() + 1e-12);
                    // Little is lost to the single-scattering model at low roughness; more at
                    // grazing angles and high roughness (the missing multiple scattering).
                    if (alpha <= 0.02) assert_true(e.mean() > 0.99);
                    if (alpha <= 0.1 && theta <= 1.0) assert_true(e.mean() > 0.95);
                }
}

void rough_dielectric_radiance_mode_scales_transmission(void **) {
    // Importance minus Radiance weights: transmission is scaled by 1/eta'^2, reflection not.
    const Bsdf b = Bsdf::rough_dielectric(MicrofacetType::GGX, 0.2, 0.2, kIntIor, kExtIor);
    const double eta = kIntIor / kExtIor;
    test_rng rng{5};
    for (int k = 0; k < 2000; ++k) {
        const double u0 = test_rng_uniform(&rng), u1 = test_rng_uniform(&rng), u2 = test_rng_uniform(&rng);
        Vec3 wo = direction(1.2 * test_rng_uniform(&rng), 6 * test_rng_uniform(&rng));
        if (k % 2) wo.z = -wo.z;
        const BsdfSample r = b.sample(wo, u0, u1, u2, TransportMode::Radiance);
        const BsdfSample i = b.sample(wo, u0, u1, u2, TransportMode::Importance);
        assert_true(r.valid() == i.valid());
        if (!r.valid()) continue;
        assert_true(r.wi.x == i.wi.x && r.wi.z == i.wi.z && r.pdf == i.pdf && !r.is_specular);
        const bool transmitted = r.wi.z * wo.z < 0;
        const double eta_t = wo.z > 0 ? eta : 1 / eta; // n(wi side) / n(wo side)
        const double expected = transmitted ? 1 / (eta_t * eta_t) : 1.0;
        assert_true(std::fabs(r.weight.r - expected * i.weight.r) <= 1e-12 * i.weight.r);
        const Rgb fr = b.eval(wo, r.wi, TransportMode::Radiance), fi = b.eval(wo, r.wi, TransportMode::Importance);
        assert_true(std::fabs(fr.r - expected * fi.r) <= 1e-12 * fi.r);
    }
}

void rough_dielectric_refraction_is_reciprocal(void **) {
    const double eta = kIntIor / kExtIor;
    for (const RoughConfig &c : kRough) {
        const Bsdf b = Bsdf::rough_dielectric(c.type, c.alpha_u, c.alpha_v, kIntIor, kExtIor, c.visible);
        test_rng rng{9};
        int checked = 0;
        for (int k = 0; k < 4000; ++k) {
            const Vec3 wo = direction(1.5 * test_rng_uniform(&rng), 6.28 * test_rng_uniform(&rng));
            Vec3 wi = direction(1.5 * test_rng_uniform(&rng), 6.28 * test_rng_uniform(&rng));
            if (k % 2) wi.z = -wi.z;                        // half reflection, half refraction
            const double n_o = 1, n_i = wi.z < 0 ? eta : 1; // indices of wo's and wi's media
            const Rgb f_oi = b.eval(wo, wi, TransportMode::Radiance), f_io = b.eval(wi, wo, TransportMode::Radiance);
            const Rgb adjoint = b.eval(wi, wo, TransportMode::Importance);
            // Adjoint: f*(wo, wi) = f(wi, wo); generalised (Veach 1997, eq. 5.15):
            // f(wo, wi) / n_o^2 = f(wi, wo) / n_i^2 for radiance.
            assert_true(std::fabs(f_oi.r - adjoint.r) <= 1e-10 * std::max(1.0, f_oi.r));
            assert_true(std::fabs(f_oi.r / (n_o * n_o) - f_io.r / (n_i * n_i)) <= 1e-10 * std::max(1.0, f_oi.r));
            checked += f_oi.r > 0;
        }
        assert_true(checked > 1000);
    }
}

void rough_dielectric_samples_follow_pdf(void **) {
    for (const RoughConfig &c : kRough)
        for (double theta : {0.4, 1.2})
            for (double side : {1.0, -1.0}) {
                const Bsdf b = Bsdf::rough_dielectric(c.type, c.alpha_u, c.alpha_v, kIntIor, kExtIor, c.visible);
                Vec3 wo = direction(theta, 0.9);
                wo.z *= side;
                ppm_test::Chi2Options opt;
                opt.samples = 200000;
                // The refracted lobe's density is steep near its edge: a finer rule for the bins.
                opt.quadrature = 64;
                const ppm_test::Chi2Result r = ppm_test::chi2_test(
                    [&](double u0, double u1, double u2, Vec3 *w) {
                        const BsdfSample s = b.sample(wo, u0, u1, u2, TransportMode::Radiance);
                        *w = s.wi;
                        return s.valid();
                    },
                    [&](const Vec3 &w) { return b.pdf(wo, w); }, opt);
                printf("roughdielectric %s (%g, %g) visible %d theta %.1f side %+.0f: chi2 %.1f dof %d p %.3g "
                       "(integral %.5f)\n",
                       microfacet_type_name(c.type), c.alpha_u, c.alpha_v, c.visible, theta, side, r.statistic, r.dof,
                       r.p_value, r.pdf_integral);
                assert_true(r.p_value > 1e-4);
            }
}

// E[weight] of sample() against the midpoint rule of the integral of f |cos wi| over the sphere.
void check_sampled_albedo_against_quadrature(const Bsdf &b, const Vec3 &wo, TransportMode mode, const char *what) {
    const double quadrature =
        sphere_integral(600, 1200, [&](const Vec3 &wi) { return b.eval(wo, wi, mode).r * std::fabs(wi.z); });
    const Estimate e = sampled_albedo(b, wo, mode, 400000, 17);
    printf("%s wo.z %+.3f: sampled %.5f +- %.5f, quadrature %.5f\n", what, wo.z, e.mean(), e.error(), quadrature);
    assert_true(std::fabs(e.mean() - quadrature) < 4 * e.error() + 2e-3 * quadrature);
}

void rough_dielectric_sampled_albedo_matches_quadrature(void **) {
    for (const RoughConfig &c : {kRough[0], kRough[3], kRough[4]})
        for (double theta : {0.3, 1.1})
            for (double side : {1.0, -1.0})
                for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                    const Bsdf b = Bsdf::rough_dielectric(c.type, c.alpha_u, c.alpha_v, kIntIor, kExtIor, c.visible);
                    Vec3 wo = direction(theta, 0.2);
                    wo.z *= side;
                    check_sampled_albedo_against_quadrature(b, wo, mode, "roughdielectric");
                }
}

void rough_dielectric_is_continued_not_gathered(void **) {
    const Bsdf b = Bsdf::rough_dielectric(MicrofacetType::Beckmann, 0.6, 0.6, kIntIor, kExtIor);
    assert_false(b.has_non_specular());
    assert_true(b.specular_probability({0, 0, 1}) == 0.0);
}

// ---- roughplastic -----------------------------------------------------------------------

void rough_plastic_tables_have_their_limits(void **) {
    const double eta = 1.49 / 1.000277;
    // A nearly smooth coat: the transmittance at normal incidence is 1 - F(1), the internal
    // reflectance Mitsuba's 64-point sum of the smooth Fresnel's hemispherical average (its
    // rule misses some of the total internal reflection near grazing: within 2 %).
    const Bsdf smooth = Bsdf::rough_plastic(Rgb(0.5), MicrofacetType::Beckmann, 0.005, 1.49, 1.000277);
    const double f0 = fresnel_dielectric(1.0, eta);
    assert_true(std::fabs(smooth.rough_coat_transmittance(1.0) - (1 - f0)) < 1e-4);
    assert_true(std::fabs(smooth.rough_coat_transmittance(0.5) - (1 - fresnel_dielectric(0.5, eta))) < 2e-3);
    const double fdr_int = fresnel_diffuse_reflectance(1 / eta);
    printf("internal reflectance alpha 0.005: %.5f, smooth Fdr_int %.5f\n", smooth.rough_coat_internal_reflectance(),
           fdr_int);
    assert_true(std::fabs(smooth.rough_coat_internal_reflectance() - fdr_int) < 0.02 * fdr_int);
    for (double alpha : {0.1, 0.3, 1.0}) {
        const Bsdf b = Bsdf::rough_plastic(Rgb(0.5), MicrofacetType::GGX, alpha, 1.49, 1.000277);
        printf("ggx alpha %.1f: T(1) %.5f T(0.5) %.5f T(0.1) %.5f R_int %.5f\n", alpha, b.rough_coat_transmittance(1),
               b.rough_coat_transmittance(0.5), b.rough_coat_transmittance(0.1), b.rough_coat_internal_reflectance());
        for (double mu = 0; mu <= 1; mu += 0.05) {
            const double t = b.rough_coat_transmittance(mu);
            assert_true(t >= 0 && t <= 1);
        }
        assert_true(b.rough_coat_internal_reflectance() > 0 && b.rough_coat_internal_reflectance() < 1);
    }
}

void rough_plastic_albedo_is_at_most_one(void **) {
    for (MicrofacetType type : {MicrofacetType::Beckmann, MicrofacetType::GGX})
        for (double alpha : {0.05, 0.1, 0.3, 0.7})
            for (double theta : {0.0, 0.6, 1.2, 1.5}) {
                const Bsdf b = Bsdf::rough_plastic(Rgb(1.0), type, alpha, 1.49, 1.000277);
                const Vec3 wo = direction(theta, 0.4);
                const Estimate e = sampled_albedo(b, wo, TransportMode::Importance, 100000, 21);
                printf("roughplastic %s alpha %.2f theta %.1f: white albedo %.4f +- %.4f\n", microfacet_type_name(type),
                       alpha, theta, e.mean(), e.error());
                assert_true(e.mean() <= 1 + 4 * e.error());
                // Mitsuba's model loses energy as the coat roughens (single scattering in
                // the coat, and the base's normalisation by the rough internal reflectance).
                if (alpha <= 0.1 && theta <= 1.2) assert_true(e.mean() > 0.9);
            }
}

void rough_plastic_samples_follow_pdf(void **) {
    for (const RoughConfig &c : kRough) {
        if (c.alpha_u != c.alpha_v) continue; // isotropic only, as Mitsuba
        for (double theta : {0.3, 1.2}) {
            const Bsdf b = Bsdf::rough_plastic({0.7, 0.5, 0.2}, c.type, c.alpha_u, 1.49, 1.000277, c.visible);
            for (double side : {1.0, -1.0}) {
                Vec3 wo = direction(theta, 2.0);
                wo.z *= side;
                ppm_test::Chi2Options opt;
                opt.samples = 300000;
                const ppm_test::Chi2Result r = ppm_test::chi2_test(
                    [&](double u0, double u1, double u2, Vec3 *w) {
                        const BsdfSample s = b.sample(wo, u0, u1, u2, TransportMode::Importance);
                        *w = s.wi;
                        return s.valid();
                    },
                    [&](const Vec3 &w) { return b.pdf(wo, w); }, opt);
                printf("roughplastic %s %g visible %d theta %.1f side %+.0f: chi2 %.1f dof %d p %.3g (integral "
                       "%.5f)\n",
                       microfacet_type_name(c.type), c.alpha_u, c.visible, theta, side, r.statistic, r.dof, r.p_value,
                       r.pdf_integral);
                assert_true(r.p_value > 1e-4);
            }
        }
    }
}

void rough_plastic_sampled_albedo_matches_quadrature(void **) {
    for (const RoughConfig &c : {kRough[0], kRough[2], kRough[4]})
        for (double theta : {0.3, 1.1}) {
            const Bsdf b = Bsdf::rough_plastic(Rgb(0.8), c.type, c.alpha_u, 1.49, 1.000277, c.visible);
            check_sampled_albedo_against_quadrature(b, direction(theta, 0.2), TransportMode::Radiance, "roughplastic");
        }
}

void rough_plastic_is_reciprocal_and_two_sided(void **) {
    const Bsdf b = Bsdf::rough_plastic({0.7, 0.5, 0.2}, MicrofacetType::GGX, 0.25, 1.49, 1.000277);
    test_rng rng{33};
    for (int k = 0; k < 2000; ++k) {
        const Vec3 wo = direction(1.5 * test_rng_uniform(&rng), 6.28 * test_rng_uniform(&rng));
        const Vec3 wi = direction(1.5 * test_rng_uniform(&rng), 6.28 * test_rng_uniform(&rng));
        const Rgb a = b.eval(wo, wi), c = b.eval(wi, wo);
        for (double d : {a.r - c.r, a.g - c.g, a.b - c.b}) assert_true(std::fabs(d) <= 1e-12 * std::max(1.0, a.r));
        const Vec3 wo_back{wo.x, wo.y, -wo.z}, wi_back{wi.x, wi.y, -wi.z};
        const Rgb back = b.eval(wo_back, wi_back);
        assert_true(back.r == a.r && back.g == a.g && back.b == a.b);
        assert_true(b.pdf(wo_back, wi_back) == b.pdf(wo, wi));
        assert_true(b.eval(wo, wi_back).is_black() && b.pdf(wo, wi_back) == 0);
    }
    assert_true(b.has_non_specular());
    assert_true(b.specular_probability({0, 0, 1}) == 0.0);
    assert_true(b.fixed_wo({0, 0, 1}, Rgb(1.0)).needs_full_eval());
}

void rough_plastic_with_reflectance_keeps_the_coat(void **) {
    const Bsdf b = Bsdf::rough_plastic(Rgb(0.5), MicrofacetType::Beckmann, 0.1, 1.49, 1.000277);
    const Bsdf c = b.with_reflectance({0.2, 0.4, 0.9});
    assert_true(c.type() == Bsdf::Type::RoughPlastic);
    assert_true(c.rough_coat_internal_reflectance() == b.rough_coat_internal_reflectance());
    const Vec3 wo = direction(0.5, 0), wi = direction(0.7, 3.0); // far from the highlight
    const Rgb fb = b.eval(wo, wi), fc = c.eval(wo, wi);
    // The base scales with the colour; the coat (grey) is the same in both.
    const double coat = fb.r - (fb.r - fc.r) / (0.5 - 0.2) * 0.5;
    assert_true(std::fabs((fc.b - coat) / (fb.b - coat) - 0.9 / 0.5) < 1e-9);
}

void invalid_parameters_are_rejected(void **) {
    expect_invalid_argument([] { Bsdf::thin_dielectric(1.5, 1.5); });
    expect_invalid_argument([] { Bsdf::thin_dielectric(-1.0, 1.0); });
    expect_invalid_argument([] { Bsdf::thin_dielectric(NAN, 1.0); });
    expect_invalid_argument([] { Bsdf::rough_dielectric(MicrofacetType::GGX, 0.0, 0.1, 1.5, 1.0); });
    expect_invalid_argument([] { Bsdf::rough_dielectric(MicrofacetType::GGX, 0.1, NAN, 1.5, 1.0); });
    expect_invalid_argument([] { Bsdf::rough_dielectric(MicrofacetType::GGX, 0.1, 0.1, 1.5, INFINITY); });
    expect_invalid_argument([] { Bsdf::rough_plastic(Rgb(0.5), MicrofacetType::GGX, -0.1, 1.5, 1.0); });
    expect_invalid_argument([] { Bsdf::rough_plastic(Rgb(1.5), MicrofacetType::GGX, 0.1, 1.5, 1.0); });
    expect_invalid_argument([] { Bsdf::rough_plastic(Rgb(0.5), MicrofacetType::GGX, 0.1, 1.0, 1.0); });
}

} // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(thin_dielectric_sums_the_internal_bounces),
        cmocka_unit_test(rough_dielectric_albedo_is_at_most_one),
        cmocka_unit_test(rough_dielectric_radiance_mode_scales_transmission),
        cmocka_unit_test(rough_dielectric_refraction_is_reciprocal),
        cmocka_unit_test(rough_dielectric_samples_follow_pdf),
        cmocka_unit_test(rough_dielectric_sampled_albedo_matches_quadrature),
        cmocka_unit_test(rough_dielectric_is_continued_not_gathered),
        cmocka_unit_test(rough_plastic_tables_have_their_limits),
        cmocka_unit_test(rough_plastic_albedo_is_at_most_one),
        cmocka_unit_test(rough_plastic_samples_follow_pdf),
        cmocka_unit_test(rough_plastic_sampled_albedo_matches_quadrature),
        cmocka_unit_test(rough_plastic_is_reciprocal_and_two_sided),
        cmocka_unit_test(rough_plastic_with_reflectance_keeps_the_coat),
        cmocka_unit_test(invalid_parameters_are_rejected),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
