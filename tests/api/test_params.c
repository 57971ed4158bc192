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

static const double kPiParams = 3.14159265358979323846;

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
        {"conductor", string_param("material", "Auu"),
         "'material' 'Auu' is not a known conductor (did you mean 'Au'?)"},
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
    /* Rotations are accepted (a missing file is then the error); a singular to_uv is not. */
    const double rotate[16] = {0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const ppm_param rotated[] = {string_param("filename", "/nonexistent/texture.png"), numbers("to_uv", rotate, 16)};
    assert_ppm_error(ppm_scene_add_texture(f->scene, "bitmap", rotated, 2, NULL), PPM_ERROR_IO, "texture.png");
    const double flat[16] = {1, 2, 0, 0, 2, 4, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const ppm_param singular[] = {string_param("filename", "/nonexistent/texture.png"), numbers("to_uv", flat, 16)};
    assert_ppm_error(ppm_scene_add_texture(f->scene, "bitmap", singular, 2, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "bitmap texture: parameter 'to_uv' is singular");
    const ppm_param bad_filter[] = {string_param("filename", "x.png"), string_param("filter_type", "nearst")};
    assert_ppm_error(ppm_scene_add_texture(f->scene, "bitmap", bad_filter, 2, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "'filter_type' must be one of");
    const ppm_param bad_wrap[] = {string_param("filename", "x.png"), string_param("wrap_mode", "wrap")};
    assert_ppm_error(ppm_scene_add_texture(f->scene, "bitmap", bad_wrap, 2, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "'wrap_mode' must be one of");
    const double two = 2;
    const ppm_param bad_raw[] = {string_param("filename", "x.png"), numbers("raw", &two, 1)};
    assert_ppm_error(ppm_scene_add_texture(f->scene, "bitmap", bad_raw, 2, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "'raw' is a boolean");
}

/* A checkerboard is a texture like a bitmap: any colour parameter takes it. */
static void test_checkerboard_textures(void **state) {
    fixture *f = *state;
    uint32_t texture = PPM_INVALID_ID, material = PPM_INVALID_ID;
    assert_ppm_ok(ppm_scene_add_texture(f->scene, "checkerboard", NULL, 0, &texture));
    const double red[3] = {0.8, 0.1, 0.1}, scale4[16] = {4, 0, 0, 0, 0, 4, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const ppm_param params[] = {numbers("color0", red, 3), numbers("to_uv", scale4, 16)};
    assert_ppm_ok(ppm_scene_add_texture(f->scene, "checkerboard", params, 2, &texture));
    const ppm_param uses[] = {id_param("reflectance", PPM_PARAM_TEXTURE, texture)};
    assert_ppm_ok(ppm_scene_add_material(f->scene, "diffuse", uses, 1, &material));
    const ppm_param base[] = {id_param("diffuse_reflectance", PPM_PARAM_TEXTURE, texture)};
    assert_ppm_ok(ppm_scene_add_material(f->scene, "plastic", base, 1, &material));
    const double negative = -0.5;
    const ppm_param bad = numbers("color1", &negative, 1);
    assert_ppm_error(ppm_scene_add_texture(f->scene, "checkerboard", &bad, 1, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "checkerboard texture: parameter 'color1' must be >= 0");
    const ppm_param misspelt = numbers("colour0", red, 3);
    assert_ppm_error(ppm_scene_add_texture(f->scene, "checkerboard", &misspelt, 1, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "color0");
}

/* Plane z = 0 (4 x 4) of material `plane` under a point light of intensity 2 at (0, 0, 1),
 * seen from (0, 0, 3) with a 60 degree fov at 24 x 24; a quad of material `cover` at z = 1.5
 * between the light and the camera when cover != PPM_INVALID_ID. Writes the image's mean
 * radiance per channel. */
static const double kPlaneLight = 2.0, kCover = 1.5;
static void render_lit_plane(ppm_scene scene, uint32_t plane, uint32_t cover, double mean[3]) {
    const double origin[3] = {-2, -2, 0}, eu[3] = {4, 0, 0}, ev[3] = {0, 4, 0};
    uint32_t id = 0;
    assert_ppm_ok(ppm_scene_add_quad(scene, origin, eu, ev, &id));
    assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, plane));
    if (cover != PPM_INVALID_ID) {
        const double top[3] = {-2, -2, kCover};
        assert_ppm_ok(ppm_scene_add_quad(scene, top, eu, ev, &id));
        assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, cover));
    }
    const double light[3] = {0, 0, 1}, intensity[3] = {kPlaneLight, kPlaneLight, kPlaneLight};
    assert_ppm_ok(ppm_scene_add_point_light(scene, light, intensity, NULL));
    assert_ppm_ok(ppm_scene_commit(scene));
    ppm_camera_v2 camera;
    ppm_camera_v2_init(&camera);
    camera.origin[2] = 3;
    camera.target[2] = 0;
    camera.fov = 60;
    camera.width = camera.height = 24;
    ppm_renderer renderer = NULL;
    assert_ppm_ok(ppm_renderer_create_v2(scene, &camera, &renderer));
    assert_ppm_ok(ppm_renderer_set_int(renderer, "photons_per_pass", 2000));
    for (int pass = 0; pass < 32; ++pass) assert_ppm_ok(ppm_render_pass(renderer));
    float rgb[3 * 24 * 24];
    assert_ppm_ok(ppm_renderer_get_layer(renderer, "radiance", rgb, 3 * 24 * 24));
    ppm_renderer_release(renderer);
    for (int c = 0; c < 3; ++c) {
        mean[c] = 0;
        for (int i = 0; i < 24 * 24; ++i) mean[c] += rgb[3 * i + c] / (24.0 * 24.0);
    }
}

/* The mean over that image of L = rho I cos / (pi d^2) for rho = 1 (8 x 8 samples a pixel). */
static double lit_plane_mean(void) {
    const double t = tan(60 * kPiParams / 360.0);
    double sum = 0;
    for (int y = 0; y < 24 * 8; ++y)
        for (int x = 0; x < 24 * 8; ++x) {
            const double px = (1 - 2 * (x + 0.5) / (24 * 8)) * t * 3, py = (1 - 2 * (y + 0.5) / (24 * 8)) * t * 3;
            const double d2 = px * px + py * py + 1;
            sum += kPlaneLight / kPiParams * (1 / sqrt(d2)) / d2;
        }
    return sum / (24 * 8 * 24 * 8);
}

/* blendbsdf of two diffuse colours renders (1 - w) rho0 + w rho1. */
static void test_blendbsdf_renders_the_weighted_mean(void **state) {
    fixture *f = *state;
    const double rho0[3] = {0.8, 0.2, 0.1}, rho1[3] = {0.1, 0.4, 0.9}, w = 0.3;
    uint32_t d0 = 0, d1 = 0, blend = 0;
    assert_ppm_ok(ppm_scene_add_diffuse_material(f->scene, rho0, &d0));
    assert_ppm_ok(ppm_scene_add_diffuse_material(f->scene, rho1, &d1));
    const ppm_param params[] = {numbers("weight", &w, 1), id_param("bsdf_0", PPM_PARAM_MATERIAL, d0),
                                id_param("bsdf_1", PPM_PARAM_MATERIAL, d1)};
    assert_ppm_ok(ppm_scene_add_material(f->scene, "blendbsdf", params, 3, &blend));
    double mean[3];
    render_lit_plane(f->scene, blend, PPM_INVALID_ID, mean);
    const double unit = lit_plane_mean();
    for (int c = 0; c < 3; ++c) {
        const double expected = ((1 - w) * rho0[c] + w * rho1[c]) * unit;
        print_message("blendbsdf channel %d: mean %.5f, expected %.5f\n", c, mean[c], expected);
        assert_close(mean[c], expected, 0.02 * expected);
    }
}

/* A black mask of opacity o between the camera and the lit plane lets (1 - o) through. */
static void test_mask_passes_light_through(void **state) {
    fixture *f = *state;
    const double rho[3] = {0.8, 0.5, 0.3}, black[3] = {0, 0, 0}, o = 0.4;
    uint32_t plane = 0, ink = 0, mask = 0;
    assert_ppm_ok(ppm_scene_add_diffuse_material(f->scene, rho, &plane));
    assert_ppm_ok(ppm_scene_add_diffuse_material(f->scene, black, &ink));
    const ppm_param params[] = {numbers("opacity", &o, 1), id_param("bsdf", PPM_PARAM_MATERIAL, ink)};
    assert_ppm_ok(ppm_scene_add_material(f->scene, "mask", params, 2, &mask));
    double mean[3];
    render_lit_plane(f->scene, plane, mask, mean);
    const double unit = lit_plane_mean();
    for (int c = 0; c < 3; ++c) {
        const double expected = (1 - o) * rho[c] * unit;
        print_message("mask channel %d: mean %.5f, expected %.5f\n", c, mean[c], expected);
        assert_close(mean[c], expected, 0.02 * expected);
    }
}

/* Given as a colour, the opacity is the mean of its channels, as Mitsuba's RGB variants read
 * a colour where a float is wanted: (0.1, 0.4, 0.7) passes what 0.4 does. */
static void test_mask_opacity_as_a_colour_is_its_mean(void **state) {
    fixture *f = *state;
    const double rho[3] = {0.8, 0.5, 0.3}, black[3] = {0, 0, 0}, o[3] = {0.1, 0.4, 0.7};
    uint32_t plane = 0, ink = 0, mask = 0;
    assert_ppm_ok(ppm_scene_add_diffuse_material(f->scene, rho, &plane));
    assert_ppm_ok(ppm_scene_add_diffuse_material(f->scene, black, &ink));
    const ppm_param params[] = {numbers("opacity", o, 3), id_param("bsdf", PPM_PARAM_MATERIAL, ink)};
    assert_ppm_ok(ppm_scene_add_material(f->scene, "mask", params, 2, &mask));
    double mean[3];
    render_lit_plane(f->scene, plane, mask, mean);
    const double unit = lit_plane_mean();
    for (int c = 0; c < 3; ++c) {
        const double expected = (1 - 0.4) * rho[c] * unit;
        print_message("mask of a colour, channel %d: mean %.5f, expected %.5f\n", c, mean[c], expected);
        assert_close(mean[c], expected, 0.02 * expected);
    }
    const ppm_param two[] = {numbers("opacity", o, 2), id_param("bsdf", PPM_PARAM_MATERIAL, ink)};
    assert_ppm_error(ppm_scene_add_material(f->scene, "mask", two, 2, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "'opacity' must be a number or 3 numbers (r, g, b), not 2 numbers");
}

static void test_blend_and_mask_bad_values(void **state) {
    fixture *f = *state;
    const double grey[3] = {0.5, 0.5, 0.5}, big = 1.5, nan_value = NAN;
    uint32_t d = 0;
    assert_ppm_ok(ppm_scene_add_diffuse_material(f->scene, grey, &d));
    const ppm_param too_big[] = {numbers("weight", &big, 1), id_param("bsdf_0", PPM_PARAM_MATERIAL, d),
                                 id_param("bsdf_1", PPM_PARAM_MATERIAL, d)};
    assert_ppm_error(ppm_scene_add_material(f->scene, "blendbsdf", too_big, 3, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "blendbsdf material: parameter 'weight' must lie in [0, 1]");
    const ppm_param missing[] = {id_param("bsdf_0", PPM_PARAM_MATERIAL, d)};
    assert_ppm_error(ppm_scene_add_material(f->scene, "blendbsdf", missing, 1, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "'bsdf_1' is required");
    const ppm_param dangling[] = {id_param("bsdf_0", PPM_PARAM_MATERIAL, d),
                                  id_param("bsdf_1", PPM_PARAM_MATERIAL, 99)};
    assert_ppm_error(ppm_scene_add_material(f->scene, "blendbsdf", dangling, 2, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "99");
    const ppm_param bad_opacity[] = {numbers("opacity", &nan_value, 1), id_param("bsdf", PPM_PARAM_MATERIAL, d)};
    assert_ppm_error(ppm_scene_add_material(f->scene, "mask", bad_opacity, 2, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "mask material: parameter 'opacity' must be finite");
    uint32_t texture = 0, mask = 0;
    assert_ppm_ok(ppm_scene_add_texture(f->scene, "checkerboard", NULL, 0, &texture));
    const ppm_param textured[] = {id_param("opacity", PPM_PARAM_TEXTURE, texture),
                                  id_param("bsdf", PPM_PARAM_MATERIAL, d)};
    assert_ppm_ok(ppm_scene_add_material(f->scene, "mask", textured, 2, &mask));
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
        cmocka_unit_test_setup_teardown(test_checkerboard_textures, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_blendbsdf_renders_the_weighted_mean, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_mask_passes_light_through, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_mask_opacity_as_a_colour_is_its_mean, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_blend_and_mask_bad_values, scene_fixture_setup, scene_fixture_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
