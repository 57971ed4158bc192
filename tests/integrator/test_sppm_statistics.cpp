// SPDX-License-Identifier: Apache-2.0
// SPPM per-pixel statistics: the radius update against hand-computed values, M = 0, monotone
// shrinking, the radiance estimate, convergence to a known photon density as passes grow, and
// bit-identical fixed-point flux sums whatever the order and the number of threads.
#include "photon/random.h"
#include "photon/sppm_statistics.h"

#include "core/error.h"

#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <thread>
#include <vector>

using namespace ppm;

namespace {

void assert_rgb_close(const Rgb &a, const Rgb &b, double tolerance) {
    assert_close(a.r, b.r, tolerance);
    assert_close(a.g, b.g, tolerance);
    assert_close(a.b, b.b, tolerance);
}

bool same_bits(const Rgb &a, const Rgb &b) {
    return std::memcmp(&a.r, &b.r, sizeof(double)) == 0 && std::memcmp(&a.g, &b.g, sizeof(double)) == 0 &&
           std::memcmp(&a.b, &b.b, sizeof(double)) == 0;
}

PassPhotons pass_of(std::uint64_t m, Rgb phi) {
    PassPhotons p;
    p.m = m;
    p.phi = phi;
    return p;
}

void radius_update_matches_hand_computed_values(void **) {
    PixelStatistics s;
    s.r2 = 1;
    // First pass, N = 0: N' = alpha M = 2, R'^2 = R^2 alpha = 2/3, tau' = Phi 2/3.
    progressive_update(s, pass_of(3, {3, 6, 9}));
    assert_close(s.n, 2, 1e-15);
    assert_close(s.r2, 2.0 / 3.0, 1e-15);
    assert_rgb_close(s.tau, {2, 4, 6}, 1e-15);
    // N = 2, M = 4: N' = 2 + 8/3 = 14/3, ratio = (14/3) / 6 = 7/9.
    progressive_update(s, pass_of(4, {1, 1, 1}));
    assert_close(s.n, 14.0 / 3.0, 1e-15);
    assert_close(s.r2, 14.0 / 27.0, 1e-15);
    assert_rgb_close(s.tau, Rgb{3, 5, 7} * (7.0 / 9.0), 1e-15);

    // alpha = 1/2 from N = 10, M = 10: N' = 15, ratio = 15/20.
    PixelStatistics h;
    h.n = 10;
    h.r2 = 0.04;
    h.tau = {1, 2, 3};
    progressive_update(h, pass_of(10, {1, 0, 0.5}), 0.5);
    assert_close(h.n, 15, 0);
    assert_close(h.r2, 0.03, 1e-17);
    assert_rgb_close(h.tau, {1.5, 1.5, 2.625}, 1e-15);

    // alpha = 1 keeps every photon and the radius: plain accumulation.
    const double r2 = h.r2;
    progressive_update(h, pass_of(5, {0.5, 0.5, 0.375}), 1.0);
    assert_close(h.n, 20, 0);
    assert_close(h.r2, r2, 0);
    assert_rgb_close(h.tau, {2, 2, 3}, 0);
}

void no_photons_change_nothing(void **) {
    PixelStatistics fresh; // N = 0: the ratio would be 0/0
    fresh.r2 = 0.25;
    progressive_update(fresh, pass_of(0, {}));
    assert_close(fresh.n, 0, 0);
    assert_close(fresh.r2, 0.25, 0);
    assert_true(fresh.tau.is_black());

    PixelStatistics s;
    s.n = 7.5;
    s.r2 = 0.01;
    s.tau = {0.1, 0.2, 0.3};
    s.direct = {1, 1, 1};
    for (int i = 0; i < 10; ++i) progressive_update(s, pass_of(0, {}));
    assert_close(s.n, 7.5, 0);
    assert_close(s.r2, 0.01, 0);
    assert_rgb_close(s.tau, {0.1, 0.2, 0.3}, 0);
    assert_rgb_close(s.direct, {1, 1, 1}, 0);
}

void radius_shrinks_monotonically(void **) {
    test_rng rng{21};
    for (const double alpha : {0.1, 0.5, kDefaultAlpha, 0.9}) {
        PixelStatistics s;
        s.r2 = 1;
        double previous_r2 = s.r2, previous_n = s.n;
        for (int pass = 0; pass < 2000; ++pass) {
            const auto m = static_cast<std::uint64_t>(test_rng_uniform(&rng) * 4); // often 0
            progressive_update(s, pass_of(m, Rgb(static_cast<double>(m))), alpha);
            if (m > 0) {
                assert_true(s.r2 < previous_r2);
                assert_true(s.n > previous_n);
            } else {
                assert_true(s.r2 == previous_r2);
            }
            assert_true(s.r2 > 0);
            previous_r2 = s.r2;
            previous_n = s.n;
        }
    }
}

void radiance_estimate_divides_by_photons_emitted(void **) {
    PixelStatistics s;
    s.r2 = 0.5;
    s.tau = Rgb{1, 2, 3} * M_PI;
    s.direct = {3, 6, 9};
    // tau / (pi R^2 N_e) = (1, 2, 3) / 2, plus direct / 3 passes.
    assert_rgb_close(radiance_estimate(s, 4, 3), {1.5, 3, 4.5}, 1e-15);
    assert_rgb_close(radiance_estimate(s, 0, 3), {1, 2, 3}, 0);
    assert_true(radiance_estimate(s, 0, 0).is_black());
    assert_rgb_close(radiance_estimate(s, 4, 0), {0.5, 1, 1.5}, 1e-15);
}

// Photons land on a plane with a known density around a few fixed visible points; half of
// those emitted leave the scene. Each photon carries flux 1, so the estimate
// tau / (pi R^2 N_e) converges to 0.5 times the landing density at the visible point.
// `density(r2)` is that density at squared distance r2 from the centre, `sample` draws a
// landing point from u, v.
struct DensityExperiment {
    double initial_r2;
    double (*density)(double r2);
    void (*sample)(double u, double v, double *x, double *y);
};

constexpr int kPixels = 12;
constexpr int kPhotonsPerPass = 400;
constexpr int kRuns = 6;

double pixel_x(int k) { return -0.4 + 0.8 * k / (kPixels - 1); }
double pixel_y(int k) { return 0.3 * std::sin(1.7 * k); }

// Relative RMS error over pixels and runs after each of `checkpoints` passes.
std::vector<double> run_density_experiment(const DensityExperiment &e, const std::vector<int> &checkpoints) {
    std::vector<double> squared_error(checkpoints.size(), 0.0);
    for (int run = 0; run < kRuns; ++run) {
        std::vector<PixelStatistics> pixels(kPixels);
        for (PixelStatistics &s : pixels) s.r2 = e.initial_r2;
        std::uint64_t emitted = 0;
        std::size_t next = 0;
        for (int pass = 1; next < checkpoints.size(); ++pass) {
            std::vector<PassPhotons> found(kPixels);
            for (int i = 0; i < kPhotonsPerPass; ++i) {
                CounterRng rng(1000 + run, 1, static_cast<std::uint32_t>(pass), static_cast<std::uint64_t>(i));
                ++emitted;
                if (rng.uniform() < 0.5) continue; // left the scene
                double x, y;
                const double u = rng.uniform(), v = rng.uniform();
                e.sample(u, v, &x, &y);
                for (int k = 0; k < kPixels; ++k) {
                    const double dx = x - pixel_x(k), dy = y - pixel_y(k);
                    if (dx * dx + dy * dy <= pixels[k].r2) {
                        found[k].m += 1;
                        found[k].phi += Rgb(1.0);
                    }
                }
            }
            for (int k = 0; k < kPixels; ++k) progressive_update(pixels[k], found[k]);
            if (pass == checkpoints[next]) {
                for (int k = 0; k < kPixels; ++k) {
                    const double truth = 0.5 * e.density(pixel_x(k) * pixel_x(k) + pixel_y(k) * pixel_y(k));
                    const double estimate = radiance_estimate(pixels[k], emitted, pass).g;
                    squared_error[next] += (estimate / truth - 1) * (estimate / truth - 1);
                }
                ++next;
            }
        }
    }
    for (double &e2 : squared_error) e2 = std::sqrt(e2 / (kPixels * kRuns));
    return squared_error;
}

// Uniform in the unit disc: density 1/pi everywhere inside, so only noise remains.
double uniform_density(double) { return 1.0 / M_PI; }
void sample_uniform_disc(double u, double v, double *x, double *y) {
    const double r = std::sqrt(u), phi = 2 * M_PI * v;
    *x = r * std::cos(phi);
    *y = r * std::sin(phi);
}

// Density proportional to 1 + r^2 in the unit disc (integral 3 pi / 2): a radius-R disc around
// a point overestimates by R^2/2 in the numerator, a bias that must fade as R shrinks.
double quadratic_density(double r2) { return (1 + r2) / (1.5 * M_PI); }
void sample_quadratic_disc(double u, double v, double *x, double *y) {
    // CDF of s = r^2: (2 s + s^2) / 3 = u.
    const double r = std::sqrt(-1 + std::sqrt(1 + 3 * u)), phi = 2 * M_PI * v;
    *x = r * std::cos(phi);
    *y = r * std::sin(phi);
}

void estimate_converges_to_a_uniform_density(void **) {
    // R0 = 0.5: the visible points' discs stay inside the unit disc.
    const std::vector<int> checkpoints = {16, 128, 1024};
    const std::vector<double> error = run_density_experiment({0.25, uniform_density, sample_uniform_disc}, checkpoints);
    print_message("uniform density: relative RMS error %.4f, %.4f, %.4f after 16, 128, 1024 passes\n", error[0],
                  error[1], error[2]);
    // Expected about N^-1/3: a factor 2 per 8 times as many passes.
    assert_true(error[1] < 0.75 * error[0]);
    assert_true(error[2] < 0.75 * error[1]);
    assert_true(error[2] < 0.4 * error[0]);
    assert_true(error[2] < 0.05);
}

void estimate_converges_despite_a_density_gradient(void **) {
    const std::vector<int> checkpoints = {16, 128, 1024};
    const std::vector<double> error =
        run_density_experiment({0.25, quadratic_density, sample_quadratic_disc}, checkpoints);
    print_message("quadratic density: relative RMS error %.4f, %.4f, %.4f after 16, 128, 1024 passes\n", error[0],
                  error[1], error[2]);
    assert_true(error[1] < 0.75 * error[0]);
    assert_true(error[2] < 0.75 * error[1]);
    assert_true(error[2] < 0.05);
}

// Photon contributions spanning nine orders of magnitude, summed into a few pixels.
struct Contribution {
    std::size_t pixel;
    Rgb flux;
};

std::vector<Contribution> random_contributions(std::size_t count, std::size_t pixels, std::uint64_t seed) {
    std::vector<Contribution> c(count);
    test_rng rng{seed};
    for (Contribution &x : c) {
        x.pixel = static_cast<std::size_t>(test_rng_uniform(&rng) * pixels);
        const double scale = std::pow(10.0, -6 + 9 * test_rng_uniform(&rng));
        x.flux = Rgb{test_rng_uniform(&rng), test_rng_uniform(&rng), test_rng_uniform(&rng)} * scale;
    }
    return c;
}

// Adds contributions[order[i]] for i in [0, count) on `threads` threads, thread t taking
// every threads-th one (or contiguous chunks), and takes the pass.
std::vector<PassPhotons> accumulate(const std::vector<Contribution> &contributions,
                                    const std::vector<std::size_t> &order, std::size_t pixels, int threads,
                                    bool chunked) {
    FluxAccumulator acc(pixels, 1000.0);
    std::vector<std::thread> workers;
    const std::size_t n = order.size();
    for (int t = 0; t < threads; ++t)
        workers.emplace_back([&, t] {
            if (chunked) {
                for (std::size_t i = n * t / threads; i < n * (t + 1) / threads; ++i)
                    acc.add(contributions[order[i]].pixel, contributions[order[i]].flux);
            } else {
                for (std::size_t i = t; i < n; i += threads)
                    acc.add(contributions[order[i]].pixel, contributions[order[i]].flux);
            }
        });
    for (std::thread &w : workers) w.join();
    assert_int_equal(acc.rejected(), 0);
    std::vector<PassPhotons> result(pixels);
    for (std::size_t p = 0; p < pixels; ++p) result[p] = acc.take(p);
    return result;
}

void flux_sums_are_bit_identical_in_any_order_and_thread_count(void **) {
    const std::size_t pixels = 48;
    const std::vector<Contribution> contributions = random_contributions(120000, pixels, 22);
    std::vector<std::size_t> forward(contributions.size());
    for (std::size_t i = 0; i < forward.size(); ++i) forward[i] = i;
    std::vector<std::size_t> backward(forward.rbegin(), forward.rend());
    std::vector<std::size_t> shuffled = forward;
    test_rng rng{23};
    for (std::size_t i = shuffled.size(); i > 1; --i)
        std::swap(shuffled[i - 1], shuffled[static_cast<std::size_t>(test_rng_uniform(&rng) * i)]);

    const std::vector<PassPhotons> reference = accumulate(contributions, forward, pixels, 1, false);
    const struct {
        const std::vector<std::size_t> *order;
        int threads;
        bool chunked;
    } variants[] = {{&backward, 1, false}, {&shuffled, 1, false}, {&forward, 2, false}, {&shuffled, 3, true},
                    {&backward, 4, false}, {&shuffled, 8, false}, {&forward, 5, true}};
    for (const auto &v : variants) {
        const std::vector<PassPhotons> result = accumulate(contributions, *v.order, pixels, v.threads, v.chunked);
        for (std::size_t p = 0; p < pixels; ++p) {
            assert_int_equal(result[p].m, reference[p].m);
            assert_true(same_bits(result[p].phi, reference[p].phi));
        }
    }

    // And the fixed-point sum is the true sum to within half a quantum per photon.
    std::vector<long double> exact(pixels, 0.0L);
    std::vector<std::uint64_t> count(pixels, 0);
    for (const Contribution &c : contributions) {
        exact[c.pixel] += c.flux.g;
        ++count[c.pixel];
    }
    const double quantum = FluxAccumulator(1, 1000.0).quantum();
    assert_close(quantum, std::ldexp(1.0, 10 - 40), 0); // 1000 rounds up to S = 1024
    for (std::size_t p = 0; p < pixels; ++p) {
        assert_int_equal(reference[p].m, count[p]);
        assert_close(reference[p].phi.g, static_cast<double>(exact[p]),
                     0.5 * quantum * static_cast<double>(count[p]) + 1e-15 * static_cast<double>(exact[p]));
    }
}

// The 64-bit low word wraps around several times; the count of wraps keeps the sum exact.
void flux_sums_beyond_64_bits_stay_exact(void **) {
    FluxAccumulator acc(2, 1.0);            // q = 2^-40
    const double big = std::ldexp(1.0, 21); // 2^61 quanta each
    std::vector<std::thread> workers;
    for (int t = 0; t < 4; ++t)
        workers.emplace_back([&] {
            for (int i = 0; i < 10; ++i) acc.add(1, {big, big * 0.5, big + 0.25});
        });
    for (std::thread &w : workers) w.join();
    const PassPhotons pass = acc.take(1);
    assert_int_equal(pass.m, 40);
    assert_close(pass.phi.r, 40 * big, 0);
    assert_close(pass.phi.g, 20 * big, 0);
    assert_close(pass.phi.b, 40 * big + 10, 0);
    assert_int_equal(acc.rejected(), 0);
    // take() cleared the pixel; the other was never touched.
    assert_int_equal(acc.take(1).m, 0);
    assert_true(acc.take(1).phi.is_black());
    assert_true(acc.take(0).phi.is_black());
}

void out_of_range_flux_is_rejected_and_counted(void **) {
    FluxAccumulator acc(1, 1.0);
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    const double limit = std::ldexp(1.0, 22);
    acc.add(0, {nan, -1.0, 0.5});
    acc.add(0, {inf, limit, 0.25});
    assert_int_equal(acc.rejected(), 4);
    const PassPhotons pass = acc.take(0);
    assert_int_equal(pass.m, 2);
    // NaN and negative add nothing, +inf and 2^22 are clamped to 2^22.
    assert_close(pass.phi.r, limit, 0);
    assert_close(pass.phi.g, limit, 0);
    assert_close(pass.phi.b, 0.75, 0);
    // Just below the limit is taken as it is.
    acc.add(0, {std::nextafter(limit, 0.0), 0, 0});
    assert_int_equal(acc.rejected(), 4);
    assert_close(acc.take(0).phi.r, std::nextafter(limit, 0.0), 0);
    // Below half a quantum, nothing arrives; the photon still counts.
    acc.add(0, Rgb(std::ldexp(1.0, -42)));
    const PassPhotons faint = acc.take(0);
    assert_int_equal(faint.m, 1);
    assert_true(faint.phi.is_black());
}

void flux_scale_must_be_positive_and_finite(void **) {
    for (const double scale :
         {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 1e-320}) {
        bool thrown = false;
        try {
            FluxAccumulator acc(4, scale);
        } catch (const Error &e) {
            thrown = e.status() == PPM_ERROR_INVALID_ARGUMENT;
        }
        assert_true(thrown);
    }
    // Powers of two are their own S; anything else rounds up.
    assert_close(FluxAccumulator(1, 1.0).quantum(), std::ldexp(1.0, -40), 0);
    assert_close(FluxAccumulator(1, 0.75).quantum(), std::ldexp(1.0, -40), 0);
    assert_close(FluxAccumulator(1, 1.5).quantum(), std::ldexp(1.0, -39), 0);
}

// A whole run of passes (accumulate, take, update) gives bit-identical statistics on 1 and 4
// threads.
void statistics_are_independent_of_thread_count(void **) {
    const std::size_t pixels = 32;
    std::vector<PixelStatistics> one(pixels), four(pixels);
    for (std::size_t p = 0; p < pixels; ++p) one[p].r2 = four[p].r2 = 0.01 * (1 + p);
    for (int pass = 0; pass < 5; ++pass) {
        const std::vector<Contribution> c = random_contributions(20000, pixels, 100 + pass);
        std::vector<std::size_t> order(c.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        const std::vector<PassPhotons> a = accumulate(c, order, pixels, 1, false);
        const std::vector<PassPhotons> b = accumulate(c, order, pixels, 4, true);
        for (std::size_t p = 0; p < pixels; ++p) {
            progressive_update(one[p], a[p]);
            progressive_update(four[p], b[p]);
        }
    }
    for (std::size_t p = 0; p < pixels; ++p) {
        assert_true(std::memcmp(&one[p].n, &four[p].n, sizeof(double)) == 0);
        assert_true(std::memcmp(&one[p].r2, &four[p].r2, sizeof(double)) == 0);
        assert_true(same_bits(one[p].tau, four[p].tau));
        assert_true(one[p].r2 < 0.01 * (1 + p));
    }
}

} // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(radius_update_matches_hand_computed_values),
        cmocka_unit_test(no_photons_change_nothing),
        cmocka_unit_test(radius_shrinks_monotonically),
        cmocka_unit_test(radiance_estimate_divides_by_photons_emitted),
        cmocka_unit_test(estimate_converges_to_a_uniform_density),
        cmocka_unit_test(estimate_converges_despite_a_density_gradient),
        cmocka_unit_test(flux_sums_are_bit_identical_in_any_order_and_thread_count),
        cmocka_unit_test(flux_sums_beyond_64_bits_stay_exact),
        cmocka_unit_test(out_of_range_flux_is_rejected_and_counted),
        cmocka_unit_test(flux_scale_must_be_positive_and_finite),
        cmocka_unit_test(statistics_are_independent_of_thread_count),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
