// SPDX-License-Identifier: Apache-2.0
// Chi-square goodness-of-fit test of a direction sampler against its claimed density, in the
// style of Mitsuba 3's ChiSquareTest (src/python/python/chi2.py) and pbrt-v3's bsdftest:
// bin sampled directions on a (theta, phi) grid over the whole sphere, integrate the pdf over
// each bin numerically, pool the cells whose expected count is small, and compute the
// p-value of Pearson's statistic. One extra cell holds the samples the sampler did not
// produce (invalid or specular) against the pdf's missing mass n (1 - integral pdf).
//
// Use (deterministic with a fixed seed):
//   Chi2Result r = chi2_test([&](double u1, double u2, double u3, Vec3 *w) { ...; return valid; },
//                            [&](const Vec3 &w) { return pdf; }, {});
//   assert r.p_value > 1e-4
#pragma once

#include "math/vec3.h"

#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

namespace ppm_test {

struct Chi2Options {
    int theta_bins = 10, phi_bins = 20;
    long samples = 1000000;
    int quadrature = 24;       // sub-cells per bin side for integrating the pdf (midpoint)
    double min_expected = 5.0; // cells expecting fewer samples are pooled
    uint64_t seed = 0x5eed1234ULL;
};

struct Chi2Result {
    double statistic = 0, p_value = 0;
    int dof = 0;
    double pdf_integral = 0; // integral of the pdf over the sphere (<= 1)
};

// Regularised upper incomplete gamma Q(a, x) (series below a + 1, continued fraction above,
// as in any numerics text, e.g. Press et al. "Numerical Recipes" 6.2).
inline double chi2_gamma_q(double a, double x) {
    if (x <= 0) return 1.0;
    const double log_front = -x + a * std::log(x) - std::lgamma(a);
    if (x < a + 1) {
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 10000; ++n) {
            term *= x / (a + n);
            sum += term;
            if (std::fabs(term) < std::fabs(sum) * 1e-15) break;
        }
        return std::max(0.0, 1.0 - sum * std::exp(log_front));
    }
    // Lentz's continued fraction.
    const double tiny = 1e-300;
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1 / d;
        const double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1) < 1e-15) break;
    }
    return std::exp(log_front) * h;
}

// sampler(u1, u2, u3, &w) returns whether it produced a (non-specular) direction w.
inline Chi2Result chi2_test(const std::function<bool(double, double, double, ppm::Vec3 *)> &sampler,
                            const std::function<double(const ppm::Vec3 &)> &pdf, const Chi2Options &opt) {
    const double pi = 3.14159265358979323846;
    const int nt = opt.theta_bins, np = opt.phi_bins, cells = nt * np;
    std::vector<double> observed(cells + 1, 0.0), expected(cells + 1, 0.0);
    test_rng rng{opt.seed};
    for (long k = 0; k < opt.samples; ++k) {
        const double u1 = test_rng_uniform(&rng), u2 = test_rng_uniform(&rng), u3 = test_rng_uniform(&rng);
        ppm::Vec3 w;
        if (!sampler(u1, u2, u3, &w) || !std::isfinite(w.x + w.y + w.z)) {
            observed[cells] += 1;
            continue;
        }
        const double theta = std::acos(std::clamp(w.z, -1.0, 1.0));
        double phi = std::atan2(w.y, w.x);
        if (phi < 0) phi += 2 * pi;
        const int it = std::min(nt - 1, (int)(theta / pi * nt));
        const int ip = std::min(np - 1, (int)(phi / (2 * pi) * np));
        observed[it * np + ip] += 1;
    }
    // Expected counts: midpoint rule over q x q sub-cells of each bin in (theta, phi), with
    // d omega = sin(theta) d theta d phi.
    Chi2Result r;
    const int q = opt.quadrature;
    for (int it = 0; it < nt; ++it)
        for (int ip = 0; ip < np; ++ip) {
            const double t0 = it * pi / nt, dt = pi / nt / q;
            const double p0 = ip * 2 * pi / np, dp = 2 * pi / np / q;
            double sum = 0;
            for (int a = 0; a < q; ++a)
                for (int b = 0; b < q; ++b) {
                    const double t = t0 + (a + 0.5) * dt, phi = p0 + (b + 0.5) * dp;
                    const double s = std::sin(t);
                    sum += s * pdf(ppm::Vec3{s * std::cos(phi), s * std::sin(phi), std::cos(t)});
                }
            const double integral = sum * dt * dp;
            r.pdf_integral += integral;
            expected[it * np + ip] = integral * opt.samples;
        }
    expected[cells] = std::max(0.0, 1.0 - r.pdf_integral) * opt.samples;

    // Pool small cells (in increasing order of expectation) until the pool is big enough.
    std::vector<int> order(cells + 1);
    for (int i = 0; i <= cells; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[a] < expected[b]; });
    double pool_e = 0, pool_o = 0;
    int used = 0;
    for (int i : order) {
        if (expected[i] == 0) {
            if (observed[i] > 0) { // a sample where the pdf says none can be: reject outright
                r.statistic = INFINITY;
                r.p_value = 0;
                return r;
            }
            continue;
        }
        if (expected[i] < opt.min_expected) {
            pool_e += expected[i];
            pool_o += observed[i];
            continue;
        }
        r.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++used;
    }
    if (pool_e > 0) { // all the small cells as one
        r.statistic += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        ++used;
    }
    r.dof = std::max(1, used - 1);
    r.p_value = chi2_gamma_q(0.5 * r.dof, 0.5 * r.statistic);
    return r;
}

} // namespace ppm_test
