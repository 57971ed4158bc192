/* SPDX-License-Identifier: Apache-2.0 */
/* Scene files (docs/scene-format.md) through the C API: what a valid file builds, and a clear
 * located error for each kind of bad input. */
#include <ppm/ppm.h>

#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *const small_box = PPM_TEST_DATA_DIR "/scenes/small_box.json";

typedef struct fixture {
    ppm_context context;
    char folder[256];
    char path[320];
} fixture;

static int setup(void **state) {
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    assert_int_equal(ppm_context_create(&f->context), PPM_OK);
    assert_int_equal(test_make_folder(f->folder, sizeof f->folder, "ppm-scene-test-"), 0);
    snprintf(f->path, sizeof f->path, "%s/scene.json", f->folder);
    *state = f;
    return 0;
}

static int teardown(void **state) {
    fixture *f = *state;
    test_remove_folder(f->folder);
    ppm_context_release(f->context);
    free(f);
    return 0;
}

static void write_text(const char *path, const char *text) {
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    fputs(text, file);
    fclose(file);
}

/* Loads `text` as <folder>/scene.json and expects `status` with every fragment (NULL-ended)
 * in the message. */
static void expect_error(fixture *f, const char *text, ppm_status status, const char *const *fragments) {
    write_text(f->path, text);
    ppm_scene_file file = NULL;
    const ppm_status got = ppm_scene_file_load(f->context, f->path, &file);
    const char *message = ppm_last_error_message();
    if (got != status) fail_msg("status %d, expected %d, for\n%s\nmessage: %s", got, status, text, message);
    assert_null(file);
    for (; *fragments; ++fragments)
        if (!strstr(message, *fragments)) fail_msg("message '%s' lacks '%s'", message, *fragments);
}

#define EXPECT_ERROR(f, text, status, ...)                                                                             \
    do {                                                                                                               \
        const char *const fragments_[] = {__VA_ARGS__, NULL};                                                          \
        expect_error((f), (text), (status), fragments_);                                                               \
    } while (0)

static void test_small_box_builds_what_it_says(void **state) {
    fixture *f = *state;
    ppm_scene_file file = NULL;
    assert_int_equal(ppm_scene_file_load(f->context, small_box, &file), PPM_OK);

    ppm_camera camera;
    assert_int_equal(ppm_scene_file_get_camera(file, &camera), PPM_OK);
    assert_int_equal(camera.width, 64);
    assert_int_equal(camera.height, 48);
    assert_close(camera.fov, 45, 0);
    assert_close(camera.near_clip, 0.01, 0); /* Mitsuba's default */
    assert_close(camera.aperture_radius, 0, 0);
    /* look_at: origin, a point along the view direction, an up vector. */
    assert_close(camera.origin[1], 1, 1e-12);
    assert_close(camera.origin[2], 3.5, 1e-12);
    assert_close(camera.target[2], 2.5, 1e-12); /* one unit towards the target */
    assert_close(camera.up[1], 1, 1e-12);

    int64_t passes = 0;
    double time = -1;
    assert_int_equal(ppm_scene_file_get_int(file, "passes", &passes), PPM_OK);
    assert_int_equal(passes, 4);
    assert_int_equal(ppm_scene_file_get_double(file, "time", &time), PPM_OK);
    assert_close(time, 0, 0);
    assert_int_equal(ppm_scene_file_get_int(file, "nonsense", &passes), PPM_ERROR_INVALID_ARGUMENT);

    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_file_get_scene(file, &scene), PPM_OK);
    /* Floor [-1,1]^2 at y = 0 rotated from z = 0, back wall at z = -1, light at y = 1.99. */
    double lower[3], upper[3];
    assert_int_equal(ppm_scene_get_bounds(scene, lower, upper), PPM_OK);
    assert_close(lower[0], -1, 1e-9);
    assert_close(upper[0], 1, 1e-9);
    assert_close(lower[1], 0, 1e-9);
    assert_close(upper[1], 2, 1e-9);
    assert_close(lower[2], -1, 1e-9);
    assert_close(upper[2], 1, 1e-9);

    /* A ray down the middle hits the floor's rectangle at y = 0 from above. */
    ppm_ray ray = {{0.0, 1.5, 0.6}, 0, {0, -1, 0}, INFINITY};
    ppm_hit hit;
    assert_int_equal(ppm_scene_intersect(scene, &ray, 1, &hit), PPM_OK);
    assert_close(hit.t, 1.5, 1e-9);
    /* The emitter, scaled to 0.25 and flipped to face down, covers x in [-0.25, 0.25]. */
    ppm_ray up_ray = {{0.2, 1.0, 0.0}, 0, {0, 1, 0}, INFINITY};
    assert_int_equal(ppm_scene_intersect(scene, &up_ray, 1, &hit), PPM_OK);
    assert_close(hit.t, 0.99, 1e-9);

    /* Other shapes are not patch sets; a scene being changed has no world patches yet. */
    size_t geometries = 0;
    assert_int_equal(ppm_scene_get_geometry_count(scene, &geometries), PPM_OK);
    assert_int_equal(geometries, 6);
    double points[48];
    assert_int_equal(ppm_scene_get_bezier_patches(scene, 4, points, 48), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(ppm_last_error_message(), "not a patch set"));
    ppm_scene fresh = NULL;
    assert_int_equal(ppm_scene_create(f->context, &fresh), PPM_OK);
    uint32_t patch_id = 0;
    assert_int_equal(ppm_scene_load_bpt(fresh, PPM_TEAPOT, &patch_id), PPM_OK);
    assert_int_equal(ppm_scene_get_bezier_patches(fresh, patch_id, points, 48), PPM_ERROR_INVALID_OPERATION);
    ppm_scene_release(fresh);

    ppm_renderer renderer = NULL;
    assert_int_equal(ppm_scene_file_create_renderer(file, &renderer), PPM_OK);
    int64_t value = 0;
    assert_int_equal(ppm_renderer_get_int(renderer, "photons_per_pass", &value), PPM_OK);
    assert_int_equal(value, 20000);
    assert_int_equal(ppm_renderer_get_int(renderer, "seed", &value), PPM_OK);
    assert_int_equal(value, 7);
    assert_int_equal(ppm_render_pass(renderer), PPM_OK);

    /* The scene and renderer outlive the file handle. */
    ppm_scene_file_release(file);
    assert_int_equal(ppm_render_pass(renderer), PPM_OK);
    ppm_renderer_release(renderer);
    ppm_scene_release(scene);
}

static void test_defaults_and_inline_patches(void **state) {
    fixture *f = *state;
    /* A flat patch given inline, no sensor, no bsdfs: Mitsuba's camera defaults. */
    write_text(f->path, "{\"shapes\": [{\"type\": \"bezier\", \"patches\": [[\n"
                        "  [0,0,5],[1,0,5],[2,0,5],[3,0,5], [0,1,5],[1,1,5],[2,1,5],[3,1,5],\n"
                        "  [0,2,5],[1,2,5],[2,2,5],[3,2,5], [0,3,5],[1,3,5],[2,3,5],[3,3,5]]],\n"
                        "  \"to_world\": {\"translate\": [-1.5, -1.5, 0]}}]}\n");
    ppm_scene_file file = NULL;
    assert_int_equal(ppm_scene_file_load(f->context, f->path, &file), PPM_OK);
    ppm_camera camera;
    assert_int_equal(ppm_scene_file_get_camera(file, &camera), PPM_OK);
    assert_int_equal(camera.width, 768);
    assert_int_equal(camera.height, 576);
    assert_close(camera.fov, 39.597752709049864, 1e-12);
    assert_close(camera.target[2], 1, 0);
    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_file_get_scene(file, &scene), PPM_OK);
    ppm_ray ray = {{0, 0, 0}, 0, {0, 0, 1}, INFINITY};
    ppm_hit hit;
    assert_int_equal(ppm_scene_intersect(scene, &ray, 1, &hit), PPM_OK);
    assert_close(hit.t, 5, 1e-9);

    /* The patch comes back in world space: the file's translation applied. */
    size_t geometries = 0;
    assert_int_equal(ppm_scene_get_geometry_count(scene, &geometries), PPM_OK);
    assert_int_equal(geometries, 1);
    double points[48];
    assert_int_equal(ppm_scene_get_bezier_patches(scene, 0, points, 48), PPM_OK);
    assert_close(points[0], -1.5, 0);
    assert_close(points[1], -1.5, 0);
    assert_close(points[2], 5, 0);
    assert_close(points[45], 1.5, 0);
    assert_close(points[46], 1.5, 0);
    assert_int_equal(ppm_scene_get_bezier_patches(scene, 0, points, 47), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(ppm_last_error_message(), "need 48"));
    assert_int_equal(ppm_scene_get_bezier_patches(scene, 0, NULL, 48), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_get_bezier_patches(scene, 1, points, 48), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_get_bezier_patches(NULL, 0, points, 48), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_get_geometry_count(scene, NULL), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_get_geometry_count(NULL, &geometries), PPM_ERROR_INVALID_ARGUMENT);

    /* No light at all: passes run and the image is black. */
    ppm_renderer renderer = NULL;
    assert_int_equal(ppm_scene_file_create_renderer(file, &renderer), PPM_OK);
    assert_int_equal(ppm_renderer_set_int(renderer, "photons_per_pass", 100), PPM_OK);
    assert_int_equal(ppm_render_pass(renderer), PPM_OK);
    const size_t count = 768 * 576 * 3;
    float *rgb = malloc(count * sizeof *rgb);
    assert_non_null(rgb);
    assert_int_equal(ppm_renderer_get_layer(renderer, "radiance", rgb, count), PPM_OK);
    for (size_t i = 0; i < count; ++i)
        if (rgb[i] != 0) fail_msg("pixel value %g at %zu without any light", rgb[i], i);
    free(rgb);
    ppm_renderer_release(renderer);
    ppm_scene_release(scene);
    ppm_scene_file_release(file);
}

/* Area lights on disks, cylinders and meshes (obj, cube, rectangle), and flip_normals, from
 * JSON and from Mitsuba XML; hits on the new shapes in world space. */
static void check_light_scene(fixture *f, const char *path, int64_t lights) {
    ppm_scene_file file = NULL;
    if (ppm_scene_file_load(f->context, path, &file) != PPM_OK) fail_msg("%s", ppm_last_error_message());
    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_file_get_scene(file, &scene), PPM_OK);
    /* The disk: radius 0.5 at y = 2, its normal +y flipped to -y. */
    ppm_ray down = {{0.2, 5, 0}, 0, {0, -1, 0}, INFINITY};
    ppm_hit hit;
    assert_int_equal(ppm_scene_intersect(scene, &down, 1, &hit), PPM_OK);
    assert_close(hit.t, 3, 1e-9);
    assert_close(hit.ng[1], -1, 1e-12);
    assert_close(hit.u, 0.4, 1e-9); /* r = 0.2 / 0.5 */
    /* The cylinder: radius 0.25 around x = 3, z from 0 to 2 (p1 (0, 0, 2) scaled by the radius
     * and moved), hit from +x at x = 3.25. */
    ppm_ray side = {{10, 0, 1}, 0, {-1, 0, 0}, INFINITY};
    assert_int_equal(ppm_scene_intersect(scene, &side, 1, &hit), PPM_OK);
    assert_close(hit.t, 6.75, 1e-9);
    assert_close(hit.ng[0], 1, 1e-12);
    assert_close(hit.v, 0.5, 1e-9);
    ppm_renderer renderer = NULL;
    if (ppm_scene_file_create_renderer(file, &renderer) != PPM_OK) fail_msg("%s", ppm_last_error_message());
    int64_t count = 0;
    assert_int_equal(ppm_renderer_get_int(renderer, "lights", &count), PPM_OK);
    assert_int_equal(count, lights);
    ppm_renderer_release(renderer);
    ppm_scene_release(scene);
    ppm_scene_file_release(file);
}

static void test_area_lights_on_disks_cylinders_and_meshes(void **state) {
    fixture *f = *state;
    char obj[400], xml[400];
    snprintf(obj, sizeof obj, "%s/tri.obj", f->folder);
    write_text(obj, "v -10 -1 -10\nv 10 -1 -10\nv 0 -1 10\nf 1 3 2\n");
    write_text(
        f->path,
        "{\"shapes\": [\n"
        " {\"type\": \"disk\", \"flip_normals\": true, \"emitter\": {\"type\": \"area\", \"radiance\": 2},\n"
        "  \"to_world\": [{\"scale\": 0.5}, {\"rotate\": {\"axis\": [1, 0, 0], \"angle\": -90}},\n"
        "               {\"translate\": [0, 2, 0]}]},\n"
        " {\"type\": \"cylinder\", \"p1\": [0, 0, 2], \"emitter\": {\"type\": \"area\"},\n"
        "  \"to_world\": [{\"scale\": 0.25}, {\"translate\": [3, 0, 0.75]}]},\n"
        " {\"type\": \"obj\", \"filename\": \"tri.obj\", \"emitter\": {\"type\": \"area\", \"radiance\": 0.5}},\n"
        " {\"type\": \"cube\", \"emitter\": {\"type\": \"area\"}, \"flip_normals\": true,\n"
        "  \"to_world\": {\"translate\": [0, 0, 50]}},\n"
        " {\"type\": \"rectangle\", \"to_world\": {\"translate\": [0, 0, -50]}}]}\n");
    check_light_scene(f, f->path, 4);

    snprintf(xml, sizeof xml, "%s/scene.xml", f->folder);
    write_text(xml,
               "<scene version=\"3.0.0\">\n"
               " <shape type=\"disk\"><boolean name=\"flip_normals\" value=\"true\"/>\n"
               "  <transform name=\"to_world\"><scale value=\"0.5\"/><rotate x=\"1\" angle=\"-90\"/>"
               "<translate y=\"2\"/></transform>\n"
               "  <emitter type=\"area\"><rgb name=\"radiance\" value=\"2\"/></emitter></shape>\n"
               " <shape type=\"cylinder\"><point name=\"p1\" x=\"0\" y=\"0\" z=\"2\"/>\n"
               "  <transform name=\"to_world\"><scale value=\"0.25\"/><translate x=\"3\" z=\"0.75\"/></transform>\n"
               "  <emitter type=\"area\"/></shape>\n"
               " <shape type=\"obj\"><string name=\"filename\" value=\"tri.obj\"/>\n"
               "  <emitter type=\"area\"><rgb name=\"radiance\" value=\"0.5\"/></emitter></shape>\n"
               "</scene>\n");
    check_light_scene(f, xml, 3);

    /* A mirroring to_world keeps Mitsuba's disk normal, the inverse transpose's +z. */
    write_text(f->path, "{\"shapes\": [{\"type\": \"disk\", \"to_world\": {\"scale\": [-1, 1, 1]}}]}");
    ppm_scene_file file = NULL;
    assert_int_equal(ppm_scene_file_load(f->context, f->path, &file), PPM_OK);
    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_file_get_scene(file, &scene), PPM_OK);
    ppm_ray down = {{0.2, 0.1, 3}, 0, {0, 0, -1}, INFINITY};
    ppm_hit hit;
    assert_int_equal(ppm_scene_intersect(scene, &down, 1, &hit), PPM_OK);
    assert_close(hit.ng[2], 1, 1e-12);
    ppm_scene_release(scene);
    ppm_scene_file_release(file);

    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"cylinder\", \"p0\": [1, 1, 1], \"p1\": [1, 1, 1]}]}", PPM_ERROR_PARSE,
                 "p0 and p1");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"cylinder\", \"radius\": 0}]}", PPM_ERROR_PARSE, "radius");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"cylinder\", \"to_world\": {\"scale\": [1, 2, 1]}}]}", PPM_ERROR_PARSE,
                 "circular");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"sphere\", \"flip_normals\": true}]}", PPM_ERROR_PARSE, "flip_normals");
    EXPECT_ERROR(f,
                 "{\"shapes\": [{\"type\": \"bezier\", \"emitter\": {\"type\": \"area\"}, \"patches\": [[\n"
                 "  [0,0,5],[1,0,5],[2,0,5],[3,0,5], [0,1,5],[1,1,5],[2,1,5],[3,1,5],\n"
                 "  [0,2,5],[1,2,5],[2,2,5],[3,2,5], [0,3,5],[1,3,5],[2,3,5],[3,3,5]]]}]}",
                 PPM_ERROR_INVALID_ARGUMENT, "Bezier patches cannot be area lights");
}

static void test_errors_are_located(void **state) {
    fixture *f = *state;
    /* JSON syntax: line and column of the problem. */
    EXPECT_ERROR(f, "{\n  \"shapes\": [\n    {\"type\": \"sphere\",}\n  ]\n}\n", PPM_ERROR_PARSE, "scene.json:3:");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"sphere\", \"radius\": NaN}]}", PPM_ERROR_PARSE, "scene.json:1:");
    EXPECT_ERROR(f, "{\"shapes\": [], \"shapes\": []}", PPM_ERROR_PARSE, "scene.json:1:", "uplicate");
    EXPECT_ERROR(f, "[1, 2]", PPM_ERROR_PARSE, "must be a JSON object");
    EXPECT_ERROR(f, "", PPM_ERROR_PARSE, "scene.json");
    /* Unknown keys anywhere. */
    EXPECT_ERROR(f, "{\"shapez\": []}", PPM_ERROR_PARSE, "scene.json:1:", "shapez: unknown key");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"sphere\", \"radiuss\": 1}]}", PPM_ERROR_PARSE,
                 "shapes[0].radiuss: sphere shape has no parameter 'radiuss' (did you mean 'radius'?)");
    /* Wrong types and ranges, with the key path and the expectation. */
    EXPECT_ERROR(f, "{\"sensor\": {\"fov\": \"wide\"}, \"shapes\": [{\"type\": \"sphere\"}]}", PPM_ERROR_PARSE,
                 "scene.json:1:20: sensor.fov: expected a number in (0, 180)");
    EXPECT_ERROR(f,
                 "{\"bsdfs\": {\"glass\": {\"type\": \"dielectric\",\n"
                 "                     \"int_ior\": -1}},\n \"shapes\": [{\"type\": \"sphere\"}]}",
                 PPM_ERROR_PARSE,
                 "scene.json:2:33: bsdfs.glass.int_ior: dielectric material: parameter 'int_ior' must be > 0, not -1");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"sphere\", \"radius\": -2}]}", PPM_ERROR_PARSE,
                 "shapes[0].radius: sphere shape: parameter 'radius' must be > 0, not -2");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"sphere\", \"radius\": 1e999}]}", PPM_ERROR_PARSE, "scene.json:1:");
    EXPECT_ERROR(f, "{\"integrator\": {\"passes\": 1.5}, \"shapes\": [{\"type\": \"sphere\"}]}", PPM_ERROR_PARSE,
                 "integrator.passes: expected a whole number");
    EXPECT_ERROR(f, "{\"integrator\": {\"alpha\": 2}, \"shapes\": [{\"type\": \"sphere\"}]}", PPM_ERROR_PARSE,
                 "integrator.alpha: alpha must be in (0, 1]");
    EXPECT_ERROR(f, "{\"integrator\": {\"type\": \"bdpt\"}, \"shapes\": [{\"type\": \"sphere\"}]}", PPM_ERROR_PARSE,
                 "integrator.type: 'bdpt' is not known");
    EXPECT_ERROR(
        f, "{\"sensor\": {\"film\": {\"width\": 100000, \"height\": 100000}}, \"shapes\": [{\"type\": \"sphere\"}]}",
        PPM_ERROR_PARSE, "sensor.film: width x height = 10000000000 pixels exceeds the limit");
    EXPECT_ERROR(f, "{\"sensor\": {\"film\": {\"width\": 0}}, \"shapes\": [{\"type\": \"sphere\"}]}", PPM_ERROR_PARSE,
                 "sensor.film.width: expected a whole number in [1, ");
    EXPECT_ERROR(f, "{\"sensor\": {\"type\": \"thinlens\"}, \"shapes\": [{\"type\": \"sphere\"}]}", PPM_ERROR_PARSE,
                 "sensor: missing key 'aperture_radius'");
    EXPECT_ERROR(f,
                 "{\"bsdfs\": {\"hot\": {\"type\": \"diffuse\", \"reflectance\": [1, 2, 0]}}, \"shapes\": [{\"type\": "
                 "\"sphere\"}]}",
                 PPM_ERROR_PARSE,
                 "bsdfs.hot.reflectance: diffuse material: parameter 'reflectance' must be at most 1 in every channel");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"sphere\", \"bsdf\": \"gold\"}]}", PPM_ERROR_PARSE,
                 "shapes[0].bsdf: no bsdf named 'gold'");
    EXPECT_ERROR(f, "{\"shapes\": []}", PPM_ERROR_PARSE, "shapes: a scene needs at least one shape");
    EXPECT_ERROR(f, "{}", PPM_ERROR_PARSE, "missing key 'shapes'");
    EXPECT_ERROR(f, "{\"version\": 2, \"shapes\": [{\"type\": \"sphere\"}]}", PPM_ERROR_PARSE,
                 "version: expected a whole number in [1, 1]");
    /* Transforms. */
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"rectangle\", \"to_world\": {\"scale\": 0}}]}", PPM_ERROR_PARSE,
                 "shapes[0].to_world.scale: a scale must not be zero");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"rectangle\", \"to_world\": {\"scale\": 2, \"translate\": [1,0,0]}}]}",
                 PPM_ERROR_PARSE, "shapes[0].to_world: a transform operation has exactly one key");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"rectangle\", \"to_world\": [{\"shear\": 1}]}]}", PPM_ERROR_PARSE,
                 "shapes[0].to_world[0].shear: unknown key");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"sphere\", \"to_world\": {\"scale\": [1, 2, 1]}}]}", PPM_ERROR_PARSE,
                 "shapes[0].to_world: ");
    /* Degenerate geometry reported by the API, located in the file. */
    EXPECT_ERROR(f,
                 "{\"shapes\": [{\"type\": \"quad\", \"origin\": [0,0,0], \"edge_u\": [1,0,0], \"edge_v\": [2,0,0]}]}",
                 PPM_ERROR_INVALID_ARGUMENT, "scene.json:1:13: shapes[0]: ");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"bezier\", \"patches\": [[[0,0,0]]]}]}", PPM_ERROR_PARSE,
                 "shapes[0].patches: bezier shape: parameter 'patches' must hold 48 numbers per patch");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"obj\", \"emitter\": {\"type\": \"area\"}, \"filename\": \"x.obj\"}]}",
                 PPM_ERROR_IO, "shapes[0].filename: file not found: ");
}

/* Loads `size` bytes as <folder>/scene.json (NUL bytes included) and expects a PARSE error
 * whose message holds `fragment`. */
static void expect_bytes_error(fixture *f, const char *bytes, size_t size, const char *fragment) {
    FILE *file = fopen(f->path, "wb");
    assert_non_null(file);
    assert_int_equal(fwrite(bytes, 1, size, file), size);
    fclose(file);
    ppm_scene_file scene_file = NULL;
    const ppm_status got = ppm_scene_file_load(f->context, f->path, &scene_file);
    if (got != PPM_ERROR_PARSE || !strstr(ppm_last_error_message(), fragment))
        fail_msg("status %d, message '%s', expected PARSE with '%s'", got, ppm_last_error_message(), fragment);
    assert_null(scene_file);
}

static void test_unreadable_bytes_and_deep_nesting(void **state) {
    fixture *f = *state;
    /* 201 nested arrays: a located PARSE error, not jsoncpp's unlocated exception. */
    char deep[256];
    memset(deep, '[', 201);
    deep[201] = '\0';
    EXPECT_ERROR(f, deep, PPM_ERROR_PARSE, "scene.json:1:65: arrays and objects nested more than 64 levels deep");
    /* Deep nesting inside strings and comments is text, not nesting. */
    char text[512];
    snprintf(text, sizeof text, "// %s\n{\"shapes\": [{\"type\": \"sphere\"}]}", deep);
    ppm_scene_file file = NULL;
    write_text(f->path, text);
    assert_int_equal(ppm_scene_file_load(f->context, f->path, &file), PPM_OK);
    ppm_scene_file_release(file);
    /* A NUL byte anywhere is refused, also after a complete value. */
    static const char after_nul[] = "{\"shapes\": [{\"type\": \"sphere\"}]}\0{garbage";
    expect_bytes_error(f, after_nul, sizeof after_nul - 1, "scene.json:1:33: NUL byte in the file");
    static const char nul_in_string[] = "{\"shapes\": [{\"type\": \"sph\0ere\"}]}";
    expect_bytes_error(f, nul_in_string, sizeof nul_in_string - 1, "scene.json:1:26: NUL byte in the file");
    /* An escaped NUL inside a file name would name another file when passed on as a C string. */
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"obj\", \"filename\": \"a.obj\\u0000.png\"}]}", PPM_ERROR_PARSE,
                 "shapes[0].filename: a string must not contain a NUL character");
}

/* Numbers that would overflow while rendering are refused where the file gives them. */
static void test_overflowing_magnitudes_are_refused_where_they_stand(void **state) {
    fixture *f = *state;
    EXPECT_ERROR(f,
                 "{\"emitters\": [{\"type\": \"point\", \"intensity\": 1e308}], \"shapes\": [{\"type\": \"sphere\"}]}",
                 PPM_ERROR_PARSE,
                 "scene.json:1:46: emitters[0].intensity: point light: parameter 'intensity' exceeds the limit 1e+20");
    EXPECT_ERROR(f,
                 "{\"shapes\": [{\"type\": \"rectangle\", \"emitter\": {\"type\": \"area\", \"radiance\": [1e300, 1, "
                 "1]}}]}",
                 PPM_ERROR_INVALID_ARGUMENT, "shapes[0].emitter: radiance 1e+300 exceeds the limit 1e+20");
    EXPECT_ERROR(
        f, "{\"integrator\": {\"initial_radius\": 1e300}, \"shapes\": [{\"type\": \"sphere\"}]}", PPM_ERROR_PARSE,
        "integrator.initial_radius: initial_radius must lie in [0, 1000000000000] (0 = automatic), not 1e+300");
    EXPECT_ERROR(f,
                 "{\"sensor\": {\"to_world\": [{\"translate\": [1e308, 0, 0]}, {\"translate\": [1e308, 0, 0]}]}, "
                 "\"shapes\": [{\"type\": \"sphere\"}]}",
                 PPM_ERROR_PARSE, "sensor.to_world: the transform moves the origin to inf");
    EXPECT_ERROR(f, "{\"sensor\": {\"to_world\": {\"translate\": [0, 2e12, 0]}}, \"shapes\": [{\"type\": \"sphere\"}]}",
                 PPM_ERROR_PARSE,
                 "sensor.to_world: the transform moves the origin to 2000000000000, beyond +-1000000000000");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"sphere\", \"radius\": 1e308}]}", PPM_ERROR_INVALID_ARGUMENT,
                 "shapes[0]: sphere radius must lie in (0, 1000000000000], not 1e+308");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"sphere\", \"center\": [0, 0, 1e15]}]}", PPM_ERROR_INVALID_ARGUMENT,
                 "shapes[0]: center has a coordinate beyond +-1000000000000");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"sphere\", \"radius\": 1e12, \"center\": [1e12, 0, 0]}]}",
                 PPM_ERROR_INVALID_ARGUMENT,
                 "shapes[0]: the bounding box of the sphere reaches the coordinate 2000000000000");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"rectangle\", \"to_world\": {\"scale\": 1e13}}]}",
                 PPM_ERROR_INVALID_ARGUMENT, "scene.json:1:13: shapes[0]: origin has a coordinate beyond");
    EXPECT_ERROR(f,
                 "{\"shapes\": [{\"type\": \"bezier\", \"to_world\": {\"scale\": 1e12}, \"patches\": [[[0,0,0],[1,0,0],"
                 "[2,0,0],[3,0,0],[0,1,0],[1,1,0],[2,1,0],[3,1,0],[0,2,0],[1,2,0],[2,2,0],[3,2,0],[0,3,0],[1,3,0],"
                 "[2,3,0],[3,3,0]]]}]}",
                 PPM_ERROR_PARSE,
                 "shapes[0].to_world: bezier shape: parameter 'to_world' cannot place the shape: geometry 0 (Bezier "
                 "patches): the bounding box of the Bezier patches reaches the coordinate 3000000000000");
    char bpt[320];
    snprintf(bpt, sizeof bpt, "%s/far.bpt", f->folder);
    write_text(bpt, "1\n3 3\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n0 1 0\n1 1 0\n2 1 0\n3 1 0\n0 2 0\n1 2 0\n2 2 0\n3 2 0\n"
                    "0 3 0\n1 3 1e307\n2 3 0\n3 3 0\n");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"bezier\", \"filename\": \"far.bpt\"}]}", PPM_ERROR_PARSE,
                 "far.bpt:16: ", "'1e307' lies beyond +-1000000000000");
    char obj[320];
    snprintf(obj, sizeof obj, "%s/far.obj", f->folder);
    write_text(obj, "v 0 0 0\nv 1 0 0\nv 0 -1e13 0\nf 1 2 3\n");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"obj\", \"filename\": \"far.obj\"}]}", PPM_ERROR_PARSE,
                 "far.obj:3: coordinate '-1e13' lies beyond +-1000000000000");
}

static void test_missing_and_malformed_files(void **state) {
    fixture *f = *state;
    ppm_scene_file file = NULL;
    assert_int_equal(ppm_scene_file_load(f->context, "/nonexistent/scene.json", &file), PPM_ERROR_IO);
    assert_non_null(strstr(ppm_last_error_message(), "/nonexistent/scene.json"));
    assert_int_equal(ppm_scene_file_load(f->context, f->folder, &file), PPM_ERROR_IO); /* a directory */

    /* Files named inside are relative to the scene's folder; their own errors keep both places. */
    char bpt[320];
    snprintf(bpt, sizeof bpt, "%s/bad.bpt", f->folder);
    write_text(bpt, "1\n3 3\n0 0 0\n");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"bezier\", \"filename\": \"bad.bpt\"}]}", PPM_ERROR_PARSE,
                 "shapes[0].filename: ", "bad.bpt");
    EXPECT_ERROR(f, "{\"shapes\": [{\"type\": \"bezier\", \"filename\": \"missing.bpt\"}]}", PPM_ERROR_IO,
                 "file not found", "missing.bpt");
    EXPECT_ERROR(f,
                 "{\"bsdfs\": {\"tex\": {\"type\": \"diffuse\", \"reflectance\": {\"type\": \"bitmap\", \"filename\": "
                 "\"bad.bpt\"}}}, \"shapes\": [{\"type\": \"sphere\", \"bsdf\": \"tex\"}]}",
                 PPM_ERROR_IO, "bsdfs.tex.reflectance: ");

    assert_int_equal(ppm_scene_file_load(NULL, small_box, &file), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_file_load(f->context, NULL, &file), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_file_load(f->context, small_box, NULL), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_file_get_scene(NULL, NULL), PPM_ERROR_INVALID_ARGUMENT);
    ppm_scene_file_release(NULL);
}

/* Every example scene under examples/scenes loads (the textures are generated by the build). */
static void test_examples_load(void **state) {
    fixture *f = *state;
    static const char *const examples[] = {"teapot-cornell.json", "smallppm.json",   "caustics.json",
                                           "showcase.json",       "cornell-box.xml", "material-preview.xml"};
    for (size_t i = 0; i < sizeof examples / sizeof *examples; ++i) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", PPM_EXAMPLE_SCENES_DIR, examples[i]);
        if (access(path, R_OK) != 0) fail_msg("example scene %s is missing", path);
        ppm_scene_file file = NULL;
        if (ppm_scene_file_load(f->context, path, &file) != PPM_OK) fail_msg("%s", ppm_last_error_message());
        ppm_renderer renderer = NULL;
        assert_int_equal(ppm_scene_file_create_renderer(file, &renderer), PPM_OK);
        ppm_renderer_release(renderer);
        ppm_scene_file_release(file);
    }
}

/* Renders `path` (its own 16 x 16 film) for 4 passes and returns the mean radiance. */
static double mean_of_file(fixture *f, const char *path) {
    ppm_scene_file file = NULL;
    if (ppm_scene_file_load(f->context, path, &file) != PPM_OK) fail_msg("%s", ppm_last_error_message());
    ppm_renderer renderer = NULL;
    assert_int_equal(ppm_scene_file_create_renderer(file, &renderer), PPM_OK);
    assert_int_equal(ppm_renderer_set_int(renderer, "photons_per_pass", 2000), PPM_OK);
    for (int pass = 0; pass < 4; ++pass) assert_int_equal(ppm_render_pass(renderer), PPM_OK);
    float rgb[16 * 16 * 3];
    assert_int_equal(ppm_renderer_get_layer(renderer, "radiance", rgb, 16 * 16 * 3), PPM_OK);
    double sum = 0;
    for (int i = 0; i < 16 * 16 * 3; ++i) sum += rgb[i];
    ppm_renderer_release(renderer);
    ppm_scene_file_release(file);
    return sum / (16 * 16 * 3);
}

/* blendbsdf (a named and a nested BSDF), mask and checkerboard, in JSON and in Mitsuba XML
 * (references in the roles bsdf_0 and bsdf, nested elements named bsdf_1): the same scene,
 * the same image. */
static void test_blend_mask_and_checkerboard_in_json_and_xml(void **state) {
    fixture *f = *state;
    write_text(
        f->path,
        "{\"sensor\": {\"fov\": 60, \"film\": {\"width\": 16, \"height\": 16},\n"
        "   \"to_world\": {\"look_at\": {\"origin\": [0, 0, 3], \"target\": [0, 0, 0]}}},\n"
        " \"bsdfs\": {\"red\": {\"type\": \"diffuse\", \"reflectance\": [0.8, 0.1, 0.1]}},\n"
        " \"shapes\": [\n"
        "  {\"type\": \"rectangle\", \"bsdf\": {\"type\": \"blendbsdf\", \"weight\": 0.25, \"bsdf_0\": \"red\",\n"
        "    \"bsdf_1\": {\"type\": \"diffuse\", \"reflectance\": {\"type\": \"checkerboard\",\n"
        "      \"color0\": [0.9, 0.9, 0.9], \"to_uv\": {\"scale\": [4, 4, 1]}}}}},\n"
        "  {\"type\": \"sphere\", \"center\": [0, 0, 1], \"radius\": 0.3,\n"
        "   \"bsdf\": {\"type\": \"mask\", \"opacity\": 0.5, \"bsdf\": \"red\"}}],\n"
        " \"emitters\": [{\"type\": \"point\", \"position\": [0, 0, 2], \"intensity\": [2, 2, 2]}]}\n");
    const double json = mean_of_file(f, f->path);
    char xml[400];
    snprintf(xml, sizeof xml, "%s/scene.xml", f->folder);
    write_text(xml, "<scene version=\"3.0.0\">\n"
                    " <sensor type=\"perspective\"><float name=\"fov\" value=\"60\"/>\n"
                    "  <transform name=\"to_world\"><lookat origin=\"0, 0, 3\" target=\"0, 0, 0\" up=\"0, 1, 0\"/>"
                    "</transform>\n"
                    "  <film type=\"hdrfilm\"><integer name=\"width\" value=\"16\"/>"
                    "<integer name=\"height\" value=\"16\"/><rfilter type=\"box\"/></film></sensor>\n"
                    " <bsdf type=\"diffuse\" id=\"red\"><rgb name=\"reflectance\" value=\"0.8, 0.1, 0.1\"/></bsdf>\n"
                    " <shape type=\"rectangle\"><bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.25\"/>\n"
                    "  <ref name=\"bsdf_0\" id=\"red\"/>\n"
                    "  <bsdf type=\"diffuse\" name=\"bsdf_1\"><texture type=\"checkerboard\" name=\"reflectance\">\n"
                    "   <rgb name=\"color0\" value=\"0.9, 0.9, 0.9\"/>"
                    "<transform name=\"to_uv\"><scale x=\"4\" y=\"4\"/></transform></texture></bsdf>\n"
                    " </bsdf></shape>\n"
                    " <shape type=\"sphere\"><point name=\"center\" x=\"0\" y=\"0\" z=\"1\"/>"
                    "<float name=\"radius\" value=\"0.3\"/>\n"
                    "  <bsdf type=\"mask\"><float name=\"opacity\" value=\"0.5\"/><ref id=\"red\"/></bsdf></shape>\n"
                    " <emitter type=\"point\"><point name=\"position\" x=\"0\" y=\"0\" z=\"2\"/>"
                    "<rgb name=\"intensity\" value=\"2, 2, 2\"/></emitter>\n"
                    "</scene>\n");
    const double from_xml = mean_of_file(f, xml);
    print_message("blend/mask/checkerboard scene: JSON mean %.6f, XML mean %.6f\n", json, from_xml);
    assert_true(json > 0.01);
    assert_close(from_xml, json, 1e-6 * json);
    EXPECT_ERROR(f,
                 "{\"shapes\": [{\"type\": \"rectangle\", \"bsdf\": {\"type\": \"blendbsdf\", \"weight\": 2,\n"
                 "  \"bsdf_0\": {\"type\": \"diffuse\"}, \"bsdf_1\": {\"type\": \"diffuse\"}}}]}",
                 PPM_ERROR_PARSE, "scene.json:1:", "'weight' must lie in [0, 1]");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_small_box_builds_what_it_says, setup, teardown),
        cmocka_unit_test_setup_teardown(test_defaults_and_inline_patches, setup, teardown),
        cmocka_unit_test_setup_teardown(test_errors_are_located, setup, teardown),
        cmocka_unit_test_setup_teardown(test_area_lights_on_disks_cylinders_and_meshes, setup, teardown),
        cmocka_unit_test_setup_teardown(test_missing_and_malformed_files, setup, teardown),
        cmocka_unit_test_setup_teardown(test_unreadable_bytes_and_deep_nesting, setup, teardown),
        cmocka_unit_test_setup_teardown(test_overflowing_magnitudes_are_refused_where_they_stand, setup, teardown),
        cmocka_unit_test_setup_teardown(test_examples_load, setup, teardown),
        cmocka_unit_test_setup_teardown(test_blend_mask_and_checkerboard_in_json_and_xml, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
