/* SPDX-License-Identifier: Apache-2.0 */
/* The typed settings of contexts, scenes, renderers and scene files (ppm.h, "Typed settings"):
 * each object's int and double getters and setters with NULL arguments, unknown keys, keys of
 * another type, fractional values for integer keys and read-only keys; failed getters leave
 * their output untouched. */
#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <string.h>

typedef scene_fixture fixture;

static const char small_box[] = PPM_TEST_DATA_DIR "/scenes/small_box.json";

/* A committed unit sphere lit by a point light, and a small renderer of it. */
static ppm_renderer sphere_renderer(ppm_scene scene) {
    const double centre[3] = {0, 0, 0}, light[3] = {0, 3, 3}, intensity[3] = {5, 5, 5};
    assert_ppm_ok(ppm_scene_add_sphere(scene, centre, 1.0, NULL));
    assert_ppm_ok(ppm_scene_add_point_light(scene, light, intensity, NULL));
    assert_ppm_ok(ppm_scene_commit(scene));
    ppm_camera_v2 camera;
    ppm_camera_v2_init(&camera);
    camera.origin[2] = 5;
    camera.target[2] = 0;
    camera.width = 8;
    camera.height = 6;
    ppm_renderer renderer = NULL;
    assert_ppm_ok(ppm_renderer_create_v2(scene, &camera, &renderer));
    return renderer;
}

/* Context --------------------------------------------------------------------------------- */

static void test_context_int_key_through_doubles(void **state) {
    fixture *f = *state;
    double value = -1;
    int64_t count = -1;
    assert_ppm_ok(ppm_context_set_double(f->context, "threads", 2.0));
    assert_ppm_ok(ppm_context_get_int(f->context, "threads", &count));
    assert_int_equal(count, 2);
    assert_ppm_ok(ppm_context_get_double(f->context, "threads", &value));
    assert_true(value == 2.0);
    assert_ppm_ok(ppm_context_set_int(f->context, "threads", 1));
    assert_ppm_ok(ppm_context_get_double(f->context, "threads", &value));
    assert_true(value == 1.0);
}

static void test_context_double_setter_refuses_bad_values(void **state) {
    fixture *f = *state;
    const double bad[] = {2.5, -1.0, 1025.0, NAN, INFINITY, 1e300};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i)
        assert_ppm_error(ppm_context_set_double(f->context, "threads", bad[i]), PPM_ERROR_INVALID_ARGUMENT, "threads");
    int64_t count = -1;
    assert_ppm_ok(ppm_context_get_int(f->context, "threads", &count));
    assert_int_equal(count, 0); /* unchanged default */
}

static void test_context_double_null_and_unknown(void **state) {
    fixture *f = *state;
    double value = 7;
    assert_ppm_error(ppm_context_set_double(NULL, "threads", 1), PPM_ERROR_INVALID_ARGUMENT, "context");
    assert_ppm_error(ppm_context_set_double(f->context, NULL, 1), PPM_ERROR_INVALID_ARGUMENT, "key");
    assert_ppm_error(ppm_context_set_double(f->context, "thraeds", 1), PPM_ERROR_INVALID_ARGUMENT,
                     "unknown context setting 'thraeds' (did you mean 'threads'?) (known: threads (int))");
    assert_ppm_error(ppm_context_get_double(NULL, "threads", &value), PPM_ERROR_INVALID_ARGUMENT, "context");
    assert_ppm_error(ppm_context_get_double(f->context, NULL, &value), PPM_ERROR_INVALID_ARGUMENT, "key");
    assert_ppm_error(ppm_context_get_double(f->context, "threads", NULL), PPM_ERROR_INVALID_ARGUMENT, "out_value");
    assert_ppm_error(ppm_context_get_double(f->context, "speed", &value), PPM_ERROR_INVALID_ARGUMENT, "'speed'");
    assert_true(value == 7);
}

/* Scene ----------------------------------------------------------------------------------- */

static void test_scene_patch_presplit_is_an_int(void **state) {
    fixture *f = *state;
    int64_t n = -1;
    double d = -1;
    assert_ppm_ok(ppm_scene_get_int(f->scene, "patch_presplit", &n));
    assert_int_equal(n, 12); /* the documented default */
    assert_ppm_ok(ppm_scene_set_int(f->scene, "patch_presplit", 3));
    assert_ppm_ok(ppm_scene_get_int(f->scene, "patch_presplit", &n));
    assert_int_equal(n, 3);
    assert_ppm_ok(ppm_scene_get_double(f->scene, "patch_presplit", &d));
    assert_true(d == 3.0);
    /* The double path of the first API still works and is seen by get_int. */
    assert_ppm_ok(ppm_scene_set_double(f->scene, "patch_presplit", 5.0));
    assert_ppm_ok(ppm_scene_get_int(f->scene, "patch_presplit", &n));
    assert_int_equal(n, 5);
}

static void test_scene_set_int_range(void **state) {
    fixture *f = *state;
    const int64_t bad[] = {0, -1, 33, INT64_MAX, INT64_MIN};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i)
        assert_ppm_error(ppm_scene_set_int(f->scene, "patch_presplit", bad[i]), PPM_ERROR_INVALID_ARGUMENT,
                         "patch_presplit");
    assert_ppm_ok(ppm_scene_set_int(f->scene, "patch_presplit", 1));
    assert_ppm_ok(ppm_scene_set_int(f->scene, "patch_presplit", 32));
    assert_ppm_error(ppm_scene_set_double(f->scene, "patch_presplit", 2.5), PPM_ERROR_INVALID_ARGUMENT, "whole number");
    /* An integer for the double key is taken as a double: 1 is beyond its range. */
    assert_ppm_error(ppm_scene_set_int(f->scene, "tolerance", 1), PPM_ERROR_INVALID_ARGUMENT, "tolerance");
    assert_ppm_error(ppm_scene_set_int(f->scene, "tolerance", 0), PPM_ERROR_INVALID_ARGUMENT, "tolerance");
}

static void test_scene_get_int_refuses_the_double_key(void **state) {
    fixture *f = *state;
    int64_t n = 77;
    assert_ppm_error(ppm_scene_get_int(f->scene, "tolerance", &n), PPM_ERROR_INVALID_ARGUMENT,
                     "scene setting 'tolerance' is a double, not an integer");
    assert_int_equal(n, 77);
}

static void test_scene_int_null_and_unknown(void **state) {
    fixture *f = *state;
    int64_t n = 77;
    assert_ppm_error(ppm_scene_set_int(NULL, "patch_presplit", 3), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_set_int(f->scene, NULL, 3), PPM_ERROR_INVALID_ARGUMENT, "key");
    assert_ppm_error(ppm_scene_set_int(f->scene, "presplit", 3), PPM_ERROR_INVALID_ARGUMENT,
                     "unknown scene setting 'presplit' (known: tolerance (double), patch_presplit (int))");
    assert_ppm_error(ppm_scene_get_int(NULL, "patch_presplit", &n), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_get_int(f->scene, NULL, &n), PPM_ERROR_INVALID_ARGUMENT, "key");
    assert_ppm_error(ppm_scene_get_int(f->scene, "patch_presplit", NULL), PPM_ERROR_INVALID_ARGUMENT, "out_value");
    assert_ppm_error(ppm_scene_get_int(f->scene, "threads", &n), PPM_ERROR_INVALID_ARGUMENT, "'threads'");
    assert_int_equal(n, 77);
}

/* A presplit set as an int reaches the commit: the scene still answers rays exactly. */
static void test_scene_set_int_takes_effect_at_commit(void **state) {
    fixture *f = *state;
    double points[48];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double *p = points + 3 * (4 * i + j);
            p[0] = j / 3.0, p[1] = i / 3.0, p[2] = 0;
        }
    assert_ppm_ok(ppm_scene_add_bezier_patches(f->scene, points, 1, NULL));
    assert_ppm_ok(ppm_scene_set_int(f->scene, "patch_presplit", 2));
    assert_ppm_ok(ppm_scene_commit(f->scene));
    ppm_ray ray = {{0.25, 0.75, 1}, 0, {0, 0, -1}, INFINITY};
    ppm_hit hit;
    assert_ppm_ok(ppm_scene_intersect(f->scene, &ray, 1, &hit));
    assert_close(hit.t, 1, 1e-9);
    assert_close(hit.u, 0.25, 1e-9);
    assert_close(hit.v, 0.75, 1e-9);
}

/* Renderer -------------------------------------------------------------------------------- */

static void test_renderer_read_only_values(void **state) {
    fixture *f = *state;
    ppm_renderer r = sphere_renderer(f->scene);
    double d = -1;
    int64_t n = -1;
    assert_ppm_ok(ppm_renderer_get_double(r, "width", &d));
    assert_true(d == 8.0);
    assert_ppm_ok(ppm_renderer_get_double(r, "passes", &d));
    assert_true(d == 0.0);
    assert_ppm_error(ppm_renderer_set_int(r, "passes", 3), PPM_ERROR_INVALID_ARGUMENT, "'passes' is read-only");
    assert_ppm_error(ppm_renderer_set_double(r, "width", 9), PPM_ERROR_INVALID_ARGUMENT, "'width' is read-only");
    assert_ppm_error(ppm_renderer_set_string(r, "last_eye_pass_seconds", "1"), PPM_ERROR_INVALID_ARGUMENT, "read-only");
    assert_ppm_error(ppm_renderer_get_int(r, "last_photon_pass_seconds", &n), PPM_ERROR_INVALID_ARGUMENT,
                     "'last_photon_pass_seconds' is a double");
    assert_int_equal(n, -1);
    assert_ppm_ok(ppm_renderer_set_string(r, "mode", "sppm")); /* the photon count is sppm's */
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 500));
    assert_ppm_ok(ppm_render_pass(r));
    assert_ppm_ok(ppm_renderer_get_double(r, "passes", &d));
    assert_true(d == 1.0);
    assert_ppm_ok(ppm_renderer_get_int(r, "photons_emitted", &n));
    assert_ppm_ok(ppm_renderer_get_double(r, "photons_emitted", &d));
    assert_true(d == (double)n && n >= 500);
    ppm_renderer_release(r);
}

/* photons_per_pass 0 (the default) is automatic: one light subpath per pixel in vcm, a count
 * from the pixels in sppm; "paths_per_pass" reads what a pass traces. */
static void test_automatic_paths_per_pass(void **state) {
    fixture *f = *state;
    ppm_renderer r = sphere_renderer(f->scene);
    int64_t n = -1, emitted = -1;
    assert_ppm_ok(ppm_renderer_get_int(r, "photons_per_pass", &n));
    assert_int_equal(n, 0);
    assert_ppm_ok(ppm_renderer_get_int(r, "paths_per_pass", &n));
    assert_int_equal(n, 8 * 6); /* vcm */
    assert_ppm_error(ppm_renderer_set_int(r, "paths_per_pass", 5), PPM_ERROR_INVALID_ARGUMENT, "read-only");
    assert_ppm_error(ppm_renderer_set_int(r, "photons_per_pass", -1), PPM_ERROR_INVALID_ARGUMENT, "0 for automatic");
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 500));
    assert_ppm_ok(ppm_renderer_get_int(r, "paths_per_pass", &n));
    assert_int_equal(n, 500);
    assert_ppm_ok(ppm_renderer_set_string(r, "mode", "sppm"));
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 0));
    assert_ppm_ok(ppm_renderer_get_int(r, "paths_per_pass", &n));
    assert_true(n >= 8 * 6);
    assert_ppm_ok(ppm_render_pass(r));
    assert_ppm_ok(ppm_renderer_get_int(r, "photons_emitted", &emitted));
    assert_int_equal(emitted, n);
    ppm_renderer_release(r);
}

static void test_renderer_typed_settings(void **state) {
    fixture *f = *state;
    ppm_renderer r = sphere_renderer(f->scene);
    double d = -1;
    int64_t n = -1;
    assert_ppm_ok(ppm_renderer_set_double(r, "max_depth", 4.0));
    assert_ppm_ok(ppm_renderer_get_int(r, "max_depth", &n));
    assert_int_equal(n, 4);
    assert_ppm_ok(ppm_renderer_get_double(r, "max_depth", &d));
    assert_true(d == 4.0);
    assert_ppm_error(ppm_renderer_set_double(r, "seed", 2.5), PPM_ERROR_INVALID_ARGUMENT, "seed");
    assert_ppm_error(ppm_renderer_get_int(r, "alpha", &n), PPM_ERROR_INVALID_ARGUMENT, "'alpha' is a number setting");
    assert_ppm_error(ppm_renderer_get_double(r, "mode", &d), PPM_ERROR_INVALID_ARGUMENT, "'mode' is a string setting");
    assert_ppm_error(ppm_renderer_set_string(r, "seed", "3"), PPM_ERROR_INVALID_ARGUMENT,
                     "'seed' is an integer setting");
    assert_ppm_error(ppm_renderer_set_int(r, "photons", 3), PPM_ERROR_INVALID_ARGUMENT, "(settings: mode,");
    assert_ppm_error(ppm_renderer_set_int(r, "photons_per_pas", 3), PPM_ERROR_INVALID_ARGUMENT,
                     "'photons_per_pas' (did you mean 'photons_per_pass'?)");
    assert_ppm_error(ppm_renderer_get_double(r, NULL, &d), PPM_ERROR_INVALID_ARGUMENT, "key");
    assert_ppm_error(ppm_renderer_get_double(NULL, "alpha", &d), PPM_ERROR_INVALID_ARGUMENT, "renderer");
    assert_ppm_error(ppm_renderer_set_int(r, NULL, 1), PPM_ERROR_INVALID_ARGUMENT, "key");
    assert_int_equal(n, 4);
    assert_true(d == 4.0);
    ppm_renderer_release(r);
}

/* Scene file ------------------------------------------------------------------------------ */

static void test_scene_file_values(void **state) {
    fixture *f = *state;
    ppm_scene_file file = NULL;
    assert_ppm_ok(ppm_scene_file_load(f->context, small_box, &file));
    int64_t n = -1;
    double d = -1;
    assert_ppm_ok(ppm_scene_file_get_int(file, "passes", &n));
    assert_int_equal(n, 4);
    assert_ppm_ok(ppm_scene_file_get_double(file, "passes", &d));
    assert_true(d == 4.0);
    assert_ppm_ok(ppm_scene_file_get_double(file, "time", &d));
    assert_true(d == 0.0);
    n = 77;
    d = 77;
    assert_ppm_error(ppm_scene_file_get_int(file, "time", &n), PPM_ERROR_INVALID_ARGUMENT,
                     "scene file value 'time' is a double, not an integer");
    assert_ppm_error(ppm_scene_file_get_int(file, "seed", &n), PPM_ERROR_INVALID_ARGUMENT,
                     "unknown scene file value 'seed' (known: passes (int), time (double))");
    assert_ppm_error(ppm_scene_file_get_double(file, "seed", &d), PPM_ERROR_INVALID_ARGUMENT, "'seed'");
    assert_ppm_error(ppm_scene_file_get_int(file, NULL, &n), PPM_ERROR_INVALID_ARGUMENT, "key");
    assert_ppm_error(ppm_scene_file_get_double(file, NULL, &d), PPM_ERROR_INVALID_ARGUMENT, "key");
    assert_ppm_error(ppm_scene_file_get_int(file, "passes", NULL), PPM_ERROR_INVALID_ARGUMENT, "out_value");
    assert_ppm_error(ppm_scene_file_get_double(file, "time", NULL), PPM_ERROR_INVALID_ARGUMENT, "out_value");
    assert_ppm_error(ppm_scene_file_get_int(NULL, "passes", &n), PPM_ERROR_INVALID_ARGUMENT, "scene file");
    assert_ppm_error(ppm_scene_file_get_double(NULL, "time", &d), PPM_ERROR_INVALID_ARGUMENT, "scene file");
    assert_int_equal(n, 77);
    assert_true(d == 77);
    ppm_scene_file_release(file);
}

#define TEST(name) cmocka_unit_test_setup_teardown(name, scene_fixture_setup, scene_fixture_teardown)

int main(void) {
    const struct CMUnitTest tests[] = {
        TEST(test_context_int_key_through_doubles),
        TEST(test_context_double_setter_refuses_bad_values),
        TEST(test_context_double_null_and_unknown),
        TEST(test_scene_patch_presplit_is_an_int),
        TEST(test_scene_set_int_range),
        TEST(test_scene_get_int_refuses_the_double_key),
        TEST(test_scene_int_null_and_unknown),
        TEST(test_scene_set_int_takes_effect_at_commit),
        TEST(test_renderer_read_only_values),
        TEST(test_automatic_paths_per_pass),
        TEST(test_renderer_typed_settings),
        TEST(test_scene_file_values),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
