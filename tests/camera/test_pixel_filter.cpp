// SPDX-License-Identifier: Apache-2.0
// Pixel filters (camera/pixel_filter.h): Mitsuba's tent and gaussian; each pixel's density
// integrates to 1 over the image, also at its borders, where it is cut off as Mitsuba's film
// cuts off its samples; sampling draws that density (binned frequencies against it); the box
// is the pixel with the uniform jitter as before.
#include "camera/pixel_filter.h"
#include "core/error.h"

#include "test_support.h"

#include <cmath>
#include <vector>

using namespace ppm;

namespace {

// The integral of W_pixel over [0, size] by the midpoint rule.
double integral(const PixelFilterAxis &axis, int pixel, int size) {
    const int n = 200000;
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += axis.density(pixel, (i + 0.5) * size / n);
    return sum * size / n;
}

void densities_integrate_to_one_inside_the_image(void **) {
    for (const PixelFilterSettings settings :
         {PixelFilterSettings{PixelFilterType::Tent, 1.5}, PixelFilterSettings{PixelFilterType::Gaussian, 0},
          PixelFilterSettings{PixelFilterType::Box, 0}}) {
        const PixelFilterAxis axis(settings, 12);
        for (int pixel : {0, 1, 5, 10, 11}) assert_close(integral(axis, pixel, 12), 1.0, 2e-4);
    }
    // Mitsuba's gaussian: radius 4 stddev, and its shape: W(x) / W(centre) there.
    const PixelFilterAxis gaussian({PixelFilterType::Gaussian, 0.5}, 32);
    assert_close(gaussian.radius(), 2.0, 0);
    const double peak = gaussian.density(16, 16.5), tail = std::exp(-8.0);
    assert_close(gaussian.density(16, 17.0) / peak, (std::exp(-0.5) - tail) / (1 - tail), 1e-5);
    assert_close(gaussian.density(16, 16.5 + 2.001), 0, 0);
    const PixelFilterAxis tent({PixelFilterType::Tent, 0}, 32);
    assert_close(tent.radius(), 1.0, 0);
    assert_close(tent.density(16, 16.75), 0.75, 1e-6); // (1 - 0.25) / 1, the tent's integral being 1
}

void sampling_draws_the_density(void **) {
    const PixelFilterAxis axis({PixelFilterType::Gaussian, 0.5}, 8);
    for (int pixel : {0, 4}) {
        const int bins = 40, n = 400000;
        std::vector<double> count(bins, 0);
        for (int i = 0; i < n; ++i) {
            const double x = axis.sample(pixel, (i + 0.5) / n);
            assert_true(x >= 0 && x < 8);
            const double t = (x - (pixel + 0.5 - 2.0)) / 4.0 * bins;
            if (t >= 0 && t < bins) count[static_cast<int>(t)] += 1;
        }
        for (int b = 0; b < bins; ++b) {
            const double lo = pixel + 0.5 - 2.0 + b * 0.1;
            double expected = 0;
            for (int k = 0; k < 100; ++k) expected += axis.density(pixel, lo + (k + 0.5) * 0.001) * 0.001;
            assert_close(count[b] / n, expected, 1e-4);
        }
    }
}

void the_box_is_the_pixel(void **) {
    const PixelFilter box({PixelFilterType::Box, 0}, 10, 6);
    assert_true(box.is_box());
    double x = 0, y = 0, density = 0;
    box.sample(3, 2, 0.25, 0.75, &x, &y, &density);
    assert_true(x == 3.25 && y == 2.75 && density == 1);
    assert_close(box.density(3, 2, 3.99, 2.01), 1, 0);
    assert_close(box.density(3, 2, 4.0, 2.5), 0, 0);
}

void bad_parameters_are_refused(void **) {
    for (const PixelFilterSettings bad :
         {PixelFilterSettings{PixelFilterType::Tent, -1}, PixelFilterSettings{PixelFilterType::Gaussian, NAN},
          PixelFilterSettings{PixelFilterType::Gaussian, 100}, PixelFilterSettings{PixelFilterType(7), 0}}) {
        try {
            PixelFilterAxis axis(bad, 10);
            fail_msg("a bad filter was accepted");
        } catch (const Error &e) {
            assert_int_equal(e.status(), PPM_ERROR_INVALID_ARGUMENT);
        }
    }
}

} // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(densities_integrate_to_one_inside_the_image),
        cmocka_unit_test(sampling_draws_the_density),
        cmocka_unit_test(the_box_is_the_pixel),
        cmocka_unit_test(bad_parameters_are_refused),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
