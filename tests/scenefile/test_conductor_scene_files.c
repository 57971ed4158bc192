/* SPDX-License-Identifier: Apache-2.0 */
/* conductor (eta/k/material) and roughconductor from JSON, Mitsuba XML and named parameters:
 * Mitsuba's names and defaults load and render; bad values are refused naming the
 * parameter, unknown metals and distributions with a suggestion. */
#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef scene_fixture fixture;

static const char *const metals_json =
    "{\n"
    "  \"integrator\": {\"photons_per_pass\": 2000, \"glossy_gather_alpha\": 0.25},\n"
    "  \"sensor\": {\"fov\": 40, \"film\": {\"width\": 16, \"height\": 16},\n"
    "             \"to_world\": {\"look_at\": {\"origin\": [0, -6, 1], \"target\": [0, 0, 0.5], \"up\": [0, 0, 1]}}},\n"
    "  \"bsdfs\": {\n"
    "    \"gold\": {\"type\": \"conductor\", \"material\": \"Au\"},\n"
    "    \"custom\": {\"type\": \"conductor\", \"eta\": [0.2, 0.9, 1.1], \"k\": 3, \"specular_reflectance\": 0.9},\n"
    "    \"copper\": {\"type\": \"roughconductor\", \"material\": \"Cu\"},\n"
    "    \"brushed\": {\"type\": \"roughconductor\", \"distribution\": \"ggx\", \"alpha_u\": 0.4, \"alpha_v\": 0.1,\n"
    "                \"eta\": 1.5, \"k\": 4, \"sample_visible\": false},\n"
    "    \"wrapped\": {\"type\": \"twosided\", \"bsdf\": {\"type\": \"roughconductor\", \"alpha\": 0.3}}\n"
    "  },\n"
    "  \"shapes\": [\n"
    "    {\"type\": \"rectangle\", \"to_world\": {\"scale\": 5}},\n"
    "    {\"type\": \"sphere\", \"center\": [-2, 0, 0.5], \"radius\": 0.5, \"bsdf\": \"gold\"},\n"
    "    {\"type\": \"sphere\", \"center\": [-1, 0, 0.5], \"radius\": 0.5, \"bsdf\": \"custom\"},\n"
    "    {\"type\": \"sphere\", \"center\": [0, 0, 0.5], \"radius\": 0.5, \"bsdf\": \"copper\"},\n"
    "    {\"type\": \"sphere\", \"center\": [1, 0, 0.5], \"radius\": 0.5, \"bsdf\": \"brushed\"},\n"
    "    {\"type\": \"sphere\", \"center\": [2, 0, 0.5], \"radius\": 0.5, \"bsdf\": \"wrapped\"}\n"
    "  ],\n"
    "  \"emitters\": [{\"type\": \"point\", \"position\": [0, -3, 4], \"intensity\": 40}]\n"
    "}\n";

static const char *const metals_xml =
    "<scene version=\"3.0.0\">\n"
    "  <sensor type=\"perspective\">\n"
    "    <float name=\"fov\" value=\"40\"/>\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, -6, 1\" target=\"0, 0, 0.5\" up=\"0, 0, 1\"/></transform>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"16\"/><integer name=\"height\" value=\"16\"/></film>\n"
    "  </sensor>\n"
    "  <bsdf type=\"roughconductor\" id=\"al\">\n"
    "    <string name=\"material\" value=\"Al\"/><string name=\"distribution\" value=\"ggx\"/>\n"
    "    <float name=\"alpha\" value=\"0.3\"/>\n"
    "  </bsdf>\n"
    "  <bsdf type=\"conductor\" id=\"cr\">\n"
    "    <rgb name=\"eta\" value=\"3.1, 3.2, 2.3\"/><rgb name=\"k\" value=\"3.3, 3.3, 3.1\"/>\n"
    "  </bsdf>\n"
    "  <shape type=\"sphere\"><ref id=\"al\"/></shape>\n"
    "  <shape type=\"sphere\"><point name=\"center\" x=\"1.5\" y=\"0\" z=\"0\"/><ref id=\"cr\"/></shape>\n"
    "  <emitter type=\"point\"><point name=\"position\" x=\"0\" y=\"-3\" z=\"3\"/>"
    "<rgb name=\"intensity\" value=\"20\"/></emitter>\n"
    "</scene>\n";

/* Loads `text`, renders one pass and returns the image's mean (which must be finite, > 0). */
static double load_and_render(fixture *f, const char *text, const char *name) {
    ppm_scene_file file = NULL;
    assert_ppm_ok(ppm_scene_file_load_memory(f->context, text, strlen(text), name, NULL, NULL, &file));
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_scene_file_create_renderer(file, &r));
    assert_ppm_ok(ppm_render_pass(r));
    float rgb[16 * 16 * 3];
    assert_ppm_ok(ppm_renderer_get_layer(r, "radiance", rgb, 16 * 16 * 3));
    double sum = 0;
    for (int i = 0; i < 16 * 16 * 3; ++i) {
        assert_true(isfinite(rgb[i]) && rgb[i] >= 0);
        sum += rgb[i];
    }
    ppm_renderer_release(r);
    ppm_scene_file_release(file);
    return sum / (16 * 16 * 3);
}

static void test_json_metals_load_and_render(void **state) {
    fixture *f = *state;
    assert_true(load_and_render(f, metals_json, "metals.json") > 0);
    /* The file's glossy_gather_alpha reaches the renderer. */
    ppm_scene_file file = NULL;
    assert_ppm_ok(
        ppm_scene_file_load_memory(f->context, metals_json, strlen(metals_json), "metals.json", NULL, NULL, &file));
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_scene_file_create_renderer(file, &r));
    double gather = 0;
    assert_ppm_ok(ppm_renderer_get_double(r, "glossy_gather_alpha", &gather));
    assert_true(gather == 0.25);
    ppm_renderer_release(r);
    ppm_scene_file_release(file);
}

static void test_xml_metals_load_and_render(void **state) {
    fixture *f = *state;
    assert_true(load_and_render(f, metals_xml, "metals.xml") > 0);
}

/* A JSON scene whose one bsdf is `bsdf`: the load fails and the message holds `needle`. */
static void expect_refused(fixture *f, const char *bsdf, const char *needle) {
    char text[1024];
    snprintf(text, sizeof text,
             "{\"bsdfs\": {\"m\": %s}, \"shapes\": [{\"type\": \"sphere\", \"bsdf\": \"m\"}],"
             " \"emitters\": [{\"type\": \"point\", \"position\": [0, 0, 3]}]}",
             bsdf);
    ppm_scene_file file = NULL;
    const ppm_status status = ppm_scene_file_load_memory(f->context, text, strlen(text), "bad.json", NULL, NULL, &file);
    if (status == PPM_OK) fail_msg("accepted: %s", bsdf);
    if (!strstr(ppm_last_error_message(), needle))
        fail_msg("message '%s' for %s does not contain '%s'", ppm_last_error_message(), bsdf, needle);
}

static void test_bad_metals_are_refused(void **state) {
    fixture *f = *state;
    expect_refused(f, "{\"type\": \"conductor\", \"material\": \"Auu\"}", "did you mean 'Au'");
    expect_refused(f, "{\"type\": \"roughconductor\", \"material\": \"Cuu\"}", "did you mean 'Cu'");
    expect_refused(f, "{\"type\": \"conductor\", \"material\": \"Au\", \"eta\": 0.2}", "material");
    expect_refused(f, "{\"type\": \"conductor\", \"eta\": -0.2}", "eta");
    expect_refused(f, "{\"type\": \"conductor\", \"k\": [1, 2]}", "k");
    expect_refused(f, "{\"type\": \"roughconductor\", \"alpha\": 0}", "alpha");
    expect_refused(f, "{\"type\": \"roughconductor\", \"alpha\": -1}", "alpha");
    expect_refused(f, "{\"type\": \"roughconductor\", \"alpha_u\": 0.2}", "alpha_v");
    expect_refused(f, "{\"type\": \"roughconductor\", \"alpha\": 0.2, \"alpha_u\": 0.2, \"alpha_v\": 0.1}", "alpha");
    expect_refused(f, "{\"type\": \"roughconductor\", \"distribution\": \"ggxx\"}", "did you mean 'ggx'");
    expect_refused(f, "{\"type\": \"roughconductor\", \"specular_reflectance\": 2}", "specular_reflectance");
    expect_refused(f, "{\"type\": \"roughconductor\", \"alpah\": 0.2}", "alpah");
}

static void test_named_parameters(void **state) {
    fixture *f = *state;
    const double nan_value = NAN, alpha = 0.3;
    ppm_param p[2];
    memset(p, 0, sizeof p);
    p[0].name = "alpha";
    p[0].type = PPM_PARAM_NUMBERS;
    p[0].numbers = &nan_value;
    p[0].count = 1;
    uint32_t id = 0;
    assert_ppm_error(ppm_scene_add_material(f->scene, "roughconductor", p, 1, &id), PPM_ERROR_INVALID_ARGUMENT,
                     "alpha");
    p[0].numbers = &alpha;
    p[1].name = "material";
    p[1].type = PPM_PARAM_STRING;
    p[1].string = "Ag";
    assert_ppm_ok(ppm_scene_add_material(f->scene, "roughconductor", p, 2, &id));
    assert_ppm_ok(ppm_scene_add_material(f->scene, "conductor", p + 1, 1, &id));
    assert_ppm_error(ppm_scene_add_material(f->scene, "roughconductr", NULL, 0, &id), PPM_ERROR_INVALID_ARGUMENT,
                     "roughconductor");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_json_metals_load_and_render, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_xml_metals_load_and_render, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_bad_metals_are_refused, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_named_parameters, scene_fixture_setup, scene_fixture_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
