/* SPDX-License-Identifier: Apache-2.0 */
/* Materials, textures and lights by type name and named parameters (ppm_scene_add_material,
 * _texture, _light): a type made this way renders exactly as the typed call makes it, and
 * every misuse of a parameter (unknown, misspelt, repeated, of the wrong kind or size, out of
 * range, NaN) is refused with a message naming it. */
#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef scene_fixture fixture;

static ppm_param numbers(const char *name, const double *values, size_t count) {
    ppm_param p;
    memset(&p, 0, sizeof p);
    p.name = name;
    p.type = PPM_PARAM_NUMBERS;
    p.numbers = values;
    p.count = count;
    return p;
}

static ppm_param string_param(const char *name, const char *value) {
    ppm_param p;
    memset(&p, 0, sizeof p);
    p.name = name;
    p.type = PPM_PARAM_STRING;
    p.string = value;
    return p;
}

static ppm_param id_param(const char *name, ppm_param_type type, uint32_t id) {
    ppm_param p;
    memset(&p, 0, sizeof p);
    p.name = name;
    p.type = type;
    p.id = id;
    return p;
}

/* A 16x12 image of a unit sphere of material `material` lit by light `light` already in the
 * scene; 2 passes, fixed seed. The caller frees the pixels. */
static float *render_sphere(ppm_context context, uint32_t (*build)(ppm_scene)) {
    ppm_scene scene = NULL;
    assert_ppm_ok(ppm_scene_create(context, &scene));
    const double centre[3] = {0, 0, 0};
    uint32_t sphere = 0;
    assert_ppm_ok(ppm_scene_add_sphere(scene, centre, 1.0, &sphere));
    assert_ppm_ok(ppm_scene_set_geometry_material(scene, sphere, build(scene)));
    assert_ppm_ok(ppm_scene_commit(scene));
    ppm_camera_v2 camera;
    ppm_camera_v2_init(&camera);
    camera.origin[2] = 5;
    camera.target[2] = 0;
    camera.width = 16;
    camera.height = 12;
    ppm_renderer renderer = NULL;
    assert_ppm_ok(ppm_renderer_create_v2(scene, &camera, &renderer));
    assert_ppm_ok(ppm_renderer_set_int(renderer, "photons_per_pass", 2000));
    for (int pass = 0; pass < 2; ++pass) assert_ppm_ok(ppm_render_pass(renderer));
    float *rgb = malloc(sizeof(float) * 3 * 16 * 12);
    assert_non_null(rgb);
    assert_ppm_ok(ppm_renderer_get_layer(renderer, "radiance", rgb, 3 * 16 * 12));
    ppm_renderer_release(renderer);
    ppm_scene_release(scene);
    return rgb;
}

static const double kLightPosition[3] = {1, 2, 3}, kIntensity[3] = {6, 5, 4};

static uint32_t typed_plastic_under_point_light(ppm_scene scene) {
    assert_ppm_ok(ppm_scene_add_point_light(scene, kLightPosition, kIntensity, NULL));
    const double colour[3] = {0.7, 0.4, 0.2};
    uint32_t id = 0;
    assert_ppm_ok(ppm_scene_add_coated_material(scene, colour, 1.6, 1.0, &id));
    return id;
}

static uint32_t named_plastic_under_point_light(ppm_scene scene) {
    /* The point light placed by to_world, as Mitsuba allows. */
    const double to_world[16] = {1, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1};
    const ppm_param light[] = {numbers("to_world", to_world, 16), numbers("intensity", kIntensity, 3)};
    assert_ppm_ok(ppm_scene_add_light(scene, "point", light, 2, NULL));
    const double colour[3] = {0.7, 0.4, 0.2}, int_ior = 1.6, ext_ior = 1.0;
    const ppm_param plastic[] = {numbers("diffuse_reflectance", colour, 3), numbers("int_ior", &int_ior, 1),
                                 numbers("ext_ior", &ext_ior, 1)};
    uint32_t id = 0;
    assert_ppm_ok(ppm_scene_add_material(scene, "plastic", plastic, 3, &id));
    /* twosided wraps it: a copy under a new id. */
    const ppm_param wrapped = id_param("bsdf", PPM_PARAM_MATERIAL, id);
    uint32_t outer = 0;
    assert_ppm_ok(ppm_scene_add_material(scene, "twosided", &wrapped, 1, &outer));
    assert_int_equal(outer, id + 1);
    return outer;
}

static void test_named_parameters_render_as_the_typed_calls(void **state) {
    fixture *f = *state;
    float *typed = render_sphere(f->context, typed_plastic_under_point_light);
    float *named = render_sphere(f->context, named_plastic_under_point_light);
    double sum = 0;
    for (int i = 0; i < 3 * 16 * 12; ++i) {
        assert_true(typed[i] == named[i]);
        sum += typed[i];
    }
    assert_true(sum > 0); /* the sphere is lit */
    free(typed);
    free(named);
}

static void test_defaults_are_mitsubas(void **state) {
    fixture *f = *state;
    /* No parameters at all: every type has its Mitsuba defaults. */
    uint32_t id = 99;
    assert_ppm_ok(ppm_scene_add_material(f->scene, "diffuse", NULL, 0, &id));
    assert_int_equal(id, 0);
    assert_ppm_ok(ppm_scene_add_material(f->scene, "dielectric", NULL, 0, &id));
    assert_ppm_ok(ppm_scene_add_material(f->scene, "conductor", NULL, 0, &id));
    assert_ppm_ok(ppm_scene_add_material(f->scene, "plastic", NULL, 0, &id));
    assert_int_equal(id, 3);
    assert_ppm_ok(ppm_scene_add_light(f->scene, "point", NULL, 0, &id));
    assert_ppm_ok(ppm_scene_add_light(f->scene, "spot", NULL, 0, &id));
    assert_int_equal(id, 1);
}

static void test_unknown_types_and_names_get_suggestions(void **state) {
    fixture *f = *state;
    assert_ppm_error(ppm_scene_add_material(f->scene, "difuse", NULL, 0, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "unknown material type 'difuse' (did you mean 'diffuse'?)");
    assert_ppm_error(ppm_scene_add_light(f->scene, "pointt", NULL, 0, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "did you mean 'point'?");
    assert_ppm_error(ppm_scene_add_texture(f->scene, "bitmpa", NULL, 0, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "did you mean 'bitmap'?");
    assert_ppm_error(ppm_scene_add_material(f->scene, NULL, NULL, 0, NULL), PPM_ERROR_INVALID_ARGUMENT, "NULL");
    assert_ppm_error(ppm_scene_add_material(NULL, "diffuse", NULL, 0, NULL), PPM_ERROR_INVALID_ARGUMENT, "NULL");

    const double half = 0.5;
    const ppm_param misspelt = numbers("reflectanse", &half, 1);
    assert_ppm_error(ppm_scene_add_material(f->scene, "diffuse", &misspelt, 1, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "diffuse material has no parameter 'reflectanse' (did you mean 'reflectance'?)");
    const ppm_param foreign = numbers("int_ior", &half, 1);
    assert_ppm_error(ppm_scene_add_material(f->scene, "diffuse", &foreign, 1, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "has no parameter 'int_ior'");
    /* Nothing was added by the failed calls. */
    uint32_t id = 99;
    assert_ppm_ok(ppm_scene_add_material(f->scene, "diffuse", NULL, 0, &id));
    assert_int_equal(id, 0);
}

static void test_bad_values_name_the_parameter(void **state) {
    fixture *f = *state;
    const double bright[3] = {0.5, 1.5, 0.5}, negative = -1, nan_value = NAN, two[2] = {1, 2}, ok = 0.5;
    struct {
        const char *type;
        ppm_param param;
        const char *needle;
    } cases[] = {
        {"diffuse", numbers("reflectance", bright, 3), "'reflectance' must be at most 1"},
        {"diffuse", numbers("reflectance", &nan_value, 1), "'reflectance' must be finite"},
        {"diffuse", numbers("reflectance", two, 2), "'reflectance' must be a colour (1 or 3 numbers)"},
        {"diffuse", string_param("reflectance", "red"), "'reflectance' must be a colour"},
        {"dielectric", numbers("int_ior", &negative, 1), "'int_ior' must be > 0"},
        {"dielectric", string_param("int_ior", "bk7"), "'int_ior' must be a number, not a string"},
        {"plastic", numbers("nonlinear", &ok, 1), "'nonlinear' is a boolean"},
        {"conductor", string_param("material", "Au"), "'material' must be one of none"},
        {"twosided", numbers("bsdf", &ok, 1), "'bsdf' must be a material id"},
        {"twosided", id_param("bsdf", PPM_PARAM_MATERIAL, 7), "material id 7 does not exist"},
        {"diffuse", id_param("reflectance", PPM_PARAM_TEXTURE, 3), "texture id 3 does not exist"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
        assert_ppm_error(ppm_scene_add_material(f->scene, cases[i].type, &cases[i].param, 1, NULL),
                         PPM_ERROR_INVALID_ARGUMENT, cases[i].needle);
    assert_ppm_error(ppm_scene_add_material(f->scene, "twosided", NULL, 0, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "'bsdf' is required");

    const double huge = 1e30, cutoff = 10, beam = 20;
    const ppm_param too_bright = numbers("intensity", &huge, 1);
    assert_ppm_error(ppm_scene_add_light(f->scene, "point", &too_bright, 1, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "'intensity' exceeds the limit");
    const ppm_param spot[] = {numbers("cutoff_angle", &cutoff, 1), numbers("beam_width", &beam, 1)};
    assert_ppm_error(ppm_scene_add_light(f->scene, "spot", spot, 2, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "'beam_width' must lie in [0, 10]");
    const double projective[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1};
    const ppm_param bad_matrix = numbers("to_world", projective, 16);
    assert_ppm_error(ppm_scene_add_light(f->scene, "spot", &bad_matrix, 1, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "'to_world' must be affine");
}

static void test_malformed_lists_are_refused(void **state) {
    fixture *f = *state;
    const double half = 0.5;
    const ppm_param twice[] = {numbers("reflectance", &half, 1), numbers("reflectance", &half, 1)};
    assert_ppm_error(ppm_scene_add_material(f->scene, "diffuse", twice, 2, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "'reflectance' is given twice");
    ppm_param unnamed = numbers(NULL, &half, 1);
    assert_ppm_error(ppm_scene_add_material(f->scene, "diffuse", &unnamed, 1, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "parameter 0 has no name");
    ppm_param no_numbers = numbers("reflectance", NULL, 3);
    assert_ppm_error(ppm_scene_add_material(f->scene, "diffuse", &no_numbers, 1, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "numbers NULL");
    ppm_param null_string = string_param("material", NULL);
    assert_ppm_error(ppm_scene_add_material(f->scene, "conductor", &null_string, 1, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "is a string, but NULL");
    ppm_param bad_kind = numbers("reflectance", &half, 1);
    bad_kind.type = (ppm_param_type)42;
    assert_ppm_error(ppm_scene_add_material(f->scene, "diffuse", &bad_kind, 1, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "unknown type 42");
    assert_ppm_error(ppm_scene_add_material(f->scene, "diffuse", NULL, 2, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "params is NULL");
}

static void test_bitmap_textures(void **state) {
    fixture *f = *state;
    const ppm_param missing = string_param("filename", "/nonexistent/texture.png");
    assert_ppm_error(ppm_scene_add_texture(f->scene, "bitmap", &missing, 1, NULL), PPM_ERROR_IO, "texture.png");
    assert_ppm_error(ppm_scene_add_texture(f->scene, "bitmap", NULL, 0, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "'filename' is required");
    const double rotate[16] = {0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const ppm_param rotated[] = {string_param("filename", "/nonexistent/texture.png"), numbers("to_uv", rotate, 16)};
    assert_ppm_error(ppm_scene_add_texture(f->scene, "bitmap", rotated, 2, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "'to_uv' may only scale and translate");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_named_parameters_render_as_the_typed_calls, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_defaults_are_mitsubas, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_unknown_types_and_names_get_suggestions, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_bad_values_name_the_parameter, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_malformed_lists_are_refused, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_bitmap_textures, scene_fixture_setup, scene_fixture_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
