/* SPDX-License-Identifier: Apache-2.0 */
/* conductor (eta/k/material) and roughconductor from JSON, Mitsuba XML and named parameters:
 * a flat smooth metal under a uniform sky shows the sky times the metal's Fresnel reflectance
 * per channel (gold by name against Mitsuba 3's values, explicit eta and k); a scene renders
 * the same from JSON and from XML; bad values are refused naming the parameter, unknown
 * metals and distributions with a suggestion. */
#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef scene_fixture fixture;

/* Mitsuba 3.9.1's RGB complex index of refraction of gold ("Au"), as its scalar_rgb variant
 * gives it (mi.traverse(mi.load_dict({'type': 'conductor', 'material': 'Au'}))['eta.value'] and
 * ['k.value']): the values libppm's table of named metals must hold. */
static const double gold_eta[3] = {0.143035978, 0.375307083, 1.44204533};
static const double gold_k[3] = {3.98299694, 2.38555646, 1.60335922};

/* Unpolarised Fresnel reflectance of a conductor of complex index eta + i k (relative to the
 * outside) at incidence cos_i, Mitsuba 3's convention: the mean of the s and p reflectances,
 * in the real closed form (Born and Wolf; pbrt-v3's FrConductor), not the library's complex
 * arithmetic. */
static double conductor_reflectance(double cos_i, double eta, double k) {
    const double cos2 = cos_i * cos_i, sin2 = 1 - cos2;
    const double t0 = eta * eta - k * k - sin2;
    const double a2_plus_b2 = sqrt(t0 * t0 + 4 * eta * eta * k * k);
    const double a = sqrt(0.5 * (a2_plus_b2 + t0));
    const double t1 = a2_plus_b2 + cos2, t2 = 2 * cos_i * a;
    const double rs = (t1 - t2) / (t1 + t2);
    const double t3 = cos2 * a2_plus_b2 + sin2 * sin2, t4 = t2 * sin2;
    const double rp = rs * (t3 - t4) / (t3 + t4);
    return 0.5 * (rs + rp);
}

enum { side = 8 };

/* A camera looking at a flat conductor (the rectangle z = 0, 2000 units wide, its normal +z)
 * at `theta_degrees` from the normal, from 10 units away, through a field of view of 0.2
 * degrees, under a uniform sky of radiance `sky`: every camera ray meets the plane within 0.1
 * degrees of theta and its mirror direction leaves the scene, so each pixel is
 * sky * specular_reflectance * R(theta) (no other path reaches the camera).
 * `bsdf` is the material's JSON object. */
static void flat_metal_json(char *out, size_t size, double theta_degrees, const char *bsdf, double sky) {
    const double theta = theta_degrees * 3.14159265358979323846 / 180;
    snprintf(
        out, size,
        "{\"sensor\": {\"fov\": 0.2, \"film\": {\"width\": %d, \"height\": %d},\n"
        "  \"to_world\": {\"look_at\": {\"origin\": [0, %.17g, %.17g], \"target\": [0, 0, 0], \"up\": [0, 1, 0]}}},\n"
        " \"bsdfs\": {\"metal\": %s},\n"
        " \"shapes\": [{\"type\": \"rectangle\", \"to_world\": {\"scale\": 1000}, \"bsdf\": \"metal\"}],\n"
        " \"emitters\": [{\"type\": \"constant\", \"radiance\": %.17g}]}\n",
        side, side, -10 * sin(theta), 10 * cos(theta), bsdf, sky);
}

/* The same scene in Mitsuba 3 XML; `bsdf` is the <bsdf id="metal"> element. */
static void flat_metal_xml(char *out, size_t size, double theta_degrees, const char *bsdf, double sky) {
    const double theta = theta_degrees * 3.14159265358979323846 / 180;
    snprintf(out, size,
             "<scene version=\"3.0.0\">\n"
             "  <sensor type=\"perspective\">\n"
             "    <float name=\"fov\" value=\"0.2\"/>\n"
             "    <transform name=\"to_world\">"
             "<lookat origin=\"0, %.17g, %.17g\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>\n"
             "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"%d\"/>"
             "<integer name=\"height\" value=\"%d\"/><rfilter type=\"box\"/></film>\n"
             "  </sensor>\n"
             "  %s\n"
             "  <shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"1000\"/></transform>"
             "<ref id=\"metal\"/></shape>\n"
             "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"%.17g\"/></emitter>\n"
             "</scene>\n",
             -10 * sin(theta), 10 * cos(theta), side, side, bsdf, sky);
}

/* Loads the scene `text` and renders `passes` passes into `rgb` (side x side x 3). */
static void render(fixture *f, const char *text, const char *name, int passes, float *rgb) {
    ppm_scene_file file = NULL;
    assert_ppm_ok(ppm_scene_file_load_memory(f->context, text, strlen(text), name, NULL, NULL, &file));
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_scene_file_create_renderer(file, &r));
    for (int pass = 0; pass < passes; ++pass) assert_ppm_ok(ppm_render_pass(r));
    assert_ppm_ok(ppm_renderer_get_layer(r, "radiance", rgb, side * side * 3));
    ppm_renderer_release(r);
    ppm_scene_file_release(file);
}

/* The cosine of the angle at which pixel (x, y) of the flat metal's camera meets the plane,
 * through the pixel's centre: the view axis leans theta from the normal toward +y, the image's
 * +x is the world's x axis (at a right angle to the plane of incidence) and row 0 is the top
 * (the upper half of the image looks further from the normal). */
static double incidence_cosine(double theta_degrees, int x, int y) {
    const double theta = theta_degrees * 3.14159265358979323846 / 180;
    const double tan_half_fov = tan(0.1 * 3.14159265358979323846 / 180);
    const double u = (2 * (x + 0.5) / side - 1) * tan_half_fov, v = (1 - 2 * (y + 0.5) / side) * tan_half_fov;
    /* The ray forward + u right + v up, forward = (0, sin, -cos), up = (0, cos, sin). */
    return (cos(theta) - v * sin(theta)) / sqrt(1 + u * u + v * v);
}

/* Every pixel of the flat metal at theta is sky * scale * R of eta + i k per channel at its
 * incidence. A pixel averages its footprint (0.025 degrees) about the centre: 1.5e-4 of R at
 * most on these metals, within the tolerance. */
static void expect_reflectance(const float *rgb, double theta_degrees, const double eta[3], const double k[3],
                               double scale, double sky, const char *what) {
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            for (int c = 0; c < 3; ++c) {
                const double cos_i = incidence_cosine(theta_degrees, x, y);
                const double want = sky * scale * conductor_reflectance(cos_i, eta[c], k[c]);
                const double got = rgb[3 * (y * side + x) + c];
                if (!(fabs(got - want) <= 3e-4 * want))
                    fail_msg("%s at %g degrees, channel %d, pixel (%d, %d): %.7g, expected sky * R = %.7g", what,
                             theta_degrees, c, x, y, got, want);
            }
}

static void test_closed_form_reflectance(void **state) {
    (void)state;
    /* At normal incidence R = ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2); a lossless dielectric
     * (k = 0) at 45 degrees has the mean of Rs and Rp from Snell's law; grazing light is all
     * reflected. */
    for (int c = 0; c < 3; ++c) {
        const double n = gold_eta[c], k = gold_k[c];
        assert_close(conductor_reflectance(1, n, k), ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), 1e-14);
    }
    const double cos_i = sqrt(0.5), cos_t = sqrt(1 - 0.5 / (1.5 * 1.5));
    const double rs = (cos_i - 1.5 * cos_t) / (cos_i + 1.5 * cos_t), rp = (1.5 * cos_i - cos_t) / (1.5 * cos_i + cos_t);
    assert_close(conductor_reflectance(cos_i, 1.5, 0), 0.5 * (rs * rs + rp * rp), 1e-14);
    assert_close(conductor_reflectance(0, 0.2, 3), 1, 1e-12);
}

/* Gold by name shows gold's reflectance per channel at normal incidence and at 60 degrees:
 * red well above blue, as gold looks, so a metal read as a grey (or perfect) mirror fails. */
static void test_named_gold_reflects_its_fresnel_colour(void **state) {
    fixture *f = *state;
    static const double thetas[] = {0, 60};
    for (size_t t = 0; t < sizeof thetas / sizeof thetas[0]; ++t) {
        char text[2048];
        float rgb[side * side * 3];
        flat_metal_json(text, sizeof text, thetas[t], "{\"type\": \"conductor\", \"material\": \"Au\"}", 1);
        render(f, text, "gold.json", 1, rgb);
        expect_reflectance(rgb, thetas[t], gold_eta, gold_k, 1, 1, "gold");
        for (int i = 0; i < side * side; ++i) {
            assert_true(rgb[3 * i] > rgb[3 * i + 1] && rgb[3 * i + 1] > rgb[3 * i + 2]);
            assert_true(rgb[3 * i] - rgb[3 * i + 2] > 0.3);
        }
    }
}

/* eta and k given per channel and as one number, scaled by specular_reflectance, under a sky
 * of radiance 2. */
static void test_explicit_eta_and_k(void **state) {
    fixture *f = *state;
    char text[2048];
    float rgb[side * side * 3];
    const double eta[3] = {0.2, 0.9, 1.1}, k[3] = {3, 3, 3};
    flat_metal_json(text, sizeof text, 45,
                    "{\"type\": \"conductor\", \"eta\": [0.2, 0.9, 1.1], \"k\": 3, \"specular_reflectance\": 0.9}", 2);
    render(f, text, "custom.json", 1, rgb);
    expect_reflectance(rgb, 45, eta, k, 0.9, 2, "eta [0.2, 0.9, 1.1], k 3");

    const double grey_eta[3] = {1.5, 1.5, 1.5}, grey_k[3] = {4, 4, 4};
    flat_metal_json(text, sizeof text, 75, "{\"type\": \"conductor\", \"eta\": 1.5, \"k\": 4}", 1);
    render(f, text, "grey.json", 1, rgb);
    expect_reflectance(rgb, 75, grey_eta, grey_k, 1, 1, "eta 1.5, k 4");
}

/* The same scene as JSON and as Mitsuba XML renders the same image, bit for bit: smooth
 * metals named and explicit, and rough ones (whose image is noisy, so that any difference in
 * what the two files build would show). */
static void test_json_and_xml_give_the_same_image(void **state) {
    fixture *f = *state;
    static const struct {
        const char *json, *xml;
    } metals[] = {
        {"{\"type\": \"conductor\", \"material\": \"Au\"}",
         "<bsdf type=\"conductor\" id=\"metal\"><string name=\"material\" value=\"Au\"/></bsdf>"},
        {"{\"type\": \"conductor\", \"eta\": [3.1, 3.2, 2.3], \"k\": [3.3, 3.3, 3.1]}",
         "<bsdf type=\"conductor\" id=\"metal\"><rgb name=\"eta\" value=\"3.1, 3.2, 2.3\"/>"
         "<rgb name=\"k\" value=\"3.3, 3.3, 3.1\"/></bsdf>"},
        {"{\"type\": \"roughconductor\", \"material\": \"Cu\", \"distribution\": \"ggx\", \"alpha\": 0.3}",
         "<bsdf type=\"roughconductor\" id=\"metal\"><string name=\"material\" value=\"Cu\"/>"
         "<string name=\"distribution\" value=\"ggx\"/><float name=\"alpha\" value=\"0.3\"/></bsdf>"},
        {"{\"type\": \"roughconductor\", \"material\": \"Al\", \"alpha_u\": 0.4, \"alpha_v\": 0.1}",
         "<bsdf type=\"roughconductor\" id=\"metal\"><string name=\"material\" value=\"Al\"/>"
         "<float name=\"alpha_u\" value=\"0.4\"/><float name=\"alpha_v\" value=\"0.1\"/></bsdf>"},
    };
    for (size_t m = 0; m < sizeof metals / sizeof metals[0]; ++m) {
        char json[2048], xml[2048];
        float from_json[side * side * 3], from_xml[side * side * 3];
        flat_metal_json(json, sizeof json, 60, metals[m].json, 1);
        flat_metal_xml(xml, sizeof xml, 60, metals[m].xml, 1);
        render(f, json, "metal.json", 2, from_json);
        render(f, xml, "metal.xml", 2, from_xml);
        for (int i = 0; i < side * side * 3; ++i) {
            assert_true(isfinite(from_json[i]) && from_json[i] > 0);
            if (from_json[i] != from_xml[i])
                fail_msg("%s: value %d is %.9g from JSON, %.9g from XML", metals[m].json, i, from_json[i], from_xml[i]);
        }
    }
}

/* The file's integrator settings reach the renderer. */
static void test_integrator_settings_reach_the_renderer(void **state) {
    fixture *f = *state;
    static const char text[] =
        "{\"integrator\": {\"photons_per_pass\": 2000, \"glossy_gather_alpha\": 0.25},\n"
        " \"bsdfs\": {\"brushed\": {\"type\": \"roughconductor\", \"alpha_u\": 0.4, \"alpha_v\": 0.1}},\n"
        " \"shapes\": [{\"type\": \"sphere\", \"bsdf\": \"brushed\"}],\n"
        " \"emitters\": [{\"type\": \"point\", \"position\": [0, -3, 4], \"intensity\": 40}]}\n";
    ppm_scene_file file = NULL;
    assert_ppm_ok(ppm_scene_file_load_memory(f->context, text, strlen(text), "settings.json", NULL, NULL, &file));
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_scene_file_create_renderer(file, &r));
    double gather = 0;
    assert_ppm_ok(ppm_renderer_get_double(r, "glossy_gather_alpha", &gather));
    assert_true(gather == 0.25);
    int64_t photons = 0;
    assert_ppm_ok(ppm_renderer_get_int(r, "photons_per_pass", &photons));
    assert_int_equal(photons, 2000);
    ppm_renderer_release(r);
    ppm_scene_file_release(file);
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
        cmocka_unit_test(test_closed_form_reflectance),
        cmocka_unit_test_setup_teardown(test_named_gold_reflects_its_fresnel_colour, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_explicit_eta_and_k, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_json_and_xml_give_the_same_image, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_integrator_settings_reach_the_renderer, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_bad_metals_are_refused, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_named_parameters, scene_fixture_setup, scene_fixture_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
