/* SPDX-License-Identifier: Apache-2.0 */
/* The Mitsuba XML corpus (tests/data/mitsuba/): scenes written for libppm's tests, one per
 * construct that real Mitsuba 3 scenes use, each of which tools/validate/compare_corpus.py
 * also renders with Mitsuba. Here every one loads without a warning beyond the integrator
 * note, renders a finite, non-negative, lit image in the default mode, and shows what its
 * construct means: the folders of <path>, the principal point offset, the frame of a lookat
 * without an up vector, the top-level area emitter referred to by id, the pixel filters. */
#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define CORPUS PPM_TEST_DATA_DIR "/mitsuba/"

static int unexpected_warnings;

static void count_warning(void *user_data, const char *message) {
    (void)user_data;
    /* Each scene names Mitsuba's path tracer, which libppm renders in its own default mode. */
    if (!strstr(message, "integrator 'path' read as \"render this scene\"")) {
        print_message("unexpected warning: %s\n", message);
        ++unexpected_warnings;
    }
}

/* Loads `name`, renders 2 passes at 16 x 16 and checks the image; returns the file. */
static ppm_scene_file load_and_render(ppm_context context, const char *name) {
    char path[512];
    snprintf(path, sizeof path, "%s%s", CORPUS, name);
    unexpected_warnings = 0;
    ppm_scene_file file = NULL;
    assert_ppm_ok(ppm_scene_file_load(context, path, &file));
    assert_int_equal(unexpected_warnings, 0);
    ppm_camera_v2 camera;
    ppm_camera_v2_init(&camera);
    assert_ppm_ok(ppm_scene_file_get_camera_v2(file, &camera));
    camera.width = camera.height = 16;
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_scene_file_create_renderer_v2(file, &camera, &r));
    for (int pass = 0; pass < 2; ++pass) assert_ppm_ok(ppm_renderer_render_pass(r));
    float rgb[3 * 16 * 16];
    assert_ppm_ok(ppm_renderer_get_layer(r, "radiance", rgb, 3 * 16 * 16));
    double sum = 0;
    for (int i = 0; i < 3 * 16 * 16; ++i) {
        assert_true(isfinite(rgb[i]) && rgb[i] >= 0);
        sum += rgb[i];
    }
    print_message("%s: image mean %.4f\n", name, sum / (3 * 16 * 16));
    assert_true(sum > 0);
    ppm_renderer_release(r);
    return file;
}

static void every_corpus_scene_loads_and_renders(void **state) {
    scene_fixture *f = *state;
    assert_ppm_ok(ppm_context_set_warning_callback(f->context, count_warning, NULL));
    const char *const names[] = {"area_emitter_reference.xml", "lookat_without_up.xml", "path_search.xml",
                                 "pixel_filter_default.xml",   "pixel_filter_tent.xml", "plastic_nonlinear.xml",
                                 "principal_point.xml",        "spot_wide.xml"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
        ppm_scene_file file = load_and_render(f->context, names[i]);
        ppm_camera_v2 camera;
        ppm_camera_v2_init(&camera);
        assert_ppm_ok(ppm_scene_file_get_camera_v2(file, &camera));
        ppm_scene scene = NULL;
        assert_ppm_ok(ppm_scene_file_get_scene(file, &scene));
        size_t geometries = 0;
        assert_ppm_ok(ppm_scene_get_geometry_count(scene, &geometries));
        if (strcmp(names[i], "principal_point.xml") == 0)
            assert_true(camera.principal_point_offset_x == 0.2 && camera.principal_point_offset_y == -0.15);
        else
            assert_true(camera.principal_point_offset_x == 0 && camera.principal_point_offset_y == 0);
        if (strcmp(names[i], "lookat_without_up.xml") == 0) {
            /* Looking down -y, Mitsuba's coordinate_system gives up = (1, 0, 0). */
            assert_close(camera.up[0], 1, 1e-12);
            assert_close(camera.up[1], 0, 1e-12);
        }
        /* The room's five walls, the lamp (or the sphere) and the cube found through <path>. */
        if (strcmp(names[i], "path_search.xml") == 0 || strstr(names[i], "pixel_filter_") == names[i])
            assert_int_equal(geometries, 7);
        /* No rfilter: Mitsuba's gaussian; the tent keeps its radius; the others are boxes. */
        const unsigned filter = strcmp(names[i], "pixel_filter_default.xml") == 0 ? PPM_PIXEL_FILTER_GAUSSIAN
                                : strcmp(names[i], "pixel_filter_tent.xml") == 0  ? PPM_PIXEL_FILTER_TENT
                                                                                  : PPM_PIXEL_FILTER_BOX;
        assert_int_equal(camera.pixel_filter, filter);
        if (filter == PPM_PIXEL_FILTER_TENT) assert_true(camera.pixel_filter_parameter == 1.5);
        if (strcmp(names[i], "area_emitter_reference.xml") == 0) {
            ppm_renderer r = NULL;
            assert_ppm_ok(ppm_scene_file_create_renderer(file, &r));
            int64_t lights = 0;
            assert_ppm_ok(ppm_renderer_get_int(r, "lights", &lights));
            assert_int_equal(lights, 1); /* the lamp emits the emitter it refers to */
            ppm_renderer_release(r);
        }
        ppm_scene_release(scene);
        ppm_scene_file_release(file);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(every_corpus_scene_loads_and_renders, scene_fixture_setup,
                                        scene_fixture_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
