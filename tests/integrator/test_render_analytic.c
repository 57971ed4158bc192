/* SPDX-License-Identifier: Apache-2.0 */
/* The renderer against analytic answers through the public C API:
 *  - white furnace: a closed box of diffuse walls (albedo r) that all emit Le has radiance
 *    Le / (1 - r) everywhere, also seen through glass, in a mirror and on a coated object of
 *    white base, which neither absorb nor emit; in SPPM and PPM mode, with direct light by
 *    shadow rays and by photons;
 *  - a diffuse plane under a point light: L = rho / pi * I cos(theta) / d^2, by shadow rays
 *    (exact up to pixel jitter) and by photons, whose error falls as passes grow;
 *  - a disk light, as a disk and as a triangle mesh: the coaxial disk's view factor, by shadow
 *    rays and by photons;
 *  - a spot light: full intensity inside the beam, none beyond the cutoff; photons and
 *    shadow rays agree when two lights share the power (light selection probabilities);
 *  - the same seed gives the same image for 1 and 2 threads, another seed another image;
 *  - ppm_render_pass and ppm_render_pass_index, the first names of ppm_renderer_render_pass
 *    and ppm_renderer_render_pass_index, render the same images and refuse the same calls;
 *  - cancel, settings and argument errors.
 * All in the photon modes (sppm unless a test sets another). */
#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double kPi = 3.14159265358979323846;

typedef struct image {
    int width, height;
    float *rgb;
} image;

static ppm_renderer make_renderer(ppm_scene scene, const double origin[3], const double target[3], double fov,
                                  int width, int height) {
    ppm_camera camera;
    memset(&camera, 0, sizeof camera);
    memcpy(camera.origin, origin, sizeof camera.origin);
    memcpy(camera.target, target, sizeof camera.target);
    camera.up[1] = 1;
    if (fabs(target[0] - origin[0]) < 1e-12 && fabs(target[2] - origin[2]) < 1e-12) {
        camera.up[1] = 0; /* looking along y */
        camera.up[2] = 1;
    }
    camera.fov = fov;
    camera.width = (uint32_t)width;
    camera.height = (uint32_t)height;
    ppm_renderer renderer = NULL;
    assert_ppm_ok(ppm_renderer_create(scene, &camera, &renderer));
    /* These are the photon modes' tests (the bidirectional ones are test_vcm's); the default
     * mode, vcm, would also blur the spot's cutoff by its merging radius. */
    assert_ppm_ok(ppm_renderer_set_string(renderer, "mode", "sppm"));
    return renderer;
}

static image render(ppm_renderer renderer, int passes) {
    for (int i = 0; i < passes; ++i) assert_ppm_ok(ppm_render_pass(renderer));
    int64_t w = 0, h = 0;
    assert_ppm_ok(ppm_renderer_get_int(renderer, "width", &w));
    assert_ppm_ok(ppm_renderer_get_int(renderer, "height", &h));
    image im = {(int)w, (int)h, malloc(sizeof(float) * 3 * (size_t)(w * h))};
    assert_ppm_ok(ppm_renderer_get_layer(renderer, "radiance", im.rgb, (size_t)(3 * w * h)));
    return im;
}

static double mean_channel_value(const image *im, int x0, int y0, int x1, int y1) {
    double sum = 0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            for (int c = 0; c < 3; ++c, ++n) sum += im->rgb[3 * (y * im->width + x) + c];
    return sum / n;
}

/* Cube [-1, 1]^3 of six quads whose normals point inwards, each diffuse with albedo r and
 * emitting Le, plus (when `objects`) a glass, a mirror and a white coated sphere. */
static void build_furnace(ppm_scene scene, double albedo, double le, int objects) {
    const double wall_rgb[3] = {albedo, albedo, albedo}, emit[3] = {le, le, le};
    uint32_t wall = 0;
    assert_ppm_ok(ppm_scene_add_diffuse_material(scene, wall_rgb, &wall));
    /* For each axis and side: origin and two edges whose cross product points inwards. */
    for (int axis = 0; axis < 3; ++axis)
        for (int side = -1; side <= 1; side += 2) {
            const int a = (axis + 1) % 3, b = (axis + 2) % 3;
            double origin[3] = {0, 0, 0}, eu[3] = {0, 0, 0}, ev[3] = {0, 0, 0};
            origin[axis] = side;
            origin[a] = -1;
            origin[b] = -1;
            /* e_a x e_b = +e_axis: inwards on the -1 side; swap on the +1 side. */
            if (side < 0) {
                eu[a] = 2;
                ev[b] = 2;
            } else {
                eu[b] = 2;
                ev[a] = 2;
            }
            uint32_t id = 0;
            assert_ppm_ok(ppm_scene_add_quad(scene, origin, eu, ev, &id));
            assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, wall));
            assert_ppm_ok(ppm_scene_set_geometry_emission(scene, id, emit));
        }
    if (objects) {
        const double white[3] = {1, 1, 1};
        uint32_t glass = 0, mirror = 0, coated = 0, id = 0;
        assert_ppm_ok(ppm_scene_add_dielectric_material(scene, 1.5, 1.0, &glass));
        assert_ppm_ok(ppm_scene_add_mirror_material(scene, white, &mirror));
        assert_ppm_ok(ppm_scene_add_coated_material(scene, white, 1.5, 1.0, &coated));
        const double c_glass[3] = {0, 0, 0.3}, c_mirror[3] = {-0.5, 0.3, 0.4}, c_coated[3] = {0.5, -0.3, 0.4};
        assert_ppm_ok(ppm_scene_add_sphere(scene, c_glass, 0.3, &id));
        assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, glass));
        assert_ppm_ok(ppm_scene_add_sphere(scene, c_mirror, 0.2, &id));
        assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, mirror));
        assert_ppm_ok(ppm_scene_add_sphere(scene, c_coated, 0.2, &id));
        assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, coated));
    }
    assert_ppm_ok(ppm_scene_commit(scene));
}

static void check_furnace(void **state, const char *mode, int direct_lighting, int objects) {
    scene_fixture *f = *state;
    build_furnace(f->scene, 0.5, 1.0, objects);
    const double origin[3] = {0, 0, -0.8}, target[3] = {0, 0, 1};
    ppm_renderer r = make_renderer(f->scene, origin, target, 90, 48, 48);
    assert_ppm_ok(ppm_renderer_set_string(r, "mode", mode));
    assert_ppm_ok(ppm_renderer_set_int(r, "direct_lighting", direct_lighting));
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 40000));
    image im = render(r, 24);
    const double expected = 1.0 / (1.0 - 0.5);
    const double whole = mean_channel_value(&im, 0, 0, 48, 48);
    const double centre = mean_channel_value(&im, 18, 18, 30, 30); /* the glass sphere */
    print_message("furnace %s direct_lighting=%d objects=%d: mean %.4f, centre %.4f (expected %.4f)\n", mode,
                  direct_lighting, objects, whole, centre, expected);
    assert_close(whole, expected, 0.03 * expected);
    assert_close(centre, expected, 0.06 * expected);
    free(im.rgb);
    ppm_renderer_release(r);
}

static void furnace_sppm(void **state) { check_furnace(state, "sppm", 1, 0); }
static void furnace_sppm_photons_only(void **state) { check_furnace(state, "sppm", 0, 0); }
static void furnace_with_glass_mirror_and_coat(void **state) { check_furnace(state, "sppm", 1, 1); }
static void furnace_with_objects_ppm_mode(void **state) { check_furnace(state, "ppm", 1, 1); }
static void furnace_with_objects_pppm_mode(void **state) { check_furnace(state, "pppm", 1, 1); }
static void furnace_pppm_photons_only(void **state) { check_furnace(state, "pppm", 0, 0); }

/* Plane z = 0 (4 x 4, diffuse rho), point light at height h over the origin, camera above. */
static const double kRho = 0.8, kHeight = 1.0, kCameraHeight = 3.0, kFov = 60;

static void build_plane(ppm_scene scene) {
    const double rgb[3] = {kRho, kRho, kRho};
    const double origin[3] = {-2, -2, 0}, eu[3] = {4, 0, 0}, ev[3] = {0, 4, 0};
    uint32_t material = 0, id = 0;
    assert_ppm_ok(ppm_scene_add_diffuse_material(scene, rgb, &material));
    assert_ppm_ok(ppm_scene_add_quad(scene, origin, eu, ev, &id));
    assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, material));
}

/* Plane point seen at film position (fx, fy) by make_renderer's camera looking down -z with
 * up = +y: Mitsuba's frame has left = up x forward = -x. */
static void plane_point_at(double fx, double fy, int size, double *px, double *py) {
    const double t = tan(kFov * kPi / 360.0);
    const double a = (1 - 2 * fx / size) * t, b = (1 - 2 * fy / size) * t;
    *px = -a * kCameraHeight;
    *py = b * kCameraHeight;
}

static double point_light_radiance(double x, double y, double intensity) {
    const double d2 = x * x + y * y + kHeight * kHeight;
    return kRho / kPi * intensity * (kHeight / sqrt(d2)) / d2;
}

/* Mitsuba's spot falloff for a light pointing straight down: 1 inside the beam width,
 * linear in angle to 0 at the cutoff. */
static double spot_falloff(double x, double y, double cutoff, double beam) {
    const double angle = atan(sqrt(x * x + y * y) / kHeight) * 180 / kPi;
    return angle >= cutoff ? 0.0 : angle <= beam ? 1.0 : (cutoff - angle) / (cutoff - beam);
}

/* The analytic radiance averaged over pixel (x, y), as the box filter sees it (8 x 8
 * sub-samples); a spot light when cutoff > 0. */
static double pixel_radiance(int x, int y, int size, double intensity, double cutoff, double beam) {
    double sum = 0;
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
            double px, py;
            plane_point_at(x + (i + 0.5) / 8, y + (j + 0.5) / 8, size, &px, &py);
            const double falloff = cutoff > 0 ? spot_falloff(px, py, cutoff, beam) : 1.0;
            sum += point_light_radiance(px, py, intensity) * falloff;
        }
    return sum / 64;
}

/* RMS relative error of the image against the analytic radiance. */
static double plane_error(const image *im, double intensity) {
    double sum = 0;
    for (int y = 0; y < im->height; ++y)
        for (int x = 0; x < im->width; ++x) {
            const double expected = pixel_radiance(x, y, im->width, intensity, 0, 0);
            for (int c = 0; c < 3; ++c) {
                const double e = (im->rgb[3 * (y * im->width + x) + c] - expected) / expected;
                sum += e * e;
            }
        }
    return sqrt(sum / (3.0 * im->width * im->height));
}

/* The plane under a point light of 2 W/sr at height kHeight, seen from above at 32 x 32. */
static ppm_renderer point_light_over_plane(scene_fixture *f) {
    build_plane(f->scene);
    const double position[3] = {0, 0, kHeight}, intensity[3] = {2, 2, 2};
    assert_ppm_ok(ppm_scene_add_point_light(f->scene, position, intensity, NULL));
    assert_ppm_ok(ppm_scene_commit(f->scene));
    const double origin[3] = {0, 0, kCameraHeight}, target[3] = {0, 0, 0};
    return make_renderer(f->scene, origin, target, kFov, 32, 32);
}

static void point_light_on_plane_by_shadow_rays(void **state) {
    ppm_renderer r = point_light_over_plane(*state);
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 1000));
    image im = render(r, 64);
    const double error = plane_error(&im, 2.0);
    print_message("point light, shadow rays: rms relative error %.2e\n", error);
    assert_true(error < 0.008); /* only noise: the jitter samples each pixel box 64 times */
    free(im.rgb);
    ppm_renderer_release(r);
}

static void check_point_light_by_photons_converges(void **state, const char *mode) {
    ppm_renderer r = point_light_over_plane(*state);
    assert_ppm_ok(ppm_renderer_set_string(r, "mode", mode));
    assert_ppm_ok(ppm_renderer_set_int(r, "direct_lighting", 0));
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 20000));
    assert_ppm_ok(ppm_renderer_set_double(r, "initial_radius_pixels", 2));
    double errors[3];
    const int passes[3] = {2, 16, 128};
    int done = 0;
    for (int k = 0; k < 3; ++k) {
        image im = render(r, passes[k] - done);
        done = passes[k];
        errors[k] = plane_error(&im, 2.0);
        print_message("point light, photons only, %s: %3d passes, rms relative error %.4f\n", mode, passes[k],
                      errors[k]);
        free(im.rgb);
    }
    assert_true(errors[1] < 0.75 * errors[0]);
    assert_true(errors[2] < 0.75 * errors[1]);
    assert_true(errors[2] < 0.05);
    int64_t emitted = 0;
    assert_ppm_ok(ppm_renderer_get_int(r, "photons_emitted", &emitted));
    assert_int_equal(emitted, 128 * 20000);
    ppm_renderer_release(r);
}

static void point_light_on_plane_by_photons_converges(void **state) {
    check_point_light_by_photons_converges(state, "sppm");
}
static void point_light_on_plane_by_photons_converges_pppm(void **state) {
    check_point_light_by_photons_converges(state, "pppm");
}

/* Irradiance at distance rho off the axis of a disk light of radius R and radiance L at
 * height h facing the plane: E = pi L / 2 (1 - (h^2 + rho^2 - R^2) / sqrt((h^2 + rho^2 + R^2)^2
 * - 4 R^2 rho^2)) (the view factor of a coaxial disk). */
static double disk_irradiance(double rho, double radius, double radiance) {
    const double h2 = kHeight * kHeight, r2 = radius * radius, p2 = rho * rho;
    return kPi * radiance / 2 * (1 - (h2 + p2 - r2) / sqrt((h2 + p2 + r2) * (h2 + p2 + r2) - 4 * r2 * p2));
}

/* Mean over the image of the rendered radiance over the analytic one (the box filter's
 * average over each pixel, 4 x 4 sub-samples), leaving out the pixels that see the light's
 * back (the camera looks past the light at the plane: plane points within
 * radius * kCameraHeight / (kCameraHeight - kHeight) of the axis, plus a margin). */
static double disk_light_ratio(const image *im, double radius, double radiance) {
    const double hidden = 1.15 * radius * kCameraHeight / (kCameraHeight - kHeight);
    double sum = 0;
    int n = 0;
    for (int y = 0; y < im->height; ++y)
        for (int x = 0; x < im->width; ++x) {
            double expected = 0;
            int seen = 1;
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) {
                    double px, py;
                    plane_point_at(x + (i + 0.5) / 4, y + (j + 0.5) / 4, im->width, &px, &py);
                    const double rho = sqrt(px * px + py * py);
                    if (rho < hidden) seen = 0;
                    expected += kRho / kPi * disk_irradiance(rho, radius, radiance) / 16;
                }
            if (!seen) continue;
            for (int c = 0; c < 3; ++c, ++n) sum += im->rgb[3 * (y * im->width + x) + c] / expected;
        }
    assert_true(n > im->width * im->height);
    return sum / n;
}

/* The plane under a disk light (radius 0.5 at kHeight, facing down) as a `disk` shape and as a
 * 256-triangle mesh fan (area short by 1e-4): by shadow rays and by photons alike. */
static void disk_and_mesh_lights_on_plane(void **state) {
    const double radius = 0.5, radiance = 3;
    for (int mesh = 0; mesh < 2; ++mesh)
        for (int photons = 0; photons < 2; ++photons) {
            scene_fixture *f = *state;
            ppm_scene_release(f->scene);
            assert_ppm_ok(ppm_scene_create(f->context, &f->scene));
            build_plane(f->scene);
            uint32_t id = 0;
            if (mesh) {
                enum { n = 256 };
                double positions[3 * (n + 1)];
                uint32_t indices[3 * n];
                positions[0] = positions[1] = 0;
                positions[2] = kHeight;
                for (int k = 0; k < n; ++k) {
                    const double phi = 2 * kPi * k / n;
                    positions[3 * (k + 1)] = radius * cos(phi);
                    positions[3 * (k + 1) + 1] = radius * sin(phi);
                    positions[3 * (k + 1) + 2] = kHeight;
                    /* clockwise seen from above: face normal -z */
                    indices[3 * k] = 0;
                    indices[3 * k + 1] = (uint32_t)(1 + (k + 1) % n);
                    indices[3 * k + 2] = (uint32_t)(1 + k);
                }
                assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, positions, n + 1, indices, n, NULL, NULL, &id));
            } else {
                const double center[3] = {0, 0, kHeight}, au[3] = {0, radius, 0}, av[3] = {radius, 0, 0};
                assert_ppm_ok(ppm_scene_add_disk(f->scene, center, au, av, &id)); /* au x av = -z */
            }
            const double l[3] = {radiance, radiance, radiance}, black[3] = {0, 0, 0};
            assert_ppm_ok(ppm_scene_set_geometry_emission(f->scene, id, l));
            uint32_t absorber = 0; /* the light reflects nothing back onto the plane */
            assert_ppm_ok(ppm_scene_add_diffuse_material(f->scene, black, &absorber));
            assert_ppm_ok(ppm_scene_set_geometry_material(f->scene, id, absorber));
            assert_ppm_ok(ppm_scene_commit(f->scene));
            const double origin[3] = {0, 0, kCameraHeight}, target[3] = {0, 0, 0};
            ppm_renderer r = make_renderer(f->scene, origin, target, kFov, 24, 24);
            assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", photons ? 40000 : 1000));
            assert_ppm_ok(ppm_renderer_set_int(r, "direct_lighting", !photons));
            if (photons) assert_ppm_ok(ppm_renderer_set_double(r, "initial_radius_pixels", 2));
            image im = render(r, photons ? 48 : 32);
            const double ratio = disk_light_ratio(&im, radius, radiance);
            print_message("%s light on the plane, %s: mean ratio to the analytic radiance %.4f\n",
                          mesh ? "disk mesh" : "disk", photons ? "photons" : "shadow rays", ratio);
            assert_true(fabs(ratio - 1) < (photons ? 0.03 : 0.01));
            free(im.rgb);
            ppm_renderer_release(r);
        }
}

static void spot_light_beam_and_cutoff(void **state) {
    scene_fixture *f = *state;
    build_plane(f->scene);
    /* Spot straight down: beam 10 degrees, cutoff 20 degrees. */
    const double position[3] = {0, 0, kHeight}, target[3] = {0, 0, 0}, intensity[3] = {3, 3, 3};
    assert_ppm_ok(ppm_scene_add_spot_light(f->scene, position, target, intensity, 20, 10, NULL));
    assert_ppm_ok(ppm_scene_commit(f->scene));
    const double origin[3] = {0, 0, kCameraHeight}, target_cam[3] = {0, 0, 0};
    ppm_renderer r = make_renderer(f->scene, origin, target_cam, kFov, 32, 32);
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 1000));
    image im = render(r, 64);
    double sum = 0, peak = pixel_radiance(16, 16, 32, 3.0, 20, 10);
    int dark = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const double expected = pixel_radiance(x, y, 32, 3.0, 20, 10);
            const float value = im.rgb[3 * (y * 32 + x)];
            const double e = (value - expected) / peak;
            sum += e * e;
            double cx, cy; /* pixels wholly beyond the cutoff are black */
            plane_point_at(x + 0.5, y + 0.5, 32, &cx, &cy);
            if (atan(sqrt(cx * cx + cy * cy) / kHeight) * 180 / kPi > 25) {
                assert_true(value == 0.0f);
                ++dark;
            }
        }
    const double rms = sqrt(sum / (32 * 32));
    print_message("spot light: rms error %.2e of the peak, %d black pixels\n", rms, dark);
    assert_true(rms < 0.005);
    assert_true(dark > 500);
    free(im.rgb);
    ppm_renderer_release(r);
}

/* A spot wider than a hemisphere (Mitsuba accepts cutoffs up to 180 degrees) pointing away
 * from the plane: the plane sees it from angles 180 - a to its axis, a the angle from
 * straight down, so with beam 150 and cutoff 180 the falloff is min(1, a / 30 degrees). */
static void spot_light_wider_than_a_hemisphere(void **state) {
    scene_fixture *f = *state;
    build_plane(f->scene);
    const double position[3] = {0, 0, kHeight}, target[3] = {0, 0, 2 * kHeight}, intensity[3] = {3, 3, 3};
    assert_ppm_ok(ppm_scene_add_spot_light(f->scene, position, target, intensity, 180, 150, NULL));
    assert_ppm_ok(ppm_scene_commit(f->scene));
    const double origin[3] = {0, 0, kCameraHeight}, target_cam[3] = {0, 0, 0};
    ppm_renderer r = make_renderer(f->scene, origin, target_cam, kFov, 32, 32);
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 1000));
    image im = render(r, 64);
    double sum = 0, peak = 0;
    double expected[32 * 32];
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            double total = 0;
            for (int j = 0; j < 8; ++j)
                for (int i = 0; i < 8; ++i) {
                    double px, py;
                    plane_point_at(x + (i + 0.5) / 8, y + (j + 0.5) / 8, 32, &px, &py);
                    const double from_down = atan(sqrt(px * px + py * py) / kHeight) * 180 / kPi;
                    total += point_light_radiance(px, py, 3.0) * fmin(1.0, from_down / 30);
                }
            expected[y * 32 + x] = total / 64;
            peak = fmax(peak, expected[y * 32 + x]);
        }
    for (int i = 0; i < 32 * 32; ++i) {
        const double e = (im.rgb[3 * i] - expected[i]) / peak;
        sum += e * e;
    }
    const double rms = sqrt(sum / (32 * 32));
    print_message("spot light wider than a hemisphere: rms error %.2e of the peak\n", rms);
    assert_true(rms < 0.005);
    /* Straight below the light the spot is dim, its axis pointing away: the pixel there,
     * 0 to 9 degrees from straight down, gets about 0.15 of a point light's radiance. */
    assert_true(im.rgb[3 * (16 * 32 + 16)] < 0.3 * pixel_radiance(16, 16, 32, 3.0, 0, 0));
    free(im.rgb);
    ppm_renderer_release(r);
}

/* A point light and a spot of different powers: the photon estimate (which picks lights
 * by power) must agree with the shadow-ray estimate (which samples every light). */
static void photons_agree_with_shadow_rays_for_two_lights(void **state) {
    scene_fixture *f = *state;
    build_plane(f->scene);
    const double p1[3] = {0.5, 0, 1.2}, i1[3] = {1, 0.5, 0.25};
    const double p2[3] = {-0.5, 0.2, 0.8}, target[3] = {-0.3, 0, 0}, i2[3] = {4, 4, 4};
    assert_ppm_ok(ppm_scene_add_point_light(f->scene, p1, i1, NULL));
    assert_ppm_ok(ppm_scene_add_spot_light(f->scene, p2, target, i2, 60, 30, NULL));
    assert_ppm_ok(ppm_scene_commit(f->scene));
    const double origin[3] = {0, 0, kCameraHeight}, target_cam[3] = {0, 0, 0};
    double means[2][3];
    for (int direct = 0; direct <= 1; ++direct) {
        ppm_renderer r = make_renderer(f->scene, origin, target_cam, kFov, 24, 24);
        assert_ppm_ok(ppm_renderer_set_int(r, "direct_lighting", direct));
        assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 50000));
        image im = render(r, direct ? 4 : 40);
        for (int c = 0; c < 3; ++c) {
            double sum = 0;
            for (int p = 0; p < 24 * 24; ++p) sum += im.rgb[3 * p + c];
            means[direct][c] = sum / (24 * 24);
        }
        free(im.rgb);
        ppm_renderer_release(r);
    }
    for (int c = 0; c < 3; ++c) {
        print_message("channel %d: photons %.5f, shadow rays %.5f\n", c, means[0][c], means[1][c]);
        assert_close(means[0][c], means[1][c], 0.03 * means[1][c]);
    }
}

static void same_seed_same_image_any_thread_count(void **state) {
    scene_fixture *f = *state;
    build_furnace(f->scene, 0.6, 1.0, 1);
    const double origin[3] = {0, 0, -0.8}, target[3] = {0, 0, 1};
    float *images[3];
    const int threads[3] = {1, 2, 2};
    const int seeds[3] = {7, 7, 8};
    for (int k = 0; k < 3; ++k) {
        assert_ppm_ok(ppm_context_set_int(f->context, "threads", threads[k]));
        ppm_renderer r = make_renderer(f->scene, origin, target, 70, 24, 16);
        assert_ppm_ok(ppm_renderer_set_int(r, "seed", seeds[k]));
        assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 5000));
        image im = render(r, 3);
        images[k] = im.rgb;
        ppm_renderer_release(r);
    }
    assert_memory_equal(images[0], images[1], sizeof(float) * 3 * 24 * 16);
    assert_true(memcmp(images[0], images[2], sizeof(float) * 3 * 24 * 16) != 0);
    for (int k = 0; k < 3; ++k) free(images[k]);
}

/* 512 x 256 visible points: enough for the hit-point tree to be cut into parts (of 64k
 * points or more), built and searched on one thread and on two. Both searches find exactly
 * the hit points within their radii, and flux is summed exactly, so the KD-tree and the grid
 * give the same image too, on any thread count. */
static void same_image_with_either_search_and_the_tree_in_parts(void **state) {
    scene_fixture *f = *state;
    build_furnace(f->scene, 0.6, 1.0, 1);
    const double origin[3] = {0, 0, -0.8}, target[3] = {0, 0, 1};
    enum { width = 512, height = 256, runs = 4 };
    const char *searches[runs] = {"kdtree", "kdtree", "grid", "grid"};
    float *images[runs];
    for (int k = 0; k < runs; ++k) {
        assert_ppm_ok(ppm_context_set_int(f->context, "threads", k % 2 + 1));
        ppm_renderer r = make_renderer(f->scene, origin, target, 70, width, height);
        assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 20000));
        assert_ppm_ok(ppm_renderer_set_string(r, "hit_point_search", searches[k]));
        image im = render(r, 2);
        images[k] = im.rgb;
        ppm_renderer_release(r);
    }
    for (int k = 1; k < runs; ++k) assert_memory_equal(images[0], images[k], sizeof(float) * 3 * width * height);
    double sum = 0;
    for (int i = 0; i < 3 * width * height; ++i) sum += images[0][i];
    assert_true(sum > 0);
    for (int k = 0; k < runs; ++k) free(images[k]);
}

/* `renamed` and `alias` fail alike: the expected status, and the same message. */
#define assert_same_error(renamed, alias, expected, needle)                                                            \
    do {                                                                                                               \
        char renamed_message_[512];                                                                                    \
        assert_ppm_error(renamed, expected, needle);                                                                   \
        snprintf(renamed_message_, sizeof renamed_message_, "%s", ppm_last_error_message());                           \
        assert_ppm_error(alias, expected, needle);                                                                     \
        assert_string_equal(ppm_last_error_message(), renamed_message_);                                               \
    } while (0)

/* The aliases are the same functions: a renderer driven by the old name renders the image of
 * one driven by the new name, bit for bit, in a photon mode (passes in order) and in the
 * default, pass-independent mode (a pass by its index). */
static void former_pass_names_render_the_same(void **state) {
    scene_fixture *f = *state;
    build_furnace(f->scene, 0.6, 1.0, 1);
    const double origin[3] = {0, 0, -0.8}, target[3] = {0, 0, 1};
    enum { width = 16, height = 12, floats = 3 * width * height };
    float *images[4];
    for (int k = 0; k < 4; ++k) {
        const int alias = k % 2, by_index = k >= 2;
        ppm_renderer r = make_renderer(f->scene, origin, target, 70, width, height);
        if (by_index) assert_ppm_ok(ppm_renderer_set_string(r, "mode", "vcm"));
        assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 500));
        for (int pass = 0; pass < 2; ++pass) {
            if (by_index)
                assert_ppm_ok(alias ? ppm_render_pass_index(r, 3 - pass) : ppm_renderer_render_pass_index(r, 3 - pass));
            else
                assert_ppm_ok(alias ? ppm_render_pass(r) : ppm_renderer_render_pass(r));
        }
        int64_t passes = 0;
        assert_ppm_ok(ppm_renderer_get_int(r, "passes", &passes));
        assert_int_equal(passes, 2);
        images[k] = render(r, 0).rgb;
        ppm_renderer_release(r);
    }
    assert_memory_equal(images[0], images[1], sizeof(float) * floats);
    assert_memory_equal(images[2], images[3], sizeof(float) * floats);
    double sum = 0;
    for (int i = 0; i < floats; ++i) sum += images[0][i] + images[2][i];
    assert_true(sum > 0);
    for (int k = 0; k < 4; ++k) free(images[k]);
}

static void former_pass_names_refuse_the_same(void **state) {
    scene_fixture *f = *state;
    assert_same_error(ppm_renderer_render_pass(NULL), ppm_render_pass(NULL), PPM_ERROR_INVALID_ARGUMENT, "NULL");
    assert_same_error(ppm_renderer_render_pass_index(NULL, 0), ppm_render_pass_index(NULL, 0),
                      PPM_ERROR_INVALID_ARGUMENT, "NULL");
    build_furnace(f->scene, 0.5, 1.0, 0);
    const double origin[3] = {0, 0, 0}, target[3] = {0, 0, 1};
    ppm_renderer r = make_renderer(f->scene, origin, target, 60, 8, 8);
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 100));
    assert_same_error(ppm_renderer_render_pass_index(r, 0), ppm_render_pass_index(r, 0), PPM_ERROR_INVALID_OPERATION,
                      "pass-independent");
    assert_ppm_ok(ppm_renderer_cancel(r));
    assert_ppm_error(ppm_renderer_render_pass(r), PPM_ERROR_CANCELLED, "cancelled");
    assert_ppm_ok(ppm_renderer_cancel(r));
    assert_ppm_error(ppm_render_pass(r), PPM_ERROR_CANCELLED, "cancelled");
    ppm_renderer_release(r);

    r = make_renderer(f->scene, origin, target, 60, 8, 8);
    assert_ppm_ok(ppm_renderer_set_string(r, "mode", "pppm"));
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 100));
    assert_same_error(ppm_renderer_render_pass_index(r, UINT64_C(1) << 32), ppm_render_pass_index(r, UINT64_C(1) << 32),
                      PPM_ERROR_INVALID_ARGUMENT, "2^32");
    assert_ppm_ok(ppm_render_pass_index(r, 5));
    assert_same_error(ppm_renderer_render_pass_index(r, 5), ppm_render_pass_index(r, 5), PPM_ERROR_INVALID_OPERATION,
                      "rendered already");
    ppm_renderer_release(r);

    const double corner[3] = {-1, -1, -1}, edge_u[3] = {2, 0, 0}, edge_v[3] = {0, 2, 0};
    r = make_renderer(f->scene, origin, target, 60, 8, 8);
    assert_ppm_ok(ppm_scene_add_quad(f->scene, corner, edge_u, edge_v, NULL));
    assert_same_error(ppm_renderer_render_pass(r), ppm_render_pass(r), PPM_ERROR_INVALID_OPERATION, "not committed");
    ppm_renderer_release(r);
}

static void cancel_discards_the_pass(void **state) {
    scene_fixture *f = *state;
    build_furnace(f->scene, 0.5, 1.0, 0);
    const double origin[3] = {0, 0, 0}, target[3] = {0, 0, 1};
    ppm_renderer r = make_renderer(f->scene, origin, target, 60, 8, 8);
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 100));
    assert_ppm_ok(ppm_renderer_cancel(r));
    assert_ppm_error(ppm_render_pass(r), PPM_ERROR_CANCELLED, "cancelled");
    int64_t passes = -1;
    assert_ppm_ok(ppm_renderer_get_int(r, "passes", &passes));
    assert_int_equal(passes, 0);
    assert_ppm_ok(ppm_render_pass(r)); /* the request was used up */
    assert_ppm_ok(ppm_renderer_get_int(r, "passes", &passes));
    assert_int_equal(passes, 1);
    ppm_renderer_release(r);
}

static void settings_and_argument_errors(void **state) {
    scene_fixture *f = *state;
    build_furnace(f->scene, 0.5, 1.0, 0);
    const double origin[3] = {0, 0, 0}, target[3] = {0, 0, 1};
    ppm_renderer r = make_renderer(f->scene, origin, target, 60, 8, 4);
    assert_ppm_error(ppm_renderer_set_int(r, "photons", 5), PPM_ERROR_INVALID_ARGUMENT, "unknown");
    assert_ppm_error(ppm_renderer_set_int(r, "photons_per_pass", -1), PPM_ERROR_INVALID_ARGUMENT, "photons_per_pass");
    assert_ppm_error(ppm_renderer_set_double(r, "alpha", 1.5), PPM_ERROR_INVALID_ARGUMENT, "alpha");
    assert_ppm_error(ppm_renderer_set_double(r, "alpha", NAN), PPM_ERROR_INVALID_ARGUMENT, "finite");
    assert_ppm_error(ppm_renderer_set_string(r, "mode", "bdpt"), PPM_ERROR_INVALID_ARGUMENT, "sppm");
    assert_ppm_error(ppm_renderer_set_string(r, "alpha", "x"), PPM_ERROR_INVALID_ARGUMENT, "unknown string");
    assert_ppm_error(ppm_renderer_set_int(r, "max_depth", 0), PPM_ERROR_INVALID_ARGUMENT, "max_depth");
    double alpha = 0;
    assert_ppm_ok(ppm_renderer_get_double(r, "alpha", &alpha));
    assert_close(alpha, 2.0 / 3.0, 1e-15);
    char mode[8];
    size_t length = 0;
    assert_ppm_ok(ppm_renderer_get_string(r, "mode", mode, sizeof mode, &length));
    assert_string_equal(mode, "sppm");
    assert_int_equal(length, 4);
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 100));
    assert_ppm_ok(ppm_render_pass(r));
    assert_ppm_error(ppm_renderer_set_string(r, "mode", "ppm"), PPM_ERROR_INVALID_OPERATION, "first pass");
    assert_ppm_ok(ppm_renderer_set_double(r, "alpha", 0.5)); /* may change between passes */
    double eye_seconds = -1, build_seconds = -1, photon_seconds = -1;
    assert_ppm_ok(ppm_renderer_get_double(r, "last_eye_pass_seconds", &eye_seconds));
    assert_ppm_ok(ppm_renderer_get_double(r, "last_search_build_seconds", &build_seconds));
    assert_ppm_ok(ppm_renderer_get_double(r, "last_photon_pass_seconds", &photon_seconds));
    assert_true(build_seconds >= 0 && build_seconds <= eye_seconds && photon_seconds >= 0);
    float small[10];
    assert_ppm_error(ppm_renderer_get_layer(r, "radiance", small, 10), PPM_ERROR_INVALID_ARGUMENT, "96 floats");
    assert_ppm_error(ppm_renderer_get_layer(r, "depth", small, 10), PPM_ERROR_INVALID_ARGUMENT, "unknown image layer");
    float radius[32], photons[32];
    assert_ppm_ok(ppm_renderer_get_layer(r, "radius", radius, 32));
    assert_ppm_ok(ppm_renderer_get_layer(r, "photons", photons, 32));
    for (int i = 0; i < 32; ++i) assert_true(radius[i] > 0 && radius[i] < 1);
    ppm_renderer_release(r);

    ppm_camera bad;
    memset(&bad, 0, sizeof bad);
    bad.target[2] = 1;
    bad.up[1] = 1;
    bad.fov = 200;
    bad.width = bad.height = 4;
    ppm_renderer none = NULL;
    assert_ppm_error(ppm_renderer_create(f->scene, &bad, &none), PPM_ERROR_INVALID_ARGUMENT, "fov");
    bad.fov = 40;
    bad.width = 1u << 20;
    bad.height = 1u << 20;
    assert_ppm_error(ppm_renderer_create(f->scene, &bad, &none), PPM_ERROR_INVALID_ARGUMENT, "2^28");
    assert_null(none);
}

static void scene_errors(void **state) {
    scene_fixture *f = *state;
    const double bad_rgb[3] = {0.5, 1.5, 0.5}, nan_rgb[3] = {NAN, 0, 0}, grey[3] = {0.5, 0.5, 0.5};
    uint32_t id = 0;
    assert_ppm_error(ppm_scene_add_diffuse_material(f->scene, bad_rgb, &id), PPM_ERROR_INVALID_ARGUMENT, "at most 1");
    assert_ppm_error(ppm_scene_add_diffuse_material(f->scene, nan_rgb, &id), PPM_ERROR_INVALID_ARGUMENT, "finite");
    assert_ppm_error(ppm_scene_add_dielectric_material(f->scene, -1, 1, &id), PPM_ERROR_INVALID_ARGUMENT, "ior");
    uint32_t glass = 0, diffuse = 0;
    assert_ppm_ok(ppm_scene_add_dielectric_material(f->scene, 1.5, 1, &glass));
    assert_ppm_ok(ppm_scene_add_diffuse_material(f->scene, grey, &diffuse));
    assert_ppm_error(ppm_scene_set_material_texture(f->scene, glass, "x.png", NULL, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "glass");
    assert_ppm_error(ppm_scene_set_material_texture(f->scene, diffuse, "no/such/texture.png", NULL, NULL), PPM_ERROR_IO,
                     "no/such/texture.png");
    assert_ppm_error(ppm_scene_set_material_texture(f->scene, 9, "x.png", NULL, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "material id 9");
    const double position[3] = {0, 0, 0}, neg[3] = {-1, 0, 0};
    assert_ppm_error(ppm_scene_add_point_light(f->scene, position, neg, NULL), PPM_ERROR_INVALID_ARGUMENT, "intensity");
    assert_ppm_error(ppm_scene_add_spot_light(f->scene, position, position, grey, 20, 15, NULL),
                     PPM_ERROR_INVALID_ARGUMENT, "target");
    const double down[3] = {0, 0, -1};
    assert_ppm_error(ppm_scene_add_spot_light(f->scene, position, down, grey, 20, 25, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "beam_width");
    uint32_t patches = 0;
    assert_ppm_ok(ppm_scene_load_bpt(f->scene, PPM_TEAPOT, &patches));
    double rects[32 * 4];
    for (int i = 0; i < 32 * 4; ++i) rects[i] = (i % 4) / 4.0;
    assert_ppm_ok(ppm_scene_set_patch_uv_rects(f->scene, patches, rects));
    rects[17] = NAN;
    assert_ppm_error(ppm_scene_set_patch_uv_rects(f->scene, patches, rects), PPM_ERROR_INVALID_ARGUMENT, "patch 4");
    assert_ppm_error(ppm_scene_set_patch_uv_rects(f->scene, patches, NULL), PPM_ERROR_INVALID_ARGUMENT, "rects");
    const double q_origin[3] = {0, 0, 0}, q_u[3] = {1, 0, 0}, q_v[3] = {0, 1, 0};
    uint32_t quad = 0;
    assert_ppm_ok(ppm_scene_add_quad(f->scene, q_origin, q_u, q_v, &quad));
    assert_ppm_error(ppm_scene_set_patch_uv_rects(f->scene, quad, rects), PPM_ERROR_INVALID_ARGUMENT,
                     "not a patch set");
    assert_ppm_error(ppm_scene_set_geometry_emission(f->scene, quad, nan_rgb), PPM_ERROR_INVALID_ARGUMENT, "radiance");
    assert_ppm_error(ppm_scene_set_geometry_emission(f->scene, 99, grey), PPM_ERROR_INVALID_ARGUMENT, "99");
    assert_ppm_ok(ppm_scene_set_geometry_material(f->scene, quad, diffuse));
    assert_ppm_error(ppm_scene_set_geometry_emission(f->scene, patches, grey), PPM_ERROR_INVALID_ARGUMENT,
                     "Bezier patches cannot be area lights");
    assert_ppm_ok(ppm_scene_set_geometry_material(f->scene, patches, 5));
    assert_ppm_ok(ppm_scene_commit(f->scene));
    const double origin[3] = {0, -10, 2}, target[3] = {0, 0, 1};
    ppm_camera camera;
    memset(&camera, 0, sizeof camera);
    memcpy(camera.origin, origin, sizeof origin);
    memcpy(camera.target, target, sizeof target);
    camera.up[2] = 1;
    camera.fov = 40;
    camera.width = camera.height = 4;
    ppm_renderer none = NULL;
    assert_ppm_error(ppm_renderer_create(f->scene, &camera, &none), PPM_ERROR_INVALID_ARGUMENT, "material id 5");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(furnace_sppm, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(furnace_sppm_photons_only, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(furnace_with_glass_mirror_and_coat, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(furnace_with_objects_ppm_mode, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(furnace_with_objects_pppm_mode, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(furnace_pppm_photons_only, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(point_light_on_plane_by_shadow_rays, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(point_light_on_plane_by_photons_converges, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(point_light_on_plane_by_photons_converges_pppm, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(spot_light_beam_and_cutoff, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(spot_light_wider_than_a_hemisphere, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(disk_and_mesh_lights_on_plane, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(photons_agree_with_shadow_rays_for_two_lights, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(same_image_with_either_search_and_the_tree_in_parts, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(same_seed_same_image_any_thread_count, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(former_pass_names_render_the_same, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(former_pass_names_refuse_the_same, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(cancel_discards_the_pass, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(settings_and_argument_errors, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(scene_errors, scene_fixture_setup, scene_fixture_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
