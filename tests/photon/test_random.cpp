// SPDX-License-Identifier: Apache-2.0
// Counter-based random numbers: Philox4x32-10 against Random123's known answers, the
// statistics of the uniforms (mean, variance, histogram, correlations across dimensions,
// samples, passes and streams), and reproducibility independent of order and thread count.
#include "photon/random.h"

#include "test_support.h"

#include <cmath>
#include <thread>
#include <vector>

using namespace ppm;

namespace {

void philox_matches_random123_known_answers(void **) {
    // Random123 tests/kat_vectors, "philox4x32 10": counter, key, expected output.
    const struct {
        PhiloxCounter counter;
        PhiloxKey key;
        PhiloxCounter expected;
    } cases[] = {
        {{0, 0, 0, 0}, {0, 0}, {0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}},
        {{0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff},
         {0xffffffff, 0xffffffff},
         {0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}},
        {{0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344},
         {0xa4093822, 0x299f31d0},
         {0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}},
    };
    for (const auto &c : cases) {
        const PhiloxCounter out = philox4x32_10(c.counter, c.key);
        for (int i = 0; i < 4; ++i) assert_int_equal(out[i], c.expected[i]);
    }
}

void uniforms_lie_in_the_half_open_unit_interval(void **) {
    assert_true(uniform_from_bits(0) == 0.0);
    assert_true(uniform_from_bits(~0ull) == 1.0 - std::ldexp(1.0, -53));
    assert_true(uniform_from_bits(~0ull) < 1.0);
    assert_true(uniform_from_bits(1ull << 63) == 0.5);
    assert_true(uniform_from_bits32(0) == 0.0);
    assert_true(uniform_from_bits32(~0u) == 1.0 - std::ldexp(1.0, -32));
    assert_true(uniform_from_bits32(1u << 31) == 0.5);
    CounterRng rng(1, 0, 0, 0);
    for (int i = 0; i < 100000; ++i) {
        const double u = rng.uniform();
        assert_true(u >= 0.0 && u < 1.0);
    }
}

void uniforms_have_the_right_mean_variance_and_histogram(void **) {
    constexpr int kSamples = 250000, kDimensions = 4, kBins = 100;
    const double n = static_cast<double>(kSamples) * kDimensions;
    double sum = 0, sum2 = 0;
    std::vector<double> dimension_sum(kDimensions, 0.0);
    std::vector<int> histogram(kBins, 0);
    for (int i = 0; i < kSamples; ++i) {
        CounterRng rng(0x5eed, 1, 3, static_cast<std::uint64_t>(i));
        for (int d = 0; d < kDimensions; ++d) {
            const double u = rng.uniform();
            sum += u;
            sum2 += u * u;
            dimension_sum[d] += u;
            ++histogram[static_cast<int>(u * kBins)];
        }
    }
    const double mean = sum / n, variance = sum2 / n - mean * mean;
    // Five standard errors: sqrt(1/12 / n) for the mean, sqrt((1/80 - 1/144) / n) for the variance.
    assert_close(mean, 0.5, 5 * std::sqrt(1.0 / 12 / n));
    assert_close(variance, 1.0 / 12, 5 * std::sqrt((1.0 / 80 - 1.0 / 144) / n));
    for (int d = 0; d < kDimensions; ++d)
        assert_close(dimension_sum[d] / kSamples, 0.5, 5 * std::sqrt(1.0 / 12 / kSamples));
    double chi2 = 0;
    const double expected = n / kBins;
    for (int h : histogram) chi2 += (h - expected) * (h - expected) / expected;
    // 99 degrees of freedom: mean 99, standard deviation 14; 160 is p < 1e-4.
    print_message("histogram chi^2 = %.1f (99 degrees of freedom)\n", chi2);
    assert_true(chi2 < 160);
}

// Pearson correlation of x and y.
double correlation(const std::vector<double> &x, const std::vector<double> &y) {
    const double n = static_cast<double>(x.size());
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        sx += x[i];
        sy += y[i];
        sxx += x[i] * x[i];
        syy += y[i] * y[i];
        sxy += x[i] * y[i];
    }
    const double cov = sxy / n - sx / n * sy / n;
    return cov / std::sqrt((sxx / n - sx / n * sx / n) * (syy / n - sy / n * sy / n));
}

// Pairs of numbers that must look independent: neighbouring dimensions (within a block and
// across blocks), neighbouring samples, passes, streams and seeds.
void neighbouring_numbers_are_uncorrelated(void **) {
    constexpr int kSamples = 100000;
    const double tolerance = 5 / std::sqrt(static_cast<double>(kSamples));
    struct Draw {
        std::uint64_t seed;
        std::uint8_t stream;
        std::uint32_t pass;
        std::uint64_t index_offset;
        std::uint32_t dimension;
    };
    const struct {
        Draw a, b;
    } pairs[] = {
        {{7, 1, 0, 0, 0}, {7, 1, 0, 0, 1}},          // dimensions in one Philox block
        {{7, 1, 0, 0, 2}, {7, 1, 0, 0, 3}},          // its other half
        {{7, 1, 0, 0, 3}, {7, 1, 0, 0, 4}},          // neighbouring blocks
        {{7, 1, 0, 0, 5}, {7, 1, 0, 0, 12}},         // far dimensions
        {{7, 1, 0, 0, 0}, {7, 1, 0, 1, 0}},          // neighbouring samples
        {{7, 1, 0, 0, 0}, {7, 1, 1, 0, 0}},          // neighbouring passes
        {{7, 0, 0, 0, 0}, {7, 1, 0, 0, 0}},          // camera and photon streams
        {{7, 1, 0, 0, 0}, {8, 1, 0, 0, 0}},          // neighbouring seeds
        {{7, 1, 0, 0, 0}, {7, 1, 0, 1ull << 32, 0}}, // high bits of the index
    };
    int checked = 0;
    for (const auto &p : pairs) {
        std::vector<double> x(kSamples), y(kSamples);
        for (int i = 0; i < kSamples; ++i) {
            x[i] = CounterRng(p.a.seed, p.a.stream, p.a.pass, i + p.a.index_offset).uniform_at(p.a.dimension);
            y[i] = CounterRng(p.b.seed, p.b.stream, p.b.pass, i + p.b.index_offset).uniform_at(p.b.dimension);
        }
        const double r = correlation(x, y);
        if (std::fabs(r) >= tolerance) print_error("pair %d: correlation %.4f\n", checked, r);
        assert_true(std::fabs(r) < tolerance);
        ++checked;
    }

    // Joint histogram of dimensions (0, 1) on a 16 x 16 grid: 255 degrees of freedom, mean
    // 255, standard deviation 22.6; 350 is p < 1e-4.
    std::vector<int> cells(256, 0);
    for (int i = 0; i < kSamples; ++i) {
        CounterRng rng(9, 1, 0, static_cast<std::uint64_t>(i));
        const int a = static_cast<int>(rng.uniform() * 16), b = static_cast<int>(rng.uniform() * 16);
        ++cells[a * 16 + b];
    }
    double chi2 = 0;
    const double expected = kSamples / 256.0;
    for (int c : cells) chi2 += (c - expected) * (c - expected) / expected;
    print_message("joint (u0, u1) chi^2 = %.1f (255 degrees of freedom)\n", chi2);
    assert_true(chi2 < 350);
}

void numbers_are_reproducible_and_addressable(void **) {
    CounterRng a(42, 1, 5, 123456789012ull), b(42, 1, 5, 123456789012ull);
    const CounterRng fixed(42, 1, 5, 123456789012ull);
    for (std::uint32_t d = 0; d < 37; ++d) {
        const double u = a.uniform();
        assert_true(u == b.uniform());
        assert_true(u == fixed.uniform_at(d));
        assert_int_equal(a.dimension(), d + 1);
    }
    // Any change of seed, stream, pass or index changes the numbers.
    const double first = fixed.uniform_at(0);
    assert_true(CounterRng(43, 1, 5, 123456789012ull).uniform_at(0) != first);
    assert_true(CounterRng(42, 0, 5, 123456789012ull).uniform_at(0) != first);
    assert_true(CounterRng(42, 1, 6, 123456789012ull).uniform_at(0) != first);
    assert_true(CounterRng(42, 1, 5, 123456789013ull).uniform_at(0) != first);
    assert_true(CounterRng(42 + (1ull << 32), 1, 5, 123456789012ull).uniform_at(0) != first);
    // Dimensions repeat after 2^26 (the block counter has 24 bits).
    assert_true(fixed.uniform_at(1u << 26) == first);
    assert_true(fixed.uniform_at(1u << 25) != first);
}

// Samples drawn on any number of threads, in any order, are the same numbers.
void numbers_are_independent_of_thread_count(void **) {
    constexpr int kSamples = 40000, kDimensions = 6;
    const auto fill = [](int threads) {
        std::vector<double> out(static_cast<std::size_t>(kSamples) * kDimensions);
        std::vector<std::thread> workers;
        for (int t = 0; t < threads; ++t)
            workers.emplace_back([&out, t, threads] {
                // Each thread walks its samples backwards, to vary the order too.
                for (int i = kSamples - 1 - t; i >= 0; i -= threads) {
                    CounterRng rng(77, 1, 2, static_cast<std::uint64_t>(i));
                    for (int d = 0; d < kDimensions; ++d)
                        out[static_cast<std::size_t>(i) * kDimensions + d] = rng.uniform();
                }
            });
        for (std::thread &w : workers) w.join();
        return out;
    };
    const std::vector<double> one = fill(1);
    assert_true(fill(2) == one);
    assert_true(fill(7) == one);
}

} // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(philox_matches_random123_known_answers),
        cmocka_unit_test(uniforms_lie_in_the_half_open_unit_interval),
        cmocka_unit_test(uniforms_have_the_right_mean_variance_and_histogram),
        cmocka_unit_test(neighbouring_numbers_are_uncorrelated),
        cmocka_unit_test(numbers_are_reproducible_and_addressable),
        cmocka_unit_test(numbers_are_independent_of_thread_count),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
