// SPDX-License-Identifier: Apache-2.0
// Look-at camera against geometry worked out by hand: where the centre and the fov edges
// look, square pixels for any aspect ratio, the thin lens focus, and input validation.
#include "camera/camera.h"
#include "core/error.h"

#include "test_support.h"

#include <array>
#include <cmath>

using namespace ppm;

namespace {

const double kDeg = 3.14159265358979323846 / 180.0;

void assert_vec_close(const Vec3 &a, const Vec3 &b, double tolerance) {
    assert_close(a.x, b.x, tolerance);
    assert_close(a.y, b.y, tolerance);
    assert_close(a.z, b.z, tolerance);
}

double angle_between(const Vec3 &a, const Vec3 &b) { return std::atan2(length(cross(a, b)), dot(a, b)); }

CameraSettings oblique_settings() {
    CameraSettings s;
    s.origin = {1, 2, 3};
    s.target = {4, -1, 7};
    s.up = {0.2, 1, -0.1};
    s.fov = 50;
    s.width = 640;
    s.height = 480;
    return s;
}

void centre_ray_goes_to_the_target(void **) {
    const CameraSettings s = oblique_settings();
    const Camera camera(s);
    const CameraRay ray = camera.generate_ray(320, 240, 0.3, 0.8);
    assert_vec_close(ray.origin, s.origin, 0);
    assert_vec_close(ray.direction, normalize(s.target - s.origin), 1e-15);
    assert_close(length(ray.direction), 1.0, 1e-15);
}

// Mitsuba's identity camera: looks along +z with +x to the LEFT of the image, +y up.
void local_frame_follows_mitsuba(void **) {
    CameraSettings s;
    s.width = 200;
    s.height = 100;
    s.fov = 60;
    const Camera camera(s);
    assert_vec_close(camera.forward(), {0, 0, 1}, 0);
    assert_vec_close(camera.left(), {1, 0, 0}, 0);
    assert_vec_close(camera.up(), {0, 1, 0}, 0);
    const double t = std::tan(30 * kDeg);
    // Left and right image edges at mid-height: half the fov to either side.
    assert_vec_close(camera.generate_ray(0, 50, 0.5, 0.5).direction, normalize({t, 0, 1}), 1e-15);
    assert_vec_close(camera.generate_ray(200, 50, 0.5, 0.5).direction, normalize({-t, 0, 1}), 1e-15);
    // Top edge (y = 0) is up; the vertical extent is the horizontal one over the aspect.
    assert_vec_close(camera.generate_ray(100, 0, 0.5, 0.5).direction, normalize({0, t / 2, 1}), 1e-15);
    assert_vec_close(camera.generate_ray(0, 100, 0.5, 0.5).direction, normalize({t, -t / 2, 1}), 1e-15);
}

void fov_spans_the_image_width(void **) {
    for (double fov : {1.0, 45.0, 90.0, 150.0, 179.0}) {
        CameraSettings s = oblique_settings();
        s.fov = fov;
        const Camera camera(s);
        const Vec3 l = camera.generate_ray(0, 240, 0.5, 0.5).direction;
        const Vec3 r = camera.generate_ray(640, 240, 0.5, 0.5).direction;
        assert_close(angle_between(l, camera.forward()), 0.5 * fov * kDeg, 1e-12);
        assert_close(angle_between(r, camera.forward()), 0.5 * fov * kDeg, 1e-12);
        assert_close(angle_between(l, r), fov * kDeg, 1e-12);
        assert_true(dot(l, camera.left()) > 0);
        assert_true(dot(r, camera.left()) < 0);
        // World up appears up in the image: the top row looks more along `up`.
        assert_true(dot(camera.generate_ray(320, 0, 0.5, 0.5).direction, s.up) >
                    dot(camera.generate_ray(320, 480, 0.5, 0.5).direction, s.up));
    }
}

// On the plane at unit depth a pixel is a square of side pixel_size_at_unit_distance().
void pixels_are_square_for_any_aspect(void **) {
    const int sizes[][2] = {{640, 480}, {100, 400}, {1, 1}, {1024, 768}};
    for (const auto &size : sizes) {
        CameraSettings s = oblique_settings();
        s.width = size[0];
        s.height = size[1];
        const Camera camera(s);
        const auto on_plane = [&](double x, double y) {
            const Vec3 d = camera.generate_ray(x, y, 0.5, 0.5).direction;
            return d / dot(d, camera.forward());
        };
        const double px = camera.pixel_size_at_unit_distance();
        const Vec3 a = on_plane(0.25 * size[0], 0.75 * size[1]);
        assert_close(length(on_plane(0.25 * size[0] + 1, 0.75 * size[1]) - a), px, 1e-12);
        assert_close(length(on_plane(0.25 * size[0], 0.75 * size[1] + 1) - a), px, 1e-12);
        assert_close(px, 2 * std::tan(25 * kDeg) / size[0], 1e-15);
    }
}

void project_inverts_generate_ray(void **) {
    const Camera camera(oblique_settings());
    test_rng rng{7};
    for (int k = 0; k < 1000; ++k) {
        const double x = -50 + 740 * test_rng_uniform(&rng), y = -50 + 580 * test_rng_uniform(&rng);
        const CameraRay ray = camera.generate_ray(x, y, 0.5, 0.5);
        double px, py;
        assert_true(camera.project(ray.origin + ray.direction * (0.1 + 10 * test_rng_uniform(&rng)), &px, &py));
        assert_close(px, x, 1e-9);
        assert_close(py, y, 1e-9);
    }
    double px, py;
    assert_false(camera.project(camera.position() - camera.forward(), &px, &py));
    assert_false(camera.project(camera.position() + camera.left(), &px, &py));
}

void thin_lens_rays_meet_on_the_focus_plane(void **) {
    CameraSettings s = oblique_settings();
    s.aperture_radius = 0.25;
    s.focus_distance = 4.0;
    const Camera lens(s);
    s.aperture_radius = 0;
    const Camera pinhole(s);
    assert_true(lens.is_thin_lens());
    assert_false(pinhole.is_thin_lens());
    test_rng rng{11};
    for (int pixel = 0; pixel < 20; ++pixel) {
        const double x = 640 * test_rng_uniform(&rng), y = 480 * test_rng_uniform(&rng);
        // The pinhole ray through (x, y) meets the focus plane (depth 4 along the axis) here.
        const CameraRay centre = pinhole.generate_ray(x, y, 0, 0);
        const Vec3 focus = centre.origin + centre.direction * (4.0 / dot(centre.direction, lens.forward()));
        Vec3 mean_origin;
        const int n = 500;
        for (int k = 0; k < n; ++k) {
            const CameraRay ray = lens.generate_ray(x, y, test_rng_uniform(&rng), test_rng_uniform(&rng));
            const Vec3 offset = ray.origin - s.origin;
            assert_close(dot(offset, lens.forward()), 0.0, 1e-15); // on the lens plane
            assert_true(length(offset) <= 0.25 * (1 + 1e-12));     // inside the aperture
            assert_close(length(ray.direction), 1.0, 1e-15);
            const double t = 4.0 / dot(ray.direction, lens.forward());
            assert_vec_close(ray.origin + ray.direction * t, focus, 1e-12);
            mean_origin += offset / n;
        }
        assert_true(length(mean_origin) < 0.25 * 0.1); // the disk is covered evenly
    }
    // The lens centre (sample (0.5, 0.5)) gives the pinhole ray.
    const CameraRay c = lens.generate_ray(100, 200, 0.5, 0.5);
    assert_vec_close(c.origin, s.origin, 0);
    assert_vec_close(c.direction, pinhole.generate_ray(100, 200, 0, 0).direction, 1e-15);
}

void expect_invalid(const CameraSettings &s) {
    try {
        Camera camera(s);
    } catch (const Error &e) {
        assert_int_equal(e.status(), PPM_ERROR_INVALID_ARGUMENT);
        return;
    }
    fail_msg("invalid camera settings were accepted");
}

void invalid_settings_are_rejected(void **) {
    const double nan = std::nan("");
    CameraSettings s = oblique_settings();
    s.origin.y = nan;
    expect_invalid(s);
    s = oblique_settings();
    s.target.z = INFINITY;
    expect_invalid(s);
    s = oblique_settings();
    s.up.x = nan;
    expect_invalid(s);
    for (double fov : {0.0, -10.0, 180.0, 200.0, nan, double(INFINITY)}) {
        s = oblique_settings();
        s.fov = fov;
        expect_invalid(s);
    }
    s = oblique_settings();
    s.width = 0;
    expect_invalid(s);
    s = oblique_settings();
    s.height = -3;
    expect_invalid(s);
    s = oblique_settings();
    s.target = s.origin;
    expect_invalid(s);
    s = oblique_settings();
    s.up = {0, 0, 0};
    expect_invalid(s);
    s = oblique_settings();
    s.up = (s.target - s.origin) * -2.0; // parallel to the view
    expect_invalid(s);
    s = oblique_settings();
    s.aperture_radius = -0.1;
    expect_invalid(s);
    s.aperture_radius = nan;
    expect_invalid(s);
    s.aperture_radius = 0.1; // thin lens needs a focus distance
    s.focus_distance = 0;
    expect_invalid(s);
    s.focus_distance = nan;
    expect_invalid(s);
    s.focus_distance = 2;
    Camera ok(s);
    (void)ok;
}

// A crop window is a part of the whole film: its pixel (i, j) sees what the whole image's
// pixel (x0 + i, y0 + j) sees, and projection returns cropped film positions.
void crop_window_is_part_of_the_film(void **) {
    const CameraSettings whole_settings = oblique_settings();
    CameraSettings crop_settings = whole_settings;
    crop_settings.crop_x0 = 100, crop_settings.crop_y0 = 40;
    crop_settings.crop_x1 = 300, crop_settings.crop_y1 = 200;
    const Camera whole(whole_settings), crop(crop_settings);
    assert_int_equal(crop.width(), 200);
    assert_int_equal(crop.height(), 160);
    assert_close(crop.pixel_size_at_unit_distance(), whole.pixel_size_at_unit_distance(), 1e-15);
    for (double x : {0.0, 17.25, 199.5})
        for (double y : {0.0, 80.5, 160.0}) {
            const CameraRay a = crop.generate_ray(x, y, 0.5, 0.5);
            const CameraRay b = whole.generate_ray(x + 100, y + 40, 0.5, 0.5);
            assert_vec_close(a.direction, b.direction, 1e-14);
            double px = 0, py = 0;
            assert_true(crop.project(a.origin + a.direction * 7.0, &px, &py));
            assert_close(px, x, 1e-9);
            assert_close(py, y, 1e-9);
        }
    for (const auto &window : {std::array<int, 4>{0, 0, 641, 10}, std::array<int, 4>{5, 5, 5, 10},
                               std::array<int, 4>{-1, 0, 10, 10}, std::array<int, 4>{0, 9, 10, 3}}) {
        CameraSettings bad = whole_settings;
        bad.crop_x0 = window[0], bad.crop_y0 = window[1], bad.crop_x1 = window[2], bad.crop_y1 = window[3];
        expect_invalid(bad);
    }
}

// A principal point offset slides the image over the plane z = 1 by a fraction of its size:
// film position (x, y) sees what the centred camera's (x + ox width, y + oy height) sees,
// with a crop window too, and projection inverts it.
void principal_point_offset_slides_the_image(void **) {
    const CameraSettings centred_settings = oblique_settings();
    CameraSettings offset_settings = centred_settings;
    offset_settings.principal_point_offset_x = 0.125;
    offset_settings.principal_point_offset_y = -0.25;
    CameraSettings both_settings = offset_settings;
    both_settings.crop_x0 = 100, both_settings.crop_y0 = 40, both_settings.crop_x1 = 300, both_settings.crop_y1 = 200;
    const Camera centred(centred_settings), offset(offset_settings), both(both_settings);
    assert_close(offset.pixel_size_at_unit_distance(), centred.pixel_size_at_unit_distance(), 1e-15);
    for (double x : {0.0, 17.25, 199.5})
        for (double y : {0.0, 80.5, 160.0}) {
            const CameraRay a = offset.generate_ray(x, y, 0.5, 0.5);
            assert_vec_close(a.direction, centred.generate_ray(x + 80, y - 120, 0.5, 0.5).direction, 1e-14);
            assert_vec_close(both.generate_ray(x, y, 0.5, 0.5).direction,
                             centred.generate_ray(x + 180, y - 80, 0.5, 0.5).direction, 1e-14);
            double px = 0, py = 0;
            assert_true(offset.project(a.origin + a.direction * 7.0, &px, &py));
            assert_close(px, x, 1e-9);
            assert_close(py, y, 1e-9);
        }
    for (double bad : {std::nan(""), 1e300}) {
        CameraSettings s = centred_settings;
        s.principal_point_offset_y = bad;
        expect_invalid(s);
    }
}

} // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(centre_ray_goes_to_the_target),
        cmocka_unit_test(local_frame_follows_mitsuba),
        cmocka_unit_test(fov_spans_the_image_width),
        cmocka_unit_test(pixels_are_square_for_any_aspect),
        cmocka_unit_test(project_inverts_generate_ray),
        cmocka_unit_test(thin_lens_rays_meet_on_the_focus_plane),
        cmocka_unit_test(invalid_settings_are_rejected),
        cmocka_unit_test(crop_window_is_part_of_the_film),
        cmocka_unit_test(principal_point_offset_slides_the_image),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
