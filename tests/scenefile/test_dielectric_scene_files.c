/* SPDX-License-Identifier: Apache-2.0 */
/* thindielectric, roughdielectric and roughplastic read from JSON and Mitsuba XML scene files
 * (through ppm_scene_add_material's table) and rendered for one pass; bad parameters are
 * errors naming the parameter. */
#include <ppm/ppm.h>

#include "test_support.h"

#include <math.h>
#include <string.h>

static const char *const json_scene =
    "{ \"version\": 1,\n"
    "  \"integrator\": { \"type\": \"sppm\", \"passes\": 1, \"photons_per_pass\": 2000 },\n"
    "  \"sensor\": { \"type\": \"perspective\", \"fov\": 45, \"film\": { \"width\": 16, \"height\": 12 },\n"
    "    \"to_world\": { \"look_at\": { \"origin\": [0, 0, 4], \"target\": [0, 0, 0], \"up\": [0, 1, 0] } } },\n"
    "  \"bsdfs\": {\n"
    "    \"sheet\": { \"type\": \"thindielectric\", \"int_ior\": 1.5 },\n"
    "    \"frosted\": { \"type\": \"roughdielectric\", \"distribution\": \"ggx\", \"alpha_u\": 0.1, \"alpha_v\": 0.3 "
    "},\n"
    "    \"satin\": { \"type\": \"roughplastic\", \"alpha\": 0.2, \"diffuse_reflectance\": [0.8, 0.2, 0.1] },\n"
    "    \"grey\": { \"type\": \"diffuse\" } },\n"
    "  \"emitters\": [ { \"type\": \"point\", \"position\": [0, 2, 2], \"intensity\": 5 } ],\n"
    "  \"shapes\": [\n"
    "    { \"type\": \"sphere\", \"center\": [-1, 0, 0], \"radius\": 0.4, \"bsdf\": \"sheet\" },\n"
    "    { \"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 0.4, \"bsdf\": \"frosted\" },\n"
    "    { \"type\": \"sphere\", \"center\": [1, 0, 0], \"radius\": 0.4, \"bsdf\": \"satin\" },\n"
    "    { \"type\": \"rectangle\", \"bsdf\": \"grey\", \"to_world\": [{ \"scale\": 4 }, { \"translate\": [0, 0, -1] "
    "}] }\n"
    "  ] }\n";

static const char *const xml_scene =
    "<scene version=\"3.0.0\">\n"
    "  <integrator type=\"path\"/>\n"
    "  <sensor type=\"perspective\"><float name=\"fov\" value=\"45\"/>\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, 0, 4\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"16\"/><integer name=\"height\" value=\"12\"/></film>\n"
    "  </sensor>\n"
    "  <bsdf type=\"thindielectric\" id=\"sheet\"><string name=\"int_ior\" value=\"bk7\"/></bsdf>\n"
    "  <bsdf type=\"roughdielectric\" id=\"frosted\"><string name=\"distribution\" value=\"beckmann\"/>\n"
    "    <float name=\"alpha\" value=\"0.2\"/><string name=\"int_ior\" value=\"water\"/></bsdf>\n"
    "  <bsdf type=\"twosided\" id=\"satin\"><bsdf type=\"roughplastic\">\n"
    "    <rgb name=\"diffuse_reflectance\" value=\"0.2, 0.5, 0.8\"/><float name=\"alpha\" "
    "value=\"0.3\"/></bsdf></bsdf>\n"
    "  <emitter type=\"point\"><point name=\"position\" x=\"0\" y=\"2\" z=\"2\"/>\n"
    "    <rgb name=\"intensity\" value=\"5\"/></emitter>\n"
    "  <shape type=\"sphere\"><point name=\"center\" x=\"-1\" y=\"0\" z=\"0\"/><float name=\"radius\" value=\"0.4\"/>\n"
    "    <ref id=\"sheet\"/></shape>\n"
    "  <shape type=\"sphere\"><point name=\"center\" x=\"0\" y=\"0\" z=\"0\"/><float name=\"radius\" value=\"0.4\"/>\n"
    "    <ref id=\"frosted\"/></shape>\n"
    "  <shape type=\"sphere\"><point name=\"center\" x=\"1\" y=\"0\" z=\"0\"/><float name=\"radius\" value=\"0.4\"/>\n"
    "    <ref id=\"satin\"/></shape>\n"
    "</scene>\n";

static ppm_status load(ppm_context context, const char *text, ppm_scene_file *file) {
    return ppm_scene_file_load_memory(context, text, strlen(text), "dielectrics", NULL, NULL, file);
}

static void render_one_pass(ppm_scene_file file) {
    ppm_renderer renderer = NULL;
    assert_int_equal(ppm_scene_file_create_renderer(file, &renderer), PPM_OK);
    assert_int_equal(ppm_render_pass(renderer), PPM_OK);
    ppm_renderer_release(renderer);
}

static void test_json_and_xml_load_and_render(void **state) {
    (void)state;
    ppm_context context = NULL;
    assert_int_equal(ppm_context_create(&context), PPM_OK);
    ppm_scene_file file = NULL;
    if (load(context, json_scene, &file) != PPM_OK) fail_msg("%s", ppm_last_error_message());
    render_one_pass(file);
    ppm_scene_file_release(file);
    file = NULL;
    if (load(context, xml_scene, &file) != PPM_OK) fail_msg("%s", ppm_last_error_message());
    render_one_pass(file);
    ppm_scene_file_release(file);
    ppm_context_release(context);
}

static void expect_material_error(ppm_scene scene, const char *type, const ppm_param *params, size_t count,
                                  const char *fragment) {
    uint32_t id = 0;
    assert_int_equal(ppm_scene_add_material(scene, type, params, count, &id), PPM_ERROR_INVALID_ARGUMENT);
    if (!strstr(ppm_last_error_message(), fragment)) fail_msg("'%s' lacks '%s'", ppm_last_error_message(), fragment);
}

static ppm_param number(const char *name, const double *value) {
    ppm_param p;
    memset(&p, 0, sizeof p);
    p.name = name;
    p.type = PPM_PARAM_NUMBERS;
    p.numbers = value;
    p.count = 1;
    return p;
}

static void test_bad_parameters_name_themselves(void **state) {
    (void)state;
    ppm_context context = NULL;
    ppm_scene scene = NULL;
    assert_int_equal(ppm_context_create(&context), PPM_OK);
    assert_int_equal(ppm_scene_create(context, &scene), PPM_OK);
    const double negative = -0.1, nan = NAN, one = 1.0, small = 0.1;
    ppm_param p[2];
    p[0] = number("alpha", &negative);
    expect_material_error(scene, "roughdielectric", p, 1, "alpha");
    p[0] = number("alpha", &nan);
    expect_material_error(scene, "roughplastic", p, 1, "alpha");
    p[0] = number("int_ior", &one);
    p[1] = number("ext_ior", &one);
    expect_material_error(scene, "thindielectric", p, 2, "differ");
    p[0] = number("alpha_u", &small);
    expect_material_error(scene, "roughdielectric", p, 1, "alpha_v");
    expect_material_error(scene, "roughplastic", p, 1, "alpha_u"); /* isotropic only */
    p[0] = number("alpha", &small);
    p[1] = number("alpha_u", &small);
    expect_material_error(scene, "roughdielectric", p, 2, "not both");
    uint32_t id = 0;
    assert_int_equal(ppm_scene_add_material(scene, "roughplastic", NULL, 0, &id), PPM_OK); /* Mitsuba's defaults */
    assert_int_equal(ppm_scene_add_material(scene, "roughdielectric", NULL, 0, &id), PPM_OK);
    assert_int_equal(ppm_scene_add_material(scene, "thindielectric", NULL, 0, &id), PPM_OK);
    ppm_scene_release(scene);
    ppm_context_release(context);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_json_and_xml_load_and_render),
        cmocka_unit_test(test_bad_parameters_name_themselves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
