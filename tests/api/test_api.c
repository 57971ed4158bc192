/* SPDX-License-Identifier: Apache-2.0 */
/* Every public function with NULL and invalid arguments: the documented status, a message that
 * names the culprit, untouched outputs, and an empty message after the next success. Also
 * reference counting, the error callback and the version queries. */
#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef scene_fixture fixture;

static const double origin[3] = {0, 0, 0};
static const double unit_x[3] = {1, 0, 0};
static const double unit_y[3] = {0, 1, 0};

static uint32_t add_unit_sphere(ppm_scene scene) {
    uint32_t id = PPM_INVALID_ID;
    assert_ppm_ok(ppm_scene_add_sphere(scene, origin, 1.0, &id));
    return id;
}

static void commit_with_sphere(ppm_scene scene) {
    add_unit_sphere(scene);
    assert_ppm_ok(ppm_scene_commit(scene));
}

/* A ray from (0, 0, 5) towards the origin: it hits the unit sphere. */
static ppm_ray good_ray(void) {
    ppm_ray ray = {{0, 0, 5}, 0, {0, 0, -1}, INFINITY};
    return ray;
}

/* Any successful call, to check that it clears the message of the failure before it. */
static void succeed_once(void) {
    ppm_context context = NULL;
    assert_ppm_ok(ppm_context_create(&context));
    ppm_context_release(context);
}

static void fill_identity(double m[16]) {
    memset(m, 0, 16 * sizeof m[0]);
    m[0] = m[5] = m[10] = m[15] = 1;
}

/* Versions and status names --------------------------------------------------------------- */

static void test_version_matches_header(void **state) {
    (void)state;
    assert_int_equal(ppm_version(), PPM_VERSION);
    assert_int_equal(ppm_version(), PPM_VERSION_MAJOR * 10000 + PPM_VERSION_MINOR * 100 + PPM_VERSION_PATCH);
}

static void test_version_string_matches_header(void **state) {
    (void)state;
    assert_non_null(ppm_version_string());
    assert_string_equal(ppm_version_string(), PPM_VERSION_STRING);
}

static void test_status_string_names_every_status(void **state) {
    (void)state;
    const ppm_status all[] = {
        PPM_OK,          PPM_ERROR_INVALID_ARGUMENT, PPM_ERROR_INVALID_OPERATION, PPM_ERROR_OUT_OF_MEMORY, PPM_ERROR_IO,
        PPM_ERROR_PARSE, PPM_ERROR_UNSUPPORTED,      PPM_ERROR_CANCELLED,         PPM_ERROR_INTERNAL};
    const size_t n = sizeof all / sizeof all[0];
    for (size_t i = 0; i < n; ++i) {
        const char *name = ppm_status_string(all[i]);
        assert_non_null(name);
        assert_true(name[0] != '\0');
        for (size_t j = 0; j < i; ++j) assert_string_not_equal(name, ppm_status_string(all[j]));
    }
    assert_string_equal(ppm_status_string(PPM_OK), "ok");
    assert_string_equal(ppm_status_string(PPM_ERROR_INVALID_ARGUMENT), "invalid argument");
    assert_string_equal(ppm_status_string(PPM_ERROR_INVALID_OPERATION), "invalid operation");
    assert_string_equal(ppm_status_string(PPM_ERROR_OUT_OF_MEMORY), "out of memory");
    assert_string_equal(ppm_status_string(PPM_ERROR_PARSE), "parse error");
    assert_string_equal(ppm_status_string(PPM_ERROR_UNSUPPORTED), "unsupported");
    assert_string_equal(ppm_status_string(PPM_ERROR_CANCELLED), "cancelled");
    assert_string_equal(ppm_status_string(PPM_ERROR_INTERNAL), "internal error");
}

static void test_status_values_are_stable(void **state) {
    (void)state;
    assert_int_equal(PPM_OK, 0);
    assert_int_equal(PPM_ERROR_INVALID_ARGUMENT, 1);
    assert_int_equal(PPM_ERROR_INVALID_OPERATION, 2);
    assert_int_equal(PPM_ERROR_OUT_OF_MEMORY, 3);
    assert_int_equal(PPM_ERROR_IO, 4);
    assert_int_equal(PPM_ERROR_PARSE, 5);
    assert_int_equal(PPM_ERROR_UNSUPPORTED, 6);
    assert_int_equal(PPM_ERROR_CANCELLED, 7);
    assert_int_equal(PPM_ERROR_INTERNAL, 8);
}

static void test_status_string_of_unknown_value_is_not_null(void **state) {
    (void)state;
    const char *name = ppm_status_string((ppm_status)12345);
    assert_non_null(name);
    assert_true(name[0] != '\0');
}

static void test_success_clears_last_error(void **state) {
    (void)state;
    assert_ppm_error(ppm_context_create(NULL), PPM_ERROR_INVALID_ARGUMENT, "out_context");
    succeed_once();
    assert_string_equal(ppm_last_error_message(), "");
}

/* Context ------------------------------------------------------------------------------------ */

static void test_context_create_null_out(void **state) {
    (void)state;
    assert_ppm_error(ppm_context_create(NULL), PPM_ERROR_INVALID_ARGUMENT, "out_context");
}

static void test_context_retain_null(void **state) {
    (void)state;
    assert_ppm_error(ppm_context_retain(NULL), PPM_ERROR_INVALID_ARGUMENT, "context");
}

static void test_context_release_null_is_noop(void **state) {
    (void)state;
    ppm_context_release(NULL);
    succeed_once();
}

static void test_context_retain_keeps_it_alive(void **state) {
    (void)state;
    ppm_context context = NULL;
    assert_ppm_ok(ppm_context_create(&context));
    assert_ppm_ok(ppm_context_retain(context));
    ppm_context_release(context);
    assert_ppm_ok(ppm_context_set_int(context, "threads", 1)); /* one reference left */
    int64_t threads = -1;
    assert_ppm_ok(ppm_context_get_int(context, "threads", &threads));
    assert_int_equal(threads, 1);
    ppm_context_release(context);
}

static void test_context_set_int_null_context(void **state) {
    (void)state;
    assert_ppm_error(ppm_context_set_int(NULL, "threads", 1), PPM_ERROR_INVALID_ARGUMENT, "context");
}

static void test_context_set_int_null_key(void **state) {
    fixture *f = *state;
    assert_ppm_error(ppm_context_set_int(f->context, NULL, 1), PPM_ERROR_INVALID_ARGUMENT, "key");
}

static void test_context_set_int_unknown_key_is_named(void **state) {
    fixture *f = *state;
    assert_ppm_error(ppm_context_set_int(f->context, "thraeds", 1), PPM_ERROR_INVALID_ARGUMENT, "thraeds");
    assert_ppm_error(ppm_context_set_int(f->context, "", 1), PPM_ERROR_INVALID_ARGUMENT, "''");
}

static void test_context_threads_out_of_range(void **state) {
    fixture *f = *state;
    assert_ppm_error(ppm_context_set_int(f->context, "threads", -1), PPM_ERROR_INVALID_ARGUMENT, "threads");
    assert_ppm_error(ppm_context_set_int(f->context, "threads", 2000), PPM_ERROR_INVALID_ARGUMENT, "threads");
    assert_ppm_error(ppm_context_set_int(f->context, "threads", 1025), PPM_ERROR_INVALID_ARGUMENT, "1025");
    assert_ppm_error(ppm_context_set_int(f->context, "threads", INT64_MIN), PPM_ERROR_INVALID_ARGUMENT, "threads");
    assert_ppm_error(ppm_context_set_int(f->context, "threads", (int64_t)1 << 40), PPM_ERROR_INVALID_ARGUMENT,
                     "threads");
}

static void test_context_threads_rejected_value_keeps_old_one(void **state) {
    fixture *f = *state;
    assert_ppm_ok(ppm_context_set_int(f->context, "threads", 2));
    assert_ppm_error(ppm_context_set_int(f->context, "threads", -1), PPM_ERROR_INVALID_ARGUMENT, "threads");
    int64_t threads = -1;
    assert_ppm_ok(ppm_context_get_int(f->context, "threads", &threads));
    assert_int_equal(threads, 2);
}

static void test_context_threads_accepts_range_ends(void **state) {
    fixture *f = *state;
    const int64_t values[] = {1024, 1, 0};
    for (size_t i = 0; i < 3; ++i) {
        assert_ppm_ok(ppm_context_set_int(f->context, "threads", values[i]));
        int64_t threads = -1;
        assert_ppm_ok(ppm_context_get_int(f->context, "threads", &threads));
        assert_int_equal(threads, values[i]);
    }
}

static void test_context_threads_default_is_zero(void **state) {
    fixture *f = *state;
    int64_t threads = -1;
    assert_ppm_ok(ppm_context_get_int(f->context, "threads", &threads));
    assert_int_equal(threads, 0);
}

static void test_context_get_int_null_arguments(void **state) {
    fixture *f = *state;
    int64_t value = 77;
    assert_ppm_error(ppm_context_get_int(NULL, "threads", &value), PPM_ERROR_INVALID_ARGUMENT, "context");
    assert_ppm_error(ppm_context_get_int(f->context, NULL, &value), PPM_ERROR_INVALID_ARGUMENT, "key");
    assert_ppm_error(ppm_context_get_int(f->context, "threads", NULL), PPM_ERROR_INVALID_ARGUMENT, "out_value");
    assert_int_equal(value, 77);
}

static void test_context_get_int_unknown_key_is_named(void **state) {
    fixture *f = *state;
    int64_t value = 77;
    assert_ppm_error(ppm_context_get_int(f->context, "tolerance", &value), PPM_ERROR_INVALID_ARGUMENT, "tolerance");
    assert_int_equal(value, 77);
}

static void test_set_error_callback_null_context(void **state) {
    (void)state;
    assert_ppm_error(ppm_context_set_error_callback(NULL, NULL, NULL), PPM_ERROR_INVALID_ARGUMENT, "context");
}

typedef struct callback_log {
    int calls;
    ppm_status status;
    char message[512];
    char last_error_during_call[512];
} callback_log;

static void record_error(void *user_data, ppm_status status, const char *message) {
    callback_log *log = user_data;
    ++log->calls;
    log->status = status;
    strncpy(log->message, message ? message : "(null)", sizeof log->message - 1);
    strncpy(log->last_error_during_call, ppm_last_error_message(), sizeof log->last_error_during_call - 1);
}

static void test_error_callback_receives_status_and_message(void **state) {
    fixture *f = *state;
    callback_log log = {0};
    assert_ppm_ok(ppm_context_set_error_callback(f->context, record_error, &log));
    assert_ppm_error(ppm_context_set_int(f->context, "bogus", 1), PPM_ERROR_INVALID_ARGUMENT, "bogus");
    assert_int_equal(log.calls, 1);
    assert_int_equal(log.status, PPM_ERROR_INVALID_ARGUMENT);
    assert_string_equal(log.message, ppm_last_error_message());
    /* the per-thread message is set before the callback runs */
    assert_string_equal(log.last_error_during_call, log.message);
}

static void test_error_callback_sees_scene_errors(void **state) {
    fixture *f = *state;
    callback_log log = {0};
    assert_ppm_ok(ppm_context_set_error_callback(f->context, record_error, &log));
    assert_ppm_error(ppm_scene_commit(f->scene), PPM_ERROR_INVALID_OPERATION, "");
    assert_int_equal(log.calls, 1);
    assert_int_equal(log.status, PPM_ERROR_INVALID_OPERATION);
    assert_string_equal(log.message, ppm_last_error_message());
}

static void test_error_callback_not_called_on_success(void **state) {
    fixture *f = *state;
    callback_log log = {0};
    assert_ppm_ok(ppm_context_set_error_callback(f->context, record_error, &log));
    add_unit_sphere(f->scene);
    assert_ppm_ok(ppm_scene_commit(f->scene));
    assert_int_equal(log.calls, 0);
}

static void test_error_callback_cleared_with_null(void **state) {
    fixture *f = *state;
    callback_log log = {0};
    assert_ppm_ok(ppm_context_set_error_callback(f->context, record_error, &log));
    assert_ppm_ok(ppm_context_set_error_callback(f->context, NULL, NULL));
    assert_ppm_error(ppm_context_set_int(f->context, "bogus", 1), PPM_ERROR_INVALID_ARGUMENT, "bogus");
    assert_int_equal(log.calls, 0);
}

/* Scene lifetime and settings ------------------------------------------------------------- */

static void test_scene_create_null_arguments(void **state) {
    fixture *f = *state;
    ppm_scene scene = (ppm_scene)(uintptr_t)0x1234;
    assert_ppm_error(ppm_scene_create(NULL, &scene), PPM_ERROR_INVALID_ARGUMENT, "context");
    assert_ptr_equal(scene, (ppm_scene)(uintptr_t)0x1234);
    assert_ppm_error(ppm_scene_create(f->context, NULL), PPM_ERROR_INVALID_ARGUMENT, "out_scene");
}

static void test_scene_retain_null(void **state) {
    (void)state;
    assert_ppm_error(ppm_scene_retain(NULL), PPM_ERROR_INVALID_ARGUMENT, "scene");
}

static void test_scene_release_null_is_noop(void **state) {
    (void)state;
    ppm_scene_release(NULL);
    succeed_once();
}

static void test_scene_keeps_context_alive(void **state) {
    (void)state;
    ppm_context context = NULL;
    ppm_scene scene = NULL;
    assert_ppm_ok(ppm_context_create(&context));
    assert_ppm_ok(ppm_scene_create(context, &scene));
    ppm_context_release(context); /* the scene's reference keeps the device alive */
    commit_with_sphere(scene);
    ppm_ray ray = good_ray();
    ppm_hit hit;
    assert_ppm_ok(ppm_scene_intersect(scene, &ray, 1, &hit));
    assert_int_equal(hit.geom_id, 0);
    assert_true(fabs(hit.t - 4.0) < 1e-12);
    ppm_scene_release(scene);
}

static void test_scene_retain_keeps_it_alive(void **state) {
    (void)state;
    ppm_context context = NULL;
    ppm_scene scene = NULL;
    assert_ppm_ok(ppm_context_create(&context));
    assert_ppm_ok(ppm_scene_create(context, &scene));
    assert_ppm_ok(ppm_scene_retain(scene));
    ppm_scene_release(scene);
    ppm_context_release(context);
    commit_with_sphere(scene); /* one scene reference left, which holds the context */
    double lower[3], upper[3];
    assert_ppm_ok(ppm_scene_get_bounds(scene, lower, upper));
    assert_true(lower[0] == -1 && upper[2] == 1);
    ppm_scene_release(scene);
}

static void test_scene_set_double_null_arguments(void **state) {
    fixture *f = *state;
    assert_ppm_error(ppm_scene_set_double(NULL, "tolerance", 1e-6), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_set_double(f->scene, NULL, 1e-6), PPM_ERROR_INVALID_ARGUMENT, "key");
}

static void test_scene_set_double_unknown_key_is_named(void **state) {
    fixture *f = *state;
    assert_ppm_error(ppm_scene_set_double(f->scene, "tolerence", 1e-6), PPM_ERROR_INVALID_ARGUMENT, "tolerence");
    assert_ppm_error(ppm_scene_set_double(f->scene, "threads", 1), PPM_ERROR_INVALID_ARGUMENT, "threads");
}

static void test_scene_tolerance_out_of_range(void **state) {
    fixture *f = *state;
    const double bad[] = {NAN, 0.0, 1.0, -1e-9, INFINITY, -INFINITY, 1e-15, 0.0200001};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i)
        assert_ppm_error(ppm_scene_set_double(f->scene, "tolerance", bad[i]), PPM_ERROR_INVALID_ARGUMENT, "tolerance");
    double value = 0;
    assert_ppm_ok(ppm_scene_get_double(f->scene, "tolerance", &value));
    assert_true(value == 1e-9);
}

static void test_scene_tolerance_accepts_documented_range(void **state) {
    fixture *f = *state;
    const double good[] = {1e-14, 1e-2, 1e-6};
    for (size_t i = 0; i < 3; ++i) {
        assert_ppm_ok(ppm_scene_set_double(f->scene, "tolerance", good[i]));
        double value = 0;
        assert_ppm_ok(ppm_scene_get_double(f->scene, "tolerance", &value));
        assert_true(value == good[i]);
    }
}

static void test_scene_tolerance_default(void **state) {
    fixture *f = *state;
    double value = 0;
    assert_ppm_ok(ppm_scene_get_double(f->scene, "tolerance", &value));
    assert_true(value == 1e-9);
}

static void test_scene_patch_presplit_default_and_range(void **state) {
    fixture *f = *state;
    double value = 0;
    assert_ppm_ok(ppm_scene_get_double(f->scene, "patch_presplit", &value));
    assert_true(value == 12);
    const double bad[] = {NAN, 0.0, -1.0, 33.0, 2.5, INFINITY, 1e9};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i)
        assert_ppm_error(ppm_scene_set_double(f->scene, "patch_presplit", bad[i]), PPM_ERROR_INVALID_ARGUMENT,
                         "patch_presplit");
    assert_ppm_ok(ppm_scene_get_double(f->scene, "patch_presplit", &value));
    assert_true(value == 12);
    const double good[] = {1, 32, 4};
    for (size_t i = 0; i < 3; ++i) {
        assert_ppm_ok(ppm_scene_set_double(f->scene, "patch_presplit", good[i]));
        assert_ppm_ok(ppm_scene_get_double(f->scene, "patch_presplit", &value));
        assert_true(value == good[i]);
    }
}

static void test_scene_get_double_null_arguments(void **state) {
    fixture *f = *state;
    double value = 42;
    assert_ppm_error(ppm_scene_get_double(NULL, "tolerance", &value), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_get_double(f->scene, NULL, &value), PPM_ERROR_INVALID_ARGUMENT, "key");
    assert_ppm_error(ppm_scene_get_double(f->scene, "tolerance", NULL), PPM_ERROR_INVALID_ARGUMENT, "out_value");
    assert_true(value == 42);
}

static void test_scene_get_double_unknown_key_is_named(void **state) {
    fixture *f = *state;
    double value = 42;
    assert_ppm_error(ppm_scene_get_double(f->scene, "radius", &value), PPM_ERROR_INVALID_ARGUMENT, "radius");
    assert_true(value == 42);
}

/* Adding geometry ------------------------------------------------------------------------- */

/* A flat patch in z = 0 over [0, 1]^2. */
static void flat_patch(double points[48]) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double *p = points + 3 * (4 * i + j);
            p[0] = j / 3.0;
            p[1] = i / 3.0;
            p[2] = 0;
        }
}

static void test_add_patches_null_arguments(void **state) {
    fixture *f = *state;
    double points[48];
    flat_patch(points);
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_bezier_patches(NULL, points, 1, &id), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_add_bezier_patches(f->scene, NULL, 1, &id), PPM_ERROR_INVALID_ARGUMENT,
                     "control_points");
    assert_int_equal(id, 99);
}

static void test_add_patches_zero_count(void **state) {
    fixture *f = *state;
    double points[48];
    flat_patch(points);
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_bezier_patches(f->scene, points, 0, &id), PPM_ERROR_INVALID_ARGUMENT, "patch_count");
    assert_int_equal(id, 99);
}

static void test_add_patches_nan_names_patch_and_point(void **state) {
    fixture *f = *state;
    double points[96];
    flat_patch(points);
    flat_patch(points + 48);
    points[48 + 3 * 5 + 1] = NAN; /* patch 1, control point 5, y */
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_bezier_patches(f->scene, points, 2, &id), PPM_ERROR_INVALID_ARGUMENT,
                     "patch 1 control point 5");
    points[48 + 3 * 5 + 1] = -INFINITY;
    assert_ppm_error(ppm_scene_add_bezier_patches(f->scene, points, 2, &id), PPM_ERROR_INVALID_ARGUMENT,
                     "patch 1 control point 5");
    assert_int_equal(id, 99);
}

static void test_add_patches_returns_id_and_accepts_null_out(void **state) {
    fixture *f = *state;
    double points[48];
    flat_patch(points);
    assert_ppm_ok(ppm_scene_add_bezier_patches(f->scene, points, 1, NULL));
    uint32_t id = 99;
    assert_ppm_ok(ppm_scene_add_bezier_patches(f->scene, points, 1, &id));
    assert_int_equal(id, 1);
}

static void test_load_bpt_null_arguments(void **state) {
    fixture *f = *state;
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_load_bpt(NULL, PPM_TEAPOT, &id), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_load_bpt(f->scene, NULL, &id), PPM_ERROR_INVALID_ARGUMENT, "path");
    assert_int_equal(id, 99);
}

static void test_add_sphere_null_arguments(void **state) {
    fixture *f = *state;
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_sphere(NULL, origin, 1, &id), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_add_sphere(f->scene, NULL, 1, &id), PPM_ERROR_INVALID_ARGUMENT, "center");
    assert_int_equal(id, 99);
}

static void test_add_sphere_non_finite_center(void **state) {
    fixture *f = *state;
    const double nan_center[3] = {0, NAN, 0}, inf_center[3] = {0, 0, INFINITY};
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_sphere(f->scene, nan_center, 1, &id), PPM_ERROR_INVALID_ARGUMENT, "center");
    assert_ppm_error(ppm_scene_add_sphere(f->scene, inf_center, 1, &id), PPM_ERROR_INVALID_ARGUMENT, "center");
    assert_int_equal(id, 99);
}

static void test_add_sphere_bad_radius(void **state) {
    fixture *f = *state;
    const double bad[] = {0.0, -0.0, -1.0, NAN, INFINITY, -INFINITY};
    uint32_t id = 99;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i)
        assert_ppm_error(ppm_scene_add_sphere(f->scene, origin, bad[i], &id), PPM_ERROR_INVALID_ARGUMENT, "radius");
    assert_int_equal(id, 99);
    assert_int_equal(add_unit_sphere(f->scene), 0); /* nothing was added */
}

static void test_add_quad_null_arguments(void **state) {
    fixture *f = *state;
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_quad(NULL, origin, unit_x, unit_y, &id), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_add_quad(f->scene, NULL, unit_x, unit_y, &id), PPM_ERROR_INVALID_ARGUMENT, "origin");
    assert_ppm_error(ppm_scene_add_quad(f->scene, origin, NULL, unit_y, &id), PPM_ERROR_INVALID_ARGUMENT, "edge_u");
    assert_ppm_error(ppm_scene_add_quad(f->scene, origin, unit_x, NULL, &id), PPM_ERROR_INVALID_ARGUMENT, "edge_v");
    assert_int_equal(id, 99);
}

static void test_add_quad_non_finite(void **state) {
    fixture *f = *state;
    const double nan_vector[3] = {NAN, 0, 0}, inf_vector[3] = {0, INFINITY, 0};
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_quad(f->scene, nan_vector, unit_x, unit_y, &id), PPM_ERROR_INVALID_ARGUMENT,
                     "origin");
    assert_ppm_error(ppm_scene_add_quad(f->scene, origin, nan_vector, unit_y, &id), PPM_ERROR_INVALID_ARGUMENT,
                     "edge_u");
    assert_ppm_error(ppm_scene_add_quad(f->scene, origin, unit_x, inf_vector, &id), PPM_ERROR_INVALID_ARGUMENT,
                     "edge_v");
    assert_int_equal(id, 99);
}

static void test_add_quad_without_area(void **state) {
    fixture *f = *state;
    const double zero[3] = {0, 0, 0}, twice_x[3] = {2, 0, 0};
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_quad(f->scene, origin, unit_x, twice_x, &id), PPM_ERROR_INVALID_ARGUMENT, "edge");
    assert_ppm_error(ppm_scene_add_quad(f->scene, origin, zero, unit_y, &id), PPM_ERROR_INVALID_ARGUMENT, "edge");
    assert_ppm_error(ppm_scene_add_quad(f->scene, origin, unit_x, zero, &id), PPM_ERROR_INVALID_ARGUMENT, "edge");
    assert_int_equal(id, 99);
}

static const double tri_positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
static const uint32_t tri_indices[3] = {0, 1, 2};

static void test_add_mesh_null_arguments(void **state) {
    fixture *f = *state;
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_triangle_mesh(NULL, tri_positions, 3, tri_indices, 1, NULL, NULL, &id),
                     PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_add_triangle_mesh(f->scene, NULL, 3, tri_indices, 1, NULL, NULL, &id),
                     PPM_ERROR_INVALID_ARGUMENT, "positions");
    assert_ppm_error(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, NULL, 1, NULL, NULL, &id),
                     PPM_ERROR_INVALID_ARGUMENT, "indices");
    assert_int_equal(id, 99);
}

static void test_add_mesh_zero_counts(void **state) {
    fixture *f = *state;
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 0, tri_indices, 1, NULL, NULL, &id),
                     PPM_ERROR_INVALID_ARGUMENT, "vertices");
    assert_ppm_error(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, tri_indices, 0, NULL, NULL, &id),
                     PPM_ERROR_INVALID_ARGUMENT, "triangles");
    assert_int_equal(id, 99);
}

static void test_add_mesh_non_finite_vertex_is_named(void **state) {
    fixture *f = *state;
    double positions[9];
    memcpy(positions, tri_positions, sizeof positions);
    positions[5] = NAN; /* vertex 1, z */
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_triangle_mesh(f->scene, positions, 3, tri_indices, 1, NULL, NULL, &id),
                     PPM_ERROR_INVALID_ARGUMENT, "vertex 1");
    positions[5] = 0;
    positions[6] = INFINITY; /* vertex 2, x */
    assert_ppm_error(ppm_scene_add_triangle_mesh(f->scene, positions, 3, tri_indices, 1, NULL, NULL, &id),
                     PPM_ERROR_INVALID_ARGUMENT, "vertex 2");
    assert_int_equal(id, 99);
}

static void test_add_mesh_index_out_of_range_is_named(void **state) {
    fixture *f = *state;
    const uint32_t indices[6] = {0, 1, 2, 2, 1, 3};
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, indices, 2, NULL, NULL, &id),
                     PPM_ERROR_INVALID_ARGUMENT, "triangle 1");
    const uint32_t huge[3] = {0, 1, PPM_INVALID_ID};
    assert_ppm_error(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, huge, 1, NULL, NULL, &id),
                     PPM_ERROR_INVALID_ARGUMENT, "triangle 0");
    assert_int_equal(id, 99);
}

static void test_add_mesh_non_finite_normal_is_named(void **state) {
    fixture *f = *state;
    double normals[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    normals[7] = NAN; /* normal 2 */
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, tri_indices, 1, normals, NULL, &id),
                     PPM_ERROR_INVALID_ARGUMENT, "normal 2");
    assert_int_equal(id, 99);
}

static void test_add_mesh_non_finite_uv_is_named(void **state) {
    fixture *f = *state;
    double uvs[6] = {0, 0, 1, 0, 0, 1};
    uvs[3] = INFINITY; /* uv 1 */
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, tri_indices, 1, NULL, uvs, &id),
                     PPM_ERROR_INVALID_ARGUMENT, "uv 1");
    assert_int_equal(id, 99);
}

static void test_add_mesh_zero_area_triangle_is_allowed(void **state) {
    fixture *f = *state;
    const double positions[9] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    uint32_t id = 99;
    assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, positions, 3, tri_indices, 1, NULL, NULL, &id));
    assert_int_equal(id, 0);
}

static void test_load_obj_null_arguments(void **state) {
    fixture *f = *state;
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_load_obj(NULL, "x.obj", &id), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_load_obj(f->scene, NULL, &id), PPM_ERROR_INVALID_ARGUMENT, "path");
    assert_int_equal(id, 99);
}

static void test_geometry_ids_count_from_zero(void **state) {
    fixture *f = *state;
    uint32_t id = 99;
    assert_ppm_ok(ppm_scene_add_sphere(f->scene, origin, 1, &id));
    assert_int_equal(id, 0);
    assert_ppm_ok(ppm_scene_add_quad(f->scene, origin, unit_x, unit_y, &id));
    assert_int_equal(id, 1);
    assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, tri_indices, 1, NULL, NULL, NULL));
    assert_ppm_ok(ppm_scene_add_sphere(f->scene, origin, 2, &id));
    assert_int_equal(id, 3);
}

/* Geometry settings ------------------------------------------------------------------------ */

static void test_set_transform_null_arguments(void **state) {
    fixture *f = *state;
    add_unit_sphere(f->scene);
    double m[16];
    fill_identity(m);
    assert_ppm_error(ppm_scene_set_geometry_transform(NULL, 0, m), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, 0, NULL), PPM_ERROR_INVALID_ARGUMENT, "matrix");
}

static void test_set_transform_bad_geom_id(void **state) {
    fixture *f = *state;
    double m[16];
    fill_identity(m);
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, 0, m), PPM_ERROR_INVALID_ARGUMENT, "geom_id 0");
    add_unit_sphere(f->scene);
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, 1, m), PPM_ERROR_INVALID_ARGUMENT, "geom_id 1");
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, PPM_INVALID_ID, m), PPM_ERROR_INVALID_ARGUMENT,
                     "geom_id 4294967295");
}

static void test_set_transform_projective_last_row(void **state) {
    fixture *f = *state;
    add_unit_sphere(f->scene);
    double m[16];
    fill_identity(m);
    m[14] = 0.5;
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, 0, m), PPM_ERROR_INVALID_ARGUMENT, "last row");
    fill_identity(m);
    m[15] = 2;
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, 0, m), PPM_ERROR_INVALID_ARGUMENT, "last row");
}

static void test_set_transform_singular(void **state) {
    fixture *f = *state;
    assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, tri_indices, 1, NULL, NULL, NULL));
    double m[16];
    fill_identity(m);
    m[10] = 0; /* flattens z */
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, 0, m), PPM_ERROR_INVALID_ARGUMENT, "singular");
    memset(m, 0, sizeof m);
    m[15] = 1;
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, 0, m), PPM_ERROR_INVALID_ARGUMENT, "singular");
}

static void test_set_transform_non_finite_element_is_named(void **state) {
    fixture *f = *state;
    add_unit_sphere(f->scene);
    double m[16];
    fill_identity(m);
    m[7] = NAN;
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, 0, m), PPM_ERROR_INVALID_ARGUMENT, "element 7");
    fill_identity(m);
    m[2] = INFINITY;
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, 0, m), PPM_ERROR_INVALID_ARGUMENT, "element 2");
}

static void test_set_transform_non_uniform_scale_on_sphere(void **state) {
    fixture *f = *state;
    add_unit_sphere(f->scene);
    double m[16];
    fill_identity(m);
    m[0] = 2;
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, 0, m), PPM_ERROR_INVALID_ARGUMENT, "sphere");
    fill_identity(m);
    m[1] = 0.5; /* shear */
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, 0, m), PPM_ERROR_INVALID_ARGUMENT, "sphere");
}

static void test_set_transform_failure_keeps_old_transform(void **state) {
    fixture *f = *state;
    add_unit_sphere(f->scene);
    double m[16];
    fill_identity(m);
    m[3] = 10; /* translate x by 10 */
    assert_ppm_ok(ppm_scene_set_geometry_transform(f->scene, 0, m));
    m[0] = 3; /* now non-uniform */
    assert_ppm_error(ppm_scene_set_geometry_transform(f->scene, 0, m), PPM_ERROR_INVALID_ARGUMENT, "sphere");
    assert_ppm_ok(ppm_scene_commit(f->scene));
    double lower[3], upper[3];
    assert_ppm_ok(ppm_scene_get_bounds(f->scene, lower, upper));
    assert_true(lower[0] == 9 && upper[0] == 11);
}

static void test_set_transform_similarity_on_sphere_is_accepted(void **state) {
    fixture *f = *state;
    add_unit_sphere(f->scene);
    /* rotation by 90 degrees about z, uniform scale 2, translation */
    const double m[16] = {0, -2, 0, 1, 2, 0, 0, 2, 0, 0, 2, 3, 0, 0, 0, 1};
    assert_ppm_ok(ppm_scene_set_geometry_transform(f->scene, 0, m));
}

static void test_set_material_null_scene_and_bad_id(void **state) {
    fixture *f = *state;
    assert_ppm_error(ppm_scene_set_geometry_material(NULL, 0, 1), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_set_geometry_material(f->scene, 0, 1), PPM_ERROR_INVALID_ARGUMENT, "geom_id 0");
    add_unit_sphere(f->scene);
    assert_ppm_ok(ppm_scene_set_geometry_material(f->scene, 0, 1));
    assert_ppm_error(ppm_scene_set_geometry_material(f->scene, 1, 1), PPM_ERROR_INVALID_ARGUMENT, "geom_id 1");
}

static void test_get_primitive_count_null_arguments(void **state) {
    fixture *f = *state;
    add_unit_sphere(f->scene);
    size_t count = 77;
    assert_ppm_error(ppm_scene_get_primitive_count(NULL, 0, &count), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_get_primitive_count(f->scene, 0, NULL), PPM_ERROR_INVALID_ARGUMENT, "out_count");
    assert_ppm_error(ppm_scene_get_primitive_count(f->scene, 1, &count), PPM_ERROR_INVALID_ARGUMENT, "geom_id 1");
    assert_int_equal(count, 77);
    assert_ppm_ok(ppm_scene_get_primitive_count(f->scene, 0, &count));
    assert_int_equal(count, 1);
}

/* Commit and bounds ---------------------------------------------------------------------------- */

static void test_commit_null_scene(void **state) {
    (void)state;
    assert_ppm_error(ppm_scene_commit(NULL), PPM_ERROR_INVALID_ARGUMENT, "scene");
}

static void test_commit_empty_scene(void **state) {
    fixture *f = *state;
    assert_ppm_error(ppm_scene_commit(f->scene), PPM_ERROR_INVALID_OPERATION, "geometry");
    add_unit_sphere(f->scene);
    assert_ppm_ok(ppm_scene_commit(f->scene));
}

static void test_get_bounds_null_arguments(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    double lower[3] = {7, 7, 7}, upper[3] = {7, 7, 7};
    assert_ppm_error(ppm_scene_get_bounds(NULL, lower, upper), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_get_bounds(f->scene, NULL, upper), PPM_ERROR_INVALID_ARGUMENT, "out_lower");
    assert_ppm_error(ppm_scene_get_bounds(f->scene, lower, NULL), PPM_ERROR_INVALID_ARGUMENT, "out_upper");
    assert_true(lower[0] == 7 && upper[0] == 7);
}

static void test_get_bounds_before_commit(void **state) {
    fixture *f = *state;
    double lower[3] = {7, 7, 7}, upper[3] = {7, 7, 7};
    assert_ppm_error(ppm_scene_get_bounds(f->scene, lower, upper), PPM_ERROR_INVALID_OPERATION, "commit");
    add_unit_sphere(f->scene);
    assert_ppm_error(ppm_scene_get_bounds(f->scene, lower, upper), PPM_ERROR_INVALID_OPERATION, "commit");
    assert_true(lower[0] == 7 && upper[0] == 7);
}

static void test_get_bounds_of_sphere(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    double lower[3], upper[3];
    assert_ppm_ok(ppm_scene_get_bounds(f->scene, lower, upper));
    for (int k = 0; k < 3; ++k) {
        assert_true(lower[k] == -1);
        assert_true(upper[k] == 1);
    }
}

/* Queries ------------------------------------------------------------------------------------ */

static void test_intersect_null_arguments(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    ppm_ray ray = good_ray();
    ppm_hit hit;
    assert_ppm_error(ppm_scene_intersect(NULL, &ray, 1, &hit), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_intersect(f->scene, NULL, 1, &hit), PPM_ERROR_INVALID_ARGUMENT, "rays");
    assert_ppm_error(ppm_scene_intersect(f->scene, &ray, 1, NULL), PPM_ERROR_INVALID_ARGUMENT, "hits");
}

static void test_occluded_null_arguments(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    ppm_ray ray = good_ray();
    uint8_t occluded;
    assert_ppm_error(ppm_scene_occluded(NULL, &ray, 1, &occluded), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_scene_occluded(f->scene, NULL, 1, &occluded), PPM_ERROR_INVALID_ARGUMENT, "rays");
    assert_ppm_error(ppm_scene_occluded(f->scene, &ray, 1, NULL), PPM_ERROR_INVALID_ARGUMENT, "occluded");
}

static void test_queries_before_commit(void **state) {
    fixture *f = *state;
    ppm_ray ray = good_ray();
    ppm_hit hit;
    uint8_t occluded = 7;
    assert_ppm_error(ppm_scene_intersect(f->scene, &ray, 1, &hit), PPM_ERROR_INVALID_OPERATION, "not committed");
    assert_ppm_error(ppm_scene_occluded(f->scene, &ray, 1, &occluded), PPM_ERROR_INVALID_OPERATION, "not committed");
    add_unit_sphere(f->scene);
    assert_ppm_error(ppm_scene_intersect(f->scene, &ray, 1, &hit), PPM_ERROR_INVALID_OPERATION, "not committed");
    assert_ppm_error(ppm_scene_occluded(f->scene, &ray, 1, &occluded), PPM_ERROR_INVALID_OPERATION, "not committed");
    assert_int_equal(occluded, 7);
}

static void test_queries_after_change_need_commit(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    ppm_ray ray = good_ray();
    ppm_hit hit;
    assert_ppm_ok(ppm_scene_intersect(f->scene, &ray, 1, &hit));
    add_unit_sphere(f->scene);
    assert_ppm_error(ppm_scene_intersect(f->scene, &ray, 1, &hit), PPM_ERROR_INVALID_OPERATION, "not committed");
    assert_ppm_ok(ppm_scene_commit(f->scene));
    assert_ppm_ok(ppm_scene_set_geometry_material(f->scene, 0, 3));
    assert_ppm_error(ppm_scene_intersect(f->scene, &ray, 1, &hit), PPM_ERROR_INVALID_OPERATION, "not committed");
    assert_ppm_ok(ppm_scene_commit(f->scene));
    assert_ppm_ok(ppm_scene_set_double(f->scene, "tolerance", 1e-6));
    assert_ppm_error(ppm_scene_intersect(f->scene, &ray, 1, &hit), PPM_ERROR_INVALID_OPERATION, "not committed");
    assert_ppm_ok(ppm_scene_commit(f->scene));
    assert_ppm_ok(ppm_scene_set_double(f->scene, "patch_presplit", 3));
    assert_ppm_error(ppm_scene_intersect(f->scene, &ray, 1, &hit), PPM_ERROR_INVALID_OPERATION, "not committed");
}

static void test_queries_with_zero_count_succeed(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    ppm_ray ray = good_ray();
    ppm_hit hit;
    uint8_t occluded;
    assert_ppm_ok(ppm_scene_intersect(f->scene, &ray, 0, &hit));
    assert_ppm_ok(ppm_scene_occluded(f->scene, &ray, 0, &occluded));
}

/* Three good rays with ray 2 spoiled by `spoil`; both queries must name "ray 2". */
static void check_bad_ray(ppm_scene scene, void (*spoil)(ppm_ray *)) {
    ppm_ray rays[3] = {good_ray(), good_ray(), good_ray()};
    spoil(&rays[2]);
    ppm_hit hits[3];
    memset(hits, 0xAB, sizeof hits);
    ppm_hit untouched[3];
    memcpy(untouched, hits, sizeof hits);
    uint8_t occluded[3] = {7, 7, 7};
    assert_ppm_error(ppm_scene_intersect(scene, rays, 3, hits), PPM_ERROR_INVALID_ARGUMENT, "ray 2:");
    assert_memory_equal(hits, untouched, sizeof hits);
    assert_ppm_error(ppm_scene_occluded(scene, rays, 3, occluded), PPM_ERROR_INVALID_ARGUMENT, "ray 2:");
    assert_true(occluded[0] == 7 && occluded[1] == 7 && occluded[2] == 7);
}

static void nan_origin(ppm_ray *r) { r->org[1] = NAN; }
static void inf_origin(ppm_ray *r) { r->org[0] = -INFINITY; }
static void zero_direction(ppm_ray *r) { r->dir[0] = r->dir[1] = r->dir[2] = 0; }
static void inf_direction(ppm_ray *r) { r->dir[2] = -INFINITY; }
static void nan_direction(ppm_ray *r) { r->dir[0] = NAN; }
static void negative_tnear(ppm_ray *r) { r->tnear = -1e-300; }
static void nan_tnear(ppm_ray *r) { r->tnear = NAN; }
static void tnear_above_tfar(ppm_ray *r) { r->tnear = 2, r->tfar = 1; }
static void nan_tfar(ppm_ray *r) { r->tfar = NAN; }

static void test_ray_nan_origin_is_named(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    check_bad_ray(f->scene, nan_origin);
    check_bad_ray(f->scene, inf_origin);
}

static void test_ray_zero_direction_is_named(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    check_bad_ray(f->scene, zero_direction);
}

static void test_ray_non_finite_direction_is_named(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    check_bad_ray(f->scene, inf_direction);
    check_bad_ray(f->scene, nan_direction);
}

static void test_ray_negative_tnear_is_named(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    check_bad_ray(f->scene, negative_tnear);
    check_bad_ray(f->scene, nan_tnear);
}

static void test_ray_tnear_above_tfar_is_named(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    check_bad_ray(f->scene, tnear_above_tfar);
    check_bad_ray(f->scene, nan_tfar);
}

static void test_ray_bad_index_in_large_batch_is_named(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    enum { n = 1000 };
    static ppm_ray rays[n];
    static ppm_hit hits[n];
    for (size_t i = 0; i < n; ++i) rays[i] = good_ray();
    rays[777].dir[0] = rays[777].dir[1] = rays[777].dir[2] = 0;
    assert_ppm_error(ppm_scene_intersect(f->scene, rays, n, hits), PPM_ERROR_INVALID_ARGUMENT, "ray 777:");
}

static void test_ray_with_tnear_equal_tfar_is_valid(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    ppm_ray ray = good_ray();
    ray.tnear = ray.tfar = 1;
    ppm_hit hit;
    assert_ppm_ok(ppm_scene_intersect(f->scene, &ray, 1, &hit));
    assert_int_equal(hit.geom_id, PPM_INVALID_ID);
}

static void test_miss_hit_is_infinity_invalid_id_and_zeros(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    ppm_ray ray = {{0, 0, 5}, 0, {0, 0, 1}, INFINITY};
    ppm_hit hit;
    memset(&hit, 0xAB, sizeof hit);
    assert_ppm_ok(ppm_scene_intersect(f->scene, &ray, 1, &hit));
    assert_true(isinf(hit.t) && hit.t > 0);
    assert_int_equal(hit.geom_id, PPM_INVALID_ID);
    /* "other fields 0" */
    assert_true(hit.u == 0 && hit.v == 0 && hit.p_error == 0);
    for (int k = 0; k < 3; ++k) assert_true(hit.p[k] == 0 && hit.ng[k] == 0 && hit.ns[k] == 0);
    assert_int_equal(hit.prim_id, 0);
    assert_int_equal(hit.material, 0);
    assert_int_equal(hit.reserved, 0);
}

/* ppm_hit_spawn_ray ----------------------------------------------------------------------------- */

static ppm_hit sphere_hit(ppm_scene scene) {
    commit_with_sphere(scene);
    ppm_ray ray = good_ray();
    ppm_hit hit;
    assert_ppm_ok(ppm_scene_intersect(scene, &ray, 1, &hit));
    assert_int_equal(hit.geom_id, 0);
    return hit;
}

static void test_spawn_ray_null_arguments(void **state) {
    fixture *f = *state;
    const ppm_hit hit = sphere_hit(f->scene);
    const double dir[3] = {0, 0, 1};
    ppm_ray out;
    memset(&out, 0xAB, sizeof out);
    ppm_ray untouched = out;
    assert_ppm_error(ppm_hit_spawn_ray(NULL, dir, &out), PPM_ERROR_INVALID_ARGUMENT, "hit");
    assert_ppm_error(ppm_hit_spawn_ray(&hit, NULL, &out), PPM_ERROR_INVALID_ARGUMENT, "dir");
    assert_ppm_error(ppm_hit_spawn_ray(&hit, dir, NULL), PPM_ERROR_INVALID_ARGUMENT, "out_ray");
    assert_memory_equal(&out, &untouched, sizeof out);
}

static void test_spawn_ray_from_miss(void **state) {
    fixture *f = *state;
    commit_with_sphere(f->scene);
    ppm_ray ray = {{0, 0, 5}, 0, {0, 0, 1}, INFINITY};
    ppm_hit miss;
    assert_ppm_ok(ppm_scene_intersect(f->scene, &ray, 1, &miss));
    const double dir[3] = {0, 0, 1};
    ppm_ray out;
    assert_ppm_error(ppm_hit_spawn_ray(&miss, dir, &out), PPM_ERROR_INVALID_ARGUMENT, "miss");
}

static void test_spawn_ray_bad_direction(void **state) {
    fixture *f = *state;
    const ppm_hit hit = sphere_hit(f->scene);
    const double zero[3] = {0, 0, 0}, nan_dir[3] = {0, NAN, 1}, inf_dir[3] = {INFINITY, 0, 0};
    ppm_ray out;
    assert_ppm_error(ppm_hit_spawn_ray(&hit, zero, &out), PPM_ERROR_INVALID_ARGUMENT, "dir");
    assert_ppm_error(ppm_hit_spawn_ray(&hit, nan_dir, &out), PPM_ERROR_INVALID_ARGUMENT, "dir");
    assert_ppm_error(ppm_hit_spawn_ray(&hit, inf_dir, &out), PPM_ERROR_INVALID_ARGUMENT, "dir");
}

static void test_spawn_ray_corrupt_hit(void **state) {
    fixture *f = *state;
    ppm_hit hit = sphere_hit(f->scene);
    const double dir[3] = {0, 0, 1};
    ppm_ray out;
    hit.p[0] = NAN;
    assert_ppm_error(ppm_hit_spawn_ray(&hit, dir, &out), PPM_ERROR_INVALID_ARGUMENT, "hit");
    hit.p[0] = 0;
    hit.p_error = -1;
    assert_ppm_error(ppm_hit_spawn_ray(&hit, dir, &out), PPM_ERROR_INVALID_ARGUMENT, "p_error");
}

static void test_spawn_ray_success_writes_ray(void **state) {
    fixture *f = *state;
    const ppm_hit hit = sphere_hit(f->scene);
    const double dir[3] = {0, 1, 1};
    ppm_ray out;
    assert_ppm_ok(ppm_hit_spawn_ray(&hit, dir, &out));
    assert_true(out.tnear == 0 && isinf(out.tfar) && out.tfar > 0);
    for (int k = 0; k < 3; ++k) assert_true(out.dir[k] == dir[k]);
    assert_true(out.org[2] > hit.p[2]); /* moved outwards, the side dir points to */
}

#define TEST(name) cmocka_unit_test_setup_teardown(name, scene_fixture_setup, scene_fixture_teardown)

int main(void) {
    const struct CMUnitTest tests[] = {
        TEST(test_version_matches_header),
        TEST(test_version_string_matches_header),
        TEST(test_status_string_names_every_status),
        TEST(test_status_values_are_stable),
        TEST(test_status_string_of_unknown_value_is_not_null),
        TEST(test_success_clears_last_error),
        TEST(test_context_create_null_out),
        TEST(test_context_retain_null),
        TEST(test_context_release_null_is_noop),
        TEST(test_context_retain_keeps_it_alive),
        TEST(test_context_set_int_null_context),
        TEST(test_context_set_int_null_key),
        TEST(test_context_set_int_unknown_key_is_named),
        TEST(test_context_threads_out_of_range),
        TEST(test_context_threads_rejected_value_keeps_old_one),
        TEST(test_context_threads_accepts_range_ends),
        TEST(test_context_threads_default_is_zero),
        TEST(test_context_get_int_null_arguments),
        TEST(test_context_get_int_unknown_key_is_named),
        TEST(test_set_error_callback_null_context),
        TEST(test_error_callback_receives_status_and_message),
        TEST(test_error_callback_sees_scene_errors),
        TEST(test_error_callback_not_called_on_success),
        TEST(test_error_callback_cleared_with_null),
        TEST(test_scene_create_null_arguments),
        TEST(test_scene_retain_null),
        TEST(test_scene_release_null_is_noop),
        TEST(test_scene_keeps_context_alive),
        TEST(test_scene_retain_keeps_it_alive),
        TEST(test_scene_set_double_null_arguments),
        TEST(test_scene_set_double_unknown_key_is_named),
        TEST(test_scene_tolerance_out_of_range),
        TEST(test_scene_tolerance_accepts_documented_range),
        TEST(test_scene_tolerance_default),
        TEST(test_scene_patch_presplit_default_and_range),
        TEST(test_scene_get_double_null_arguments),
        TEST(test_scene_get_double_unknown_key_is_named),
        TEST(test_add_patches_null_arguments),
        TEST(test_add_patches_zero_count),
        TEST(test_add_patches_nan_names_patch_and_point),
        TEST(test_add_patches_returns_id_and_accepts_null_out),
        TEST(test_load_bpt_null_arguments),
        TEST(test_add_sphere_null_arguments),
        TEST(test_add_sphere_non_finite_center),
        TEST(test_add_sphere_bad_radius),
        TEST(test_add_quad_null_arguments),
        TEST(test_add_quad_non_finite),
        TEST(test_add_quad_without_area),
        TEST(test_add_mesh_null_arguments),
        TEST(test_add_mesh_zero_counts),
        TEST(test_add_mesh_non_finite_vertex_is_named),
        TEST(test_add_mesh_index_out_of_range_is_named),
        TEST(test_add_mesh_non_finite_normal_is_named),
        TEST(test_add_mesh_non_finite_uv_is_named),
        TEST(test_add_mesh_zero_area_triangle_is_allowed),
        TEST(test_load_obj_null_arguments),
        TEST(test_geometry_ids_count_from_zero),
        TEST(test_set_transform_null_arguments),
        TEST(test_set_transform_bad_geom_id),
        TEST(test_set_transform_projective_last_row),
        TEST(test_set_transform_singular),
        TEST(test_set_transform_non_finite_element_is_named),
        TEST(test_set_transform_non_uniform_scale_on_sphere),
        TEST(test_set_transform_failure_keeps_old_transform),
        TEST(test_set_transform_similarity_on_sphere_is_accepted),
        TEST(test_set_material_null_scene_and_bad_id),
        TEST(test_get_primitive_count_null_arguments),
        TEST(test_commit_null_scene),
        TEST(test_commit_empty_scene),
        TEST(test_get_bounds_null_arguments),
        TEST(test_get_bounds_before_commit),
        TEST(test_get_bounds_of_sphere),
        TEST(test_intersect_null_arguments),
        TEST(test_occluded_null_arguments),
        TEST(test_queries_before_commit),
        TEST(test_queries_after_change_need_commit),
        TEST(test_queries_with_zero_count_succeed),
        TEST(test_ray_nan_origin_is_named),
        TEST(test_ray_zero_direction_is_named),
        TEST(test_ray_non_finite_direction_is_named),
        TEST(test_ray_negative_tnear_is_named),
        TEST(test_ray_tnear_above_tfar_is_named),
        TEST(test_ray_bad_index_in_large_batch_is_named),
        TEST(test_ray_with_tnear_equal_tfar_is_valid),
        TEST(test_miss_hit_is_infinity_invalid_id_and_zeros),
        TEST(test_spawn_ray_null_arguments),
        TEST(test_spawn_ray_from_miss),
        TEST(test_spawn_ray_bad_direction),
        TEST(test_spawn_ray_corrupt_hit),
        TEST(test_spawn_ray_success_writes_ray),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
