/* SPDX-License-Identifier: Apache-2.0 */
/* The extensible camera (ppm_camera_v2): defaults, the same images as the first camera
 * struct, round trips through the renderer and scene files, and the size rules that let it
 * grow: too small or implausible sizes refused, a newer caller's zero tail accepted and its
 * non-zero tail refused, outputs written up to the caller's size only. */
#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef scene_fixture fixture;

static const char small_box[] = PPM_TEST_DATA_DIR "/scenes/small_box.json";

/* What a caller compiled against a later header might pass: the fields of this version,
 * then fields this library does not know. */
typedef struct newer_camera {
    ppm_camera_v2 known;
    double later_field;
    uint64_t later_flags;
} newer_camera;

enum { width = 12, height = 9 };

/* A diffuse unit sphere under a point light, committed. */
static void build_sphere(ppm_scene scene) {
    const double centre[3] = {0, 0, 0}, light[3] = {1, 3, 3}, intensity[3] = {5, 5, 5}, grey[3] = {0.6, 0.6, 0.6};
    assert_ppm_ok(ppm_scene_add_sphere(scene, centre, 1.0, NULL));
    assert_ppm_ok(ppm_scene_add_diffuse_material(scene, grey, NULL));
    assert_ppm_ok(ppm_scene_add_point_light(scene, light, intensity, NULL));
    assert_ppm_ok(ppm_scene_commit(scene));
}

static ppm_camera_v2 sphere_camera(void) {
    ppm_camera_v2 camera;
    ppm_camera_v2_init(&camera);
    camera.origin[0] = 0.3;
    camera.origin[2] = 4;
    camera.target[2] = 0;
    camera.fov = 50;
    camera.width = width;
    camera.height = height;
    camera.aperture_radius = 0.05;
    camera.focus_distance = 3;
    camera.near_clip = 0.1;
    return camera;
}

/* Two passes of a few photons: the radiance layer, malloc'ed. */
static float *render(ppm_renderer r) {
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 2000));
    assert_ppm_ok(ppm_render_pass(r));
    assert_ppm_ok(ppm_render_pass(r));
    float *rgb = malloc(sizeof(float) * width * height * 3);
    assert_non_null(rgb);
    assert_ppm_ok(ppm_renderer_get_layer(r, "radiance", rgb, (size_t)width * height * 3));
    return rgb;
}

static void test_init_sets_size_and_defaults(void **state) {
    (void)state;
    ppm_camera_v2 camera;
    memset(&camera, 0xAB, sizeof camera);
    ppm_camera_v2_init(&camera);
    assert_int_equal(camera.size, sizeof(ppm_camera_v2));
    for (int k = 0; k < 3; ++k) assert_true(camera.origin[k] == 0);
    assert_true(camera.target[0] == 0 && camera.target[1] == 0 && camera.target[2] == 1);
    assert_true(camera.up[0] == 0 && camera.up[1] == 1 && camera.up[2] == 0);
    assert_true(camera.fov == 39.597752709049864);
    assert_int_equal(camera.width, 0);
    assert_int_equal(camera.height, 0);
    assert_true(camera.aperture_radius == 0 && camera.focus_distance == 0 && camera.near_clip == 0.01);
    assert_true(camera.crop_x0 == 0 && camera.crop_y0 == 0 && camera.crop_x1 == 0 && camera.crop_y1 == 0);
    for (size_t k = 0; k < sizeof camera.reserved / sizeof camera.reserved[0]; ++k)
        assert_true(camera.reserved[k] == 0);
}

/* The same camera through either struct gives the same image, bit for bit. */
static void test_v2_renders_like_the_first_struct(void **state) {
    fixture *f = *state;
    build_sphere(f->scene);
    const ppm_camera_v2 v2 = sphere_camera();
    ppm_camera v1;
    memset(&v1, 0, sizeof v1);
    memcpy(v1.origin, v2.origin, sizeof v1.origin);
    memcpy(v1.target, v2.target, sizeof v1.target);
    memcpy(v1.up, v2.up, sizeof v1.up);
    v1.fov = v2.fov;
    v1.width = v2.width;
    v1.height = v2.height;
    v1.aperture_radius = v2.aperture_radius;
    v1.focus_distance = v2.focus_distance;
    v1.near_clip = v2.near_clip;
    ppm_renderer a = NULL, b = NULL;
    assert_ppm_ok(ppm_renderer_create(f->scene, &v1, &a));
    assert_ppm_ok(ppm_renderer_create_v2(f->scene, &v2, &b));
    float *image_a = render(a), *image_b = render(b);
    double sum = 0;
    for (size_t i = 0; i < (size_t)width * height * 3; ++i) sum += image_a[i];
    assert_true(sum > 0); /* the sphere is lit: the comparison is not of two black images */
    assert_memory_equal(image_a, image_b, sizeof(float) * width * height * 3);
    free(image_a);
    free(image_b);
    ppm_renderer_release(a);
    ppm_renderer_release(b);
}

static void test_renderer_returns_its_camera(void **state) {
    fixture *f = *state;
    build_sphere(f->scene);
    const ppm_camera_v2 given = sphere_camera();
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_renderer_create_v2(f->scene, &given, &r));
    ppm_camera_v2 got;
    ppm_camera_v2_init(&got);
    assert_ppm_ok(ppm_renderer_get_camera_v2(r, &got));
    assert_memory_equal(&got, &given, sizeof got);
    ppm_renderer_release(r);
}

static void test_output_is_written_up_to_the_callers_size(void **state) {
    fixture *f = *state;
    build_sphere(f->scene);
    const ppm_camera_v2 given = sphere_camera();
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_renderer_create_v2(f->scene, &given, &r));
    struct {
        newer_camera camera;
        unsigned char guard[16];
    } out;
    memset(&out, 0xAB, sizeof out);
    out.camera.known.size = sizeof out.camera;
    assert_ppm_ok(ppm_renderer_get_camera_v2(r, &out.camera.known));
    assert_int_equal(out.camera.known.size, sizeof out.camera); /* left as the caller set it */
    assert_true(out.camera.known.width == width && out.camera.known.fov == 50);
    assert_true(out.camera.later_field == 0 && out.camera.later_flags == 0); /* "as before" */
    for (size_t i = 0; i < sizeof out.guard; ++i) assert_int_equal(out.guard[i], 0xAB);
    ppm_renderer_release(r);
}

static void test_newer_callers_zero_tail_is_accepted(void **state) {
    fixture *f = *state;
    build_sphere(f->scene);
    newer_camera camera;
    memset(&camera, 0, sizeof camera);
    camera.known = sphere_camera();
    camera.known.size = sizeof camera;
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_renderer_create_v2(f->scene, &camera.known, &r));
    int64_t w = 0;
    assert_ppm_ok(ppm_renderer_get_int(r, "width", &w));
    assert_int_equal(w, width);
    ppm_renderer_release(r);
}

static void test_newer_callers_fields_are_unsupported(void **state) {
    fixture *f = *state;
    build_sphere(f->scene);
    newer_camera camera;
    memset(&camera, 0, sizeof camera);
    camera.known = sphere_camera();
    camera.known.size = sizeof camera;
    camera.later_flags = 1;
    ppm_renderer r = NULL;
    char offset[32];
    snprintf(offset, sizeof offset, "camera byte %zu of %zu", offsetof(newer_camera, later_flags), sizeof camera);
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera.known, &r), PPM_ERROR_UNSUPPORTED, offset);
    assert_null(r);
}

static void test_bad_sizes_are_refused(void **state) {
    fixture *f = *state;
    build_sphere(f->scene);
    const size_t bad[] = {0, sizeof(size_t), sizeof(ppm_camera_v2) - 8, (size_t)1 << 40, (size_t)-1};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        ppm_camera_v2 camera = sphere_camera();
        camera.size = bad[i];
        ppm_renderer r = NULL;
        assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT,
                         "ppm_camera_v2_init");
        assert_null(r);
    }
    ppm_camera_v2 camera = sphere_camera();
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_renderer_create_v2(f->scene, &camera, &r));
    ppm_camera_v2 out;
    ppm_camera_v2_init(&out);
    out.size = 3;
    out.fov = 7;
    assert_ppm_error(ppm_renderer_get_camera_v2(r, &out), PPM_ERROR_INVALID_ARGUMENT, "out_camera->size is 3");
    assert_true(out.fov == 7); /* untouched */
    ppm_renderer_release(r);
}

static void test_reserved_must_be_zero(void **state) {
    fixture *f = *state;
    build_sphere(f->scene);
    ppm_camera_v2 camera = sphere_camera();
    camera.reserved[1] = 1;
    ppm_renderer r = NULL;
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "reserved[1]");
    assert_null(r);
    camera.reserved[1] = 0;
    camera.reserved_pad = 1;
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "reserved_pad");
}

/* The pixel filter reaches the renderer and comes back; bad ones are named. */
static void test_pixel_filter_fields(void **state) {
    fixture *f = *state;
    build_sphere(f->scene);
    ppm_camera_v2 camera = sphere_camera();
    camera.pixel_filter = PPM_PIXEL_FILTER_GAUSSIAN;
    camera.pixel_filter_parameter = 0.7;
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_renderer_create_v2(f->scene, &camera, &r));
    ppm_camera_v2 back;
    ppm_camera_v2_init(&back);
    assert_ppm_ok(ppm_renderer_get_camera_v2(r, &back));
    assert_true(back.pixel_filter == PPM_PIXEL_FILTER_GAUSSIAN && back.pixel_filter_parameter == 0.7);
    assert_ppm_ok(ppm_renderer_render_pass(r));
    ppm_renderer_release(r);
    camera.pixel_filter = 5;
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "pixel_filter 5");
    camera.pixel_filter = PPM_PIXEL_FILTER_TENT;
    camera.pixel_filter_parameter = -1;
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "radius");
    camera.pixel_filter = PPM_PIXEL_FILTER_BOX;
    camera.pixel_filter_parameter = 1;
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT,
                     "pixel_filter_parameter must be 0 for the box");
}

static void test_bad_fields_are_named(void **state) {
    fixture *f = *state;
    build_sphere(f->scene);
    ppm_renderer r = NULL;
    ppm_camera_v2 camera = sphere_camera();
    camera.fov = 180;
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "fov");
    camera = sphere_camera();
    camera.width = 0;
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "image size");
    camera = sphere_camera();
    camera.height = (1u << 28) + 1;
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "2^28");
    camera = sphere_camera();
    camera.origin[1] = NAN;
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "camera origin");
    camera = sphere_camera();
    camera.focus_distance = 0;
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "focus_distance");
    ppm_camera_v2_init(&camera); /* defaults alone lack an image size */
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "image size");
    assert_null(r);
}

static void test_null_arguments(void **state) {
    fixture *f = *state;
    build_sphere(f->scene);
    ppm_camera_v2 camera = sphere_camera();
    ppm_renderer r = NULL;
    assert_ppm_error(ppm_renderer_create_v2(NULL, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "scene");
    assert_ppm_error(ppm_renderer_create_v2(f->scene, NULL, &r), PPM_ERROR_INVALID_ARGUMENT, "camera");
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, NULL), PPM_ERROR_INVALID_ARGUMENT, "out_renderer");
    assert_ppm_error(ppm_renderer_get_camera_v2(NULL, &camera), PPM_ERROR_INVALID_ARGUMENT, "renderer");
    assert_ppm_ok(ppm_renderer_create_v2(f->scene, &camera, &r));
    assert_ppm_error(ppm_renderer_get_camera_v2(r, NULL), PPM_ERROR_INVALID_ARGUMENT, "out_camera");
    ppm_renderer_release(r);
    assert_ppm_error(ppm_scene_file_get_camera_v2(NULL, &camera), PPM_ERROR_INVALID_ARGUMENT, "scene file");
}

static void test_uncommitted_scene(void **state) {
    fixture *f = *state;
    const double centre[3] = {0, 0, 0};
    assert_ppm_ok(ppm_scene_add_sphere(f->scene, centre, 1.0, NULL));
    ppm_camera_v2 camera = sphere_camera();
    ppm_renderer r = NULL;
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_OPERATION, "commit");
    assert_null(r);
}

/* The scene file's camera through both structs: the same values. */
static void test_scene_file_camera_v2(void **state) {
    fixture *f = *state;
    ppm_scene_file file = NULL;
    assert_ppm_ok(ppm_scene_file_load(f->context, small_box, &file));
    ppm_camera v1;
    ppm_camera_v2 v2;
    ppm_camera_v2_init(&v2);
    assert_ppm_ok(ppm_scene_file_get_camera(file, &v1));
    assert_ppm_ok(ppm_scene_file_get_camera_v2(file, &v2));
    assert_int_equal(v2.size, sizeof v2);
    assert_memory_equal(v2.origin, v1.origin, sizeof v1.origin);
    assert_memory_equal(v2.target, v1.target, sizeof v1.target);
    assert_memory_equal(v2.up, v1.up, sizeof v1.up);
    assert_true(v2.fov == v1.fov && v2.width == v1.width && v2.height == v1.height);
    assert_true(v2.aperture_radius == v1.aperture_radius && v2.focus_distance == v1.focus_distance);
    assert_true(v2.near_clip == v1.near_clip);
    assert_int_equal(v2.width, 64);
    v2.size = 0;
    assert_ppm_error(ppm_scene_file_get_camera_v2(file, &v2), PPM_ERROR_INVALID_ARGUMENT, "out_camera->size");
    ppm_scene_file_release(file);
}

/* A scene file's renderer through another camera: its size, the file's settings, the
 * file's camera for NULL, and the errors of ppm_renderer_create_v2. */
static void test_scene_file_renderer_with_another_camera(void **state) {
    fixture *f = *state;
    ppm_scene_file file = NULL;
    assert_ppm_ok(ppm_scene_file_load(f->context, small_box, &file));
    ppm_camera_v2 camera;
    ppm_camera_v2_init(&camera);
    assert_ppm_ok(ppm_scene_file_get_camera_v2(file, &camera));
    ppm_renderer r = NULL, base = NULL;
    int64_t width = 0, height = 0, photons = 0, base_photons = 0;

    assert_ppm_ok(ppm_scene_file_create_renderer(file, &base));
    assert_ppm_ok(ppm_renderer_get_int(base, "photons_per_pass", &base_photons));
    camera.width = 20;
    camera.height = 10;
    camera.crop_x0 = 5, camera.crop_y0 = 2, camera.crop_x1 = 15, camera.crop_y1 = 6;
    assert_ppm_ok(ppm_scene_file_create_renderer_v2(file, &camera, &r));
    assert_ppm_ok(ppm_renderer_get_int(r, "width", &width));
    assert_ppm_ok(ppm_renderer_get_int(r, "height", &height));
    assert_ppm_ok(ppm_renderer_get_int(r, "photons_per_pass", &photons));
    assert_int_equal(width, 10);
    assert_int_equal(height, 4);
    assert_int_equal(photons, base_photons); /* the file's integrator settings */
    ppm_renderer_release(r);

    r = NULL;
    assert_ppm_ok(ppm_scene_file_create_renderer_v2(file, NULL, &r)); /* the file's camera */
    assert_ppm_ok(ppm_renderer_get_int(r, "width", &width));
    assert_int_equal(width, 64);
    ppm_renderer_release(r);
    ppm_renderer_release(base);

    r = NULL;
    camera.crop_x1 = 21;
    assert_ppm_error(ppm_scene_file_create_renderer_v2(file, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "crop window");
    assert_null(r);
    camera.crop_x1 = 15;
    camera.size = 3;
    assert_ppm_error(ppm_scene_file_create_renderer_v2(file, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "camera->size");
    camera.size = sizeof camera;
    assert_ppm_error(ppm_scene_file_create_renderer_v2(file, &camera, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "out_renderer");
    assert_ppm_error(ppm_scene_file_create_renderer_v2(NULL, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "file");
    ppm_scene_file_release(file);
}

/* Passes of a pinhole camera in `mode` (a convex sphere under a point light has direct light
 * only, which sppm's shadow rays find in few passes; vcm also splats light subpaths to the
 * camera, which is noisier): the radiance of a w x h image, malloc'ed. */
static float *render_pinhole(ppm_scene scene, const ppm_camera_v2 *camera, int w, int h, const char *mode, int passes) {
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_renderer_create_v2(scene, camera, &r));
    int64_t rw = 0, rh = 0;
    assert_ppm_ok(ppm_renderer_get_int(r, "width", &rw));
    assert_ppm_ok(ppm_renderer_get_int(r, "height", &rh));
    assert_int_equal(rw, w);
    assert_int_equal(rh, h);
    assert_ppm_ok(ppm_renderer_set_string(r, "mode", mode));
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 100));
    for (int pass = 0; pass < passes; ++pass) assert_ppm_ok(ppm_render_pass(r));
    float *rgb = malloc(sizeof(float) * (size_t)w * (size_t)h * 3);
    assert_non_null(rgb);
    assert_ppm_ok(ppm_renderer_get_layer(r, "radiance", rgb, (size_t)w * (size_t)h * 3));
    ppm_renderer_release(r);
    return rgb;
}

/* A crop window renders the pixels of the whole image that it covers: the same projection,
 * so each cropped pixel converges to the whole image's pixel at the same place (the pixel
 * jitter differs, so they agree within the anti-aliasing noise), and a window moved by one
 * pixel does not. */
static void test_crop_window_renders_part_of_the_image(void **state) {
    fixture *f = *state;
    build_sphere(f->scene);
    ppm_camera_v2 camera = sphere_camera();
    camera.aperture_radius = 0;
    camera.focus_distance = 0;
    const int x0 = 3, y0 = 2, cw = 6, ch = 5;
    const char *const modes[] = {"sppm", "vcm"};
    const int passes[] = {64, 1024};
    for (int m = 0; m < 2; ++m) {
        camera.crop_x0 = camera.crop_y0 = camera.crop_x1 = camera.crop_y1 = 0;
        float *whole = render_pinhole(f->scene, &camera, width, height, modes[m], passes[m]);
        camera.crop_x0 = x0, camera.crop_y0 = y0, camera.crop_x1 = x0 + cw, camera.crop_y1 = y0 + ch;
        float *crop = render_pinhole(f->scene, &camera, cw, ch, modes[m], passes[m]);
        double peak = 0, same = 0, shifted = 0;
        for (int i = 0; i < width * height * 3; ++i) peak = fmax(peak, whole[i]);
        for (int y = 0; y < ch; ++y)
            for (int x = 0; x < cw; ++x)
                for (int c = 0; c < 3; ++c) {
                    const float v = crop[(y * cw + x) * 3 + c];
                    same = fmax(same, fabs(v - whole[((y + y0) * width + x + x0) * 3 + c]));
                    shifted = fmax(shifted, fabs(v - whole[((y + y0) * width + x + x0 + 1) * 3 + c]));
                }
        printf("crop window, %s: largest difference %.3g of the peak, shifted by a pixel %.3g\n", modes[m], same / peak,
               shifted / peak);
        assert_true(peak > 0);
        assert_true(same < 0.05 * peak);
        assert_true(shifted > 0.2 * peak);
        free(whole);
        free(crop);
    }

    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_renderer_create_v2(f->scene, &camera, &r));
    ppm_camera_v2 back;
    ppm_camera_v2_init(&back);
    assert_ppm_ok(ppm_renderer_get_camera_v2(r, &back));
    assert_true(back.crop_x0 == 3 && back.crop_y0 == 2 && back.crop_x1 == 9 && back.crop_y1 == 7);
    assert_true(back.width == width && back.height == height);
    ppm_renderer_release(r);

    camera.crop_x1 = width + 1; /* beyond the image */
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "crop window");
    camera.crop_x1 = x0; /* empty */
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT, "crop window");
}

/* A principal point offset of a / width renders what a crop window a pixels to the right
 * renders; a scene file's offset reaches the renderer, and the first camera struct, which
 * cannot hold it, refuses it. */
static void test_principal_point_offset_renders_a_shifted_window(void **state) {
    fixture *f = *state;
    build_sphere(f->scene);
    ppm_camera_v2 camera = sphere_camera();
    camera.aperture_radius = 0;
    camera.focus_distance = 0;
    const int x0 = 3, y0 = 2, cw = 6, ch = 5;
    camera.crop_x0 = x0, camera.crop_y0 = y0, camera.crop_x1 = x0 + cw, camera.crop_y1 = y0 + ch;
    float *crop = render_pinhole(f->scene, &camera, cw, ch, "sppm", 64);
    camera.crop_x0 = 0, camera.crop_y0 = 0, camera.crop_x1 = cw, camera.crop_y1 = ch;
    camera.principal_point_offset_x = (double)x0 / width;
    camera.principal_point_offset_y = (double)y0 / height;
    float *offset = render_pinhole(f->scene, &camera, cw, ch, "sppm", 64);
    double peak = 0, same = 0;
    for (int i = 0; i < cw * ch * 3; ++i) {
        peak = fmax(peak, crop[i]);
        same = fmax(same, fabs(crop[i] - offset[i]));
    }
    printf("principal point offset against a crop window: largest difference %.3g of the peak\n", same / peak);
    assert_true(peak > 0);
    assert_true(same < 0.05 * peak);
    free(crop);
    free(offset);

    const char xml[] = "<scene version=\"3.0.0\"><sensor type=\"perspective\">"
                       "<float name=\"principal_point_offset_x\" value=\"0.25\"/>"
                       "<float name=\"principal_point_offset_y\" value=\"-0.125\"/></sensor>"
                       "<shape type=\"sphere\"/><emitter type=\"point\"/></scene>";
    ppm_scene_file file = NULL;
    assert_ppm_ok(ppm_scene_file_load_memory(f->context, xml, sizeof xml - 1, "offset.xml", "", NULL, &file));
    ppm_camera_v2 from_file;
    ppm_camera_v2_init(&from_file);
    assert_ppm_ok(ppm_scene_file_get_camera_v2(file, &from_file));
    assert_true(from_file.principal_point_offset_x == 0.25 && from_file.principal_point_offset_y == -0.125);
    ppm_camera v1;
    assert_ppm_error(ppm_scene_file_get_camera(file, &v1), PPM_ERROR_UNSUPPORTED, "principal point offset");
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_scene_file_create_renderer(file, &r));
    ppm_camera_v2 back;
    ppm_camera_v2_init(&back);
    assert_ppm_ok(ppm_renderer_get_camera_v2(r, &back));
    assert_true(back.principal_point_offset_x == 0.25 && back.principal_point_offset_y == -0.125);
    ppm_renderer_release(r);
    ppm_scene_file_release(file);

    camera.principal_point_offset_x = NAN;
    assert_ppm_error(ppm_renderer_create_v2(f->scene, &camera, &r), PPM_ERROR_INVALID_ARGUMENT,
                     "principal point offset");
}

#define TEST(name) cmocka_unit_test_setup_teardown(name, scene_fixture_setup, scene_fixture_teardown)

int main(void) {
    const struct CMUnitTest tests[] = {
        TEST(test_init_sets_size_and_defaults),
        TEST(test_v2_renders_like_the_first_struct),
        TEST(test_renderer_returns_its_camera),
        TEST(test_output_is_written_up_to_the_callers_size),
        TEST(test_newer_callers_zero_tail_is_accepted),
        TEST(test_newer_callers_fields_are_unsupported),
        TEST(test_bad_sizes_are_refused),
        TEST(test_reserved_must_be_zero),
        TEST(test_pixel_filter_fields),
        TEST(test_principal_point_offset_renders_a_shifted_window),
        TEST(test_bad_fields_are_named),
        TEST(test_null_arguments),
        TEST(test_uncommitted_scene),
        TEST(test_scene_file_camera_v2),
        TEST(test_scene_file_renderer_with_another_camera),
        TEST(test_crop_window_renders_part_of_the_image),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
