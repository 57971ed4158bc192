// SPDX-License-Identifier: Apache-2.0
// Microfacet distributions and the conductor Fresnel term against closed forms: D's
// projected area is 1, visible normals integrate to 1 and are sampled with the density
// pdf() claims (chi-square), G1 lies in [0, 1], and the complex Fresnel reflectance matches
// the normal-incidence formula and the dielectric limit k = 0.
#include "material/bsdf.h"
#include "material/fresnel.h"
#include "material/microfacet.h"
#include "math/vec3.h"

#include "chi2.h"
#include "test_support.h"

#include <cmath>
#include <cstdio>

using namespace ppm;

namespace {

const double kPi = 3.14159265358979323846;

Vec3 direction(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

struct Config {
    MicrofacetType type;
    double alpha_u, alpha_v;
};

const Config kConfigs[] = {
    {MicrofacetType::Beckmann, 0.05, 0.05}, {MicrofacetType::Beckmann, 0.3, 0.3}, {MicrofacetType::Beckmann, 1.0, 1.0},
    {MicrofacetType::Beckmann, 0.1, 0.5},   {MicrofacetType::GGX, 0.05, 0.05},    {MicrofacetType::GGX, 0.3, 0.3},
    {MicrofacetType::GGX, 1.0, 1.0},        {MicrofacetType::GGX, 0.5, 0.1},
};

// Integral over the upper hemisphere of g(m) d omega, with theta = (pi/2) t^2 so the pole
// (where narrow lobes live) gets fine steps; midpoint rule.
template <typename F> double hemisphere_integral(F g, int n_theta = 3000, int n_phi = 256) {
    double sum = 0;
    for (int i = 0; i < n_theta; ++i) {
        const double t = (i + 0.5) / n_theta;
        const double theta = 0.5 * kPi * t * t, dtheta = kPi * t / n_theta;
        for (int j = 0; j < n_phi; ++j) {
            const double phi = (j + 0.5) * 2 * kPi / n_phi;
            sum += g(direction(theta, phi)) * std::sin(theta) * dtheta * (2 * kPi / n_phi);
        }
    }
    return sum;
}

void projected_area_is_one(void **) {
    for (const Config &c : kConfigs) {
        const MicrofacetDistribution d(c.type, c.alpha_u, c.alpha_v);
        const double area = hemisphere_integral([&](const Vec3 &m) { return d.eval(m) * m.z; });
        printf("%s alpha (%g, %g): integral D cos = %.6f\n", microfacet_type_name(c.type), c.alpha_u, c.alpha_v, area);
        assert_true(std::fabs(area - 1) < 2e-3);
    }
}

void visible_normals_integrate_to_one(void **) {
    for (const Config &c : kConfigs)
        for (double theta_i : {0.0, 0.6, 1.2, 1.5}) {
            const MicrofacetDistribution d(c.type, c.alpha_u, c.alpha_v);
            const Vec3 wi = direction(theta_i, 0.7);
            const double total = hemisphere_integral([&](const Vec3 &m) { return d.pdf(wi, m); });
            assert_true(std::fabs(total - 1) < 3e-3);
        }
}

void g1_lies_in_the_unit_interval(void **) {
    test_rng rng{7};
    for (const Config &c : kConfigs) {
        const MicrofacetDistribution d(c.type, c.alpha_u, c.alpha_v);
        for (int k = 0; k < 2000; ++k) {
            const Vec3 v = direction(0.5 * kPi * test_rng_uniform(&rng), 2 * kPi * test_rng_uniform(&rng));
            const Vec3 m = direction(0.5 * kPi * test_rng_uniform(&rng), 2 * kPi * test_rng_uniform(&rng));
            const double g = d.smith_g1(v, m);
            assert_true(g >= 0 && g <= 1);
            const double gg = d.G(v, m, m);
            assert_true(gg >= 0 && gg <= 1);
        }
        // Normal incidence sees no shadowing; grazing incidence, almost total.
        assert_true(std::fabs(d.smith_g1(Vec3{0, 0, 1}, Vec3{0, 0, 1}) - 1) < 1e-12);
        assert_true(d.smith_g1(normalize(Vec3{1, 0, 1e-4}), Vec3{0, 0, 1}) < 0.05);
        // The back of a facet is never visible.
        assert_true(d.smith_g1(Vec3{0, 0, 1}, normalize(Vec3{1, 0, -0.1})) == 0);
    }
}

void visible_normal_samples_follow_their_pdf(void **) {
    for (bool visible : {true, false})
        for (const Config &c : kConfigs) {
            if (c.alpha_u < 0.1 || c.alpha_v < 0.1) continue; // too narrow for a 10 x 20 grid
            for (double theta_i : {0.3, 1.3}) {
                const MicrofacetDistribution d(c.type, c.alpha_u, c.alpha_v, visible);
                const Vec3 wi = direction(theta_i, 0.4);
                ppm_test::Chi2Options opt;
                opt.samples = 300000;
                const ppm_test::Chi2Result r = ppm_test::chi2_test(
                    [&](double u1, double u2, double, Vec3 *m) {
                        double pdf;
                        *m = d.sample(wi, u1, u2, &pdf);
                        return pdf > 0;
                    },
                    [&](const Vec3 &m) { return d.pdf(wi, m); }, opt);
                printf("%s alpha (%g, %g) visible %d theta_i %.1f: chi2 %.1f dof %d p %.3g (integral %.5f)\n",
                       microfacet_type_name(c.type), c.alpha_u, c.alpha_v, visible, theta_i, r.statistic, r.dof,
                       r.p_value, r.pdf_integral);
                assert_true(r.p_value > 1e-4);
            }
        }
}

void sampled_pdf_matches_pdf(void **) {
    test_rng rng{11};
    for (const Config &c : kConfigs) {
        const MicrofacetDistribution d(c.type, c.alpha_u, c.alpha_v);
        const Vec3 wi = direction(1.0, 2.0);
        for (int k = 0; k < 1000; ++k) {
            double pdf;
            const Vec3 m = d.sample(wi, test_rng_uniform(&rng), test_rng_uniform(&rng), &pdf);
            assert_true(std::fabs(length(m) - 1) < 1e-9);
            assert_true(m.z > 0);
            assert_true(std::fabs(pdf - d.pdf(wi, m)) <= 1e-9 * pdf);
        }
    }
}

void erf_inverse_inverts_erf(void **) {
    // Where erf is well conditioned (|x| < 3) the inverse recovers x; beyond, erf(x) is within
    // a few ulp of 1 and the best one can ask is erf(erf_inverse(y)) == y to rounding.
    for (double x = -5.5; x <= 5.5; x += 0.01) {
        const double y = std::erf(x);
        if (std::fabs(y) >= 1) continue;
        const double z = erf_inverse(y);
        if (std::fabs(x) < 3)
            assert_true(std::fabs(z - x) < 1e-12 * std::max(1.0, std::fabs(x)));
        else
            assert_true(std::fabs(std::erf(z) - y) <= 4e-16);
    }
    assert_true(std::isinf(erf_inverse(1.0)) && erf_inverse(1.0) > 0);
    assert_true(erf_inverse(0.0) == 0.0);
}

void conductor_fresnel_closed_forms(void **) {
    // Normal incidence: ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2).
    for (double n : {0.2, 1.0, 1.5, 3.0})
        for (double k : {0.0, 0.5, 3.0, 8.0}) {
            const double expected = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
            assert_true(std::fabs(fresnel_conductor(1.0, n, k) - expected) < 1e-12);
            // Grazing incidence reflects everything; everything lies in [0, 1].
            assert_true(std::fabs(fresnel_conductor(0.0, n, k) - 1) < 1e-9);
            for (double c = 0; c <= 1; c += 0.01) {
                const double f = fresnel_conductor(c, n, k);
                assert_true(f >= 0 && f <= 1);
            }
        }
    // k = 0 is a dielectric seen from outside.
    for (double c = 0.05; c <= 1; c += 0.05)
        assert_true(std::fabs(fresnel_conductor(c, 1.5, 0.0) - fresnel_dielectric(c, 1.5)) < 1e-12);
}

} // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(projected_area_is_one),          cmocka_unit_test(visible_normals_integrate_to_one),
        cmocka_unit_test(g1_lies_in_the_unit_interval),   cmocka_unit_test(visible_normal_samples_follow_their_pdf),
        cmocka_unit_test(sampled_pdf_matches_pdf),        cmocka_unit_test(erf_inverse_inverts_erf),
        cmocka_unit_test(conductor_fresnel_closed_forms),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
