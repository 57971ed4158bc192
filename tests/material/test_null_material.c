/* SPDX-License-Identifier: Apache-2.0 */
/* Mitsuba's `null` BSDF: a shape with it is not there for light. A sphere of it between a
 * point light and a diffuse plane, and between the plane and the camera, leaves the plane's
 * closed-form radiance L = rho / pi * I cos(theta) / d^2 in every mode that samples such
 * paths. Shadow rays and connections stop at null surfaces as at a mask's pass-through (the
 * light behind them arrives by photons or merging), so "bpt" alone cannot carry a point
 * light's light through one to a diffuse surface seen through one (docs/scene-format.md). */
#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define SIZE 16

typedef scene_fixture fixture;

static const char *const scene_json =
    "{\"integrator\": {\"photons_per_pass\": 20000},\n"
    " \"sensor\": {\"fov\": 20, \"film\": {\"width\": 16, \"height\": 16},\n"
    "            \"to_world\": {\"look_at\": {\"origin\": [0, 0, 10], \"target\": [0, 0, 0], \"up\": [0, 1, 0]}}},\n"
    " \"bsdfs\": {\"nothing\": {\"type\": \"null\"}, \"grey\": {\"type\": \"diffuse\", \"reflectance\": 0.5}},\n"
    " \"shapes\": [{\"type\": \"rectangle\", \"to_world\": {\"scale\": 20}, \"bsdf\": \"grey\"},\n"
    "            {\"type\": \"sphere\", \"center\": [0, 0, 2], \"radius\": 1, \"bsdf\": \"nothing\"}],\n"
    " \"emitters\": [{\"type\": \"point\", \"position\": [0, 0, 4], \"intensity\": 30}]}\n";

/* The radiance of the plane at pixel (px, py): the pixel centre's ray from (0, 0, 10) meets
 * z = 0 at (x, y); the plane is lit from (0, 0, 4). */
static double expected(int px, int py) {
    const double half = tan(10.0 * M_PI / 180.0); /* fov 20 along x, square pixels */
    const double x = 10 * half * ((px + 0.5) / SIZE * 2 - 1), y = 10 * half * (1 - (py + 0.5) / SIZE * 2);
    const double d2 = x * x + y * y + 16, cos_theta = 4 / sqrt(d2);
    return 0.5 / M_PI * 30 * cos_theta / d2;
}

static void render_and_compare(fixture *f, const char *mode) {
    ppm_scene_file file = NULL;
    assert_ppm_ok(
        ppm_scene_file_load_memory(f->context, scene_json, strlen(scene_json), "null.json", NULL, NULL, &file));
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_scene_file_create_renderer(file, &r));
    assert_ppm_ok(ppm_renderer_set_string(r, "mode", mode));
    for (int pass = 0; pass < 32; ++pass) assert_ppm_ok(ppm_renderer_render_pass(r));
    static float rgb[SIZE * SIZE * 3];
    assert_ppm_ok(ppm_renderer_get_layer(r, "radiance", rgb, SIZE * SIZE * 3));
    double got = 0, want = 0;
    for (int py = 0; py < SIZE; ++py)
        for (int px = 0; px < SIZE; ++px) {
            got += rgb[(py * SIZE + px) * 3 + 1];
            want += expected(px, py);
        }
    /* 32 passes of 256 light subpaths or 20000 photons: within 2 %. */
    if (fabs(got / want - 1) > 0.02) fail_msg("%s: mean %g, closed form %g", mode, got / 256, want / 256);
    ppm_renderer_release(r);
    ppm_scene_file_release(file);
}

static void test_a_null_sphere_casts_no_shadow_and_hides_nothing(void **state) {
    const char *const modes[] = {"sppm", "pppm", "vcm", "vm"};
    for (size_t i = 0; i < sizeof modes / sizeof modes[0]; ++i) render_and_compare(*state, modes[i]);
}

static void test_null_takes_no_parameters(void **state) {
    fixture *f = *state;
    const double one = 1;
    const ppm_param reflectance = {"reflectance", PPM_PARAM_NUMBERS, &one, 1, NULL, 0};
    uint32_t id = 0;
    assert_ppm_error(ppm_scene_add_material(f->scene, "null", &reflectance, 1, &id), PPM_ERROR_INVALID_ARGUMENT,
                     "null material has no parameter 'reflectance'");
    assert_ppm_ok(ppm_scene_add_material(f->scene, "null", NULL, 0, &id));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_a_null_sphere_casts_no_shadow_and_hides_nothing, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_null_takes_no_parameters, scene_fixture_setup, scene_fixture_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
