/* SPDX-License-Identifier: Apache-2.0 */
/* Scene files read with options (ppm_scene_file_load_v2, ppm_scene_file_load_memory): Mitsuba
 * XML chosen by name or content, its parameters, lenient reading with warnings, scenes from
 * text, and the checks of the options struct. */
#include <ppm/ppm.h>

#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct fixture {
    ppm_context context;
    char folder[256];
    char path[320];
    int warnings;
    char last_warning[512];
} fixture;

static void collect_warning(void *user_data, const char *message) {
    fixture *f = user_data;
    f->warnings += 1;
    snprintf(f->last_warning, sizeof f->last_warning, "%s", message);
}

static int setup(void **state) {
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    assert_int_equal(ppm_context_create(&f->context), PPM_OK);
    assert_int_equal(ppm_context_set_warning_callback(f->context, collect_warning, f), PPM_OK);
    assert_int_equal(test_make_folder(f->folder, sizeof f->folder, "ppm-scene-options-"), 0);
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

/* Writes `text` to <folder>/<name> and leaves its path in f->path. */
static const char *write_file(fixture *f, const char *name, const char *text) {
    snprintf(f->path, sizeof f->path, "%s/%s", f->folder, name);
    FILE *file = fopen(f->path, "w");
    assert_non_null(file);
    fputs(text, file);
    fclose(file);
    return f->path;
}

static void assert_message_has(const char *fragment) {
    const char *message = ppm_last_error_message();
    if (!strstr(message, fragment)) fail_msg("message '%s' lacks '%s'", message, fragment);
}

static const char *const box_xml =
    "<scene version=\"3.0.0\">\n"
    "  <default name=\"res\" value=\"48\"/>\n"
    "  <default name=\"spp\" value=\"5\"/>\n"
    "  <sensor type=\"perspective\">\n"
    "    <float name=\"fov\" value=\"30\"/>\n"
    "    <transform name=\"to_world\"><lookat origin=\"0, -5, 1\" target=\"0, 0, 1\" up=\"0, 0, 1\"/></transform>\n"
    "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/></sampler>\n"
    "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"$res\"/><integer name=\"height\" "
    "value=\"32\"/></film>\n"
    "  </sensor>\n"
    "  <shape type=\"sphere\"><float name=\"radius\" value=\"0.5\"/></shape>\n"
    "  <emitter type=\"point\"><point name=\"position\" x=\"0\" y=\"-2\" z=\"3\"/></emitter>\n"
    "</scene>\n";

static void expect_film_and_passes(ppm_scene_file file, uint32_t width, uint32_t height, int64_t passes) {
    ppm_camera camera;
    assert_int_equal(ppm_scene_file_get_camera(file, &camera), PPM_OK);
    assert_int_equal(camera.width, width);
    assert_int_equal(camera.height, height);
    assert_close(camera.fov, 30, 1e-12);
    int64_t got = 0;
    assert_int_equal(ppm_scene_file_get_int(file, "passes", &got), PPM_OK);
    assert_int_equal(got, passes);
}

static void test_xml_is_chosen_by_extension_or_content(void **state) {
    fixture *f = *state;
    ppm_scene_file file = NULL;
    assert_int_equal(ppm_scene_file_load(f->context, write_file(f, "box.xml", box_xml), &file), PPM_OK);
    expect_film_and_passes(file, 48, 32, 5); /* the <default>s; sample_count becomes passes */
    ppm_scene_file_release(file);

    /* Any name: a text that starts with '<' is XML. */
    assert_int_equal(ppm_scene_file_load(f->context, write_file(f, "box.scene", box_xml), &file), PPM_OK);
    expect_film_and_passes(file, 48, 32, 5);
    ppm_scene_file_release(file);

    /* A format forced to JSON reads the XML as JSON, and says where that fails. */
    ppm_scene_file_options options;
    ppm_scene_file_options_init(&options);
    options.format = "json";
    file = NULL;
    assert_int_equal(ppm_scene_file_load_v2(f->context, f->path, &options, &file), PPM_ERROR_PARSE);
    assert_null(file);
    assert_message_has("box.scene:1:1");
}

static void test_parameters_replace_the_defaults(void **state) {
    fixture *f = *state;
    const char *names[] = {"res", "spp"};
    const char *values[] = {"24", "9"};
    ppm_scene_file_options options;
    ppm_scene_file_options_init(&options);
    options.define_names = names;
    options.define_values = values;
    options.define_count = 2;
    ppm_scene_file file = NULL;
    assert_int_equal(ppm_scene_file_load_v2(f->context, write_file(f, "box.xml", box_xml), &options, &file), PPM_OK);
    expect_film_and_passes(file, 24, 32, 9);
    ppm_scene_file_release(file);
    assert_int_equal(f->warnings, 0);

    /* A parameter no $name takes: a warning with the likely meaning, the file still loads. */
    names[1] = "ssp";
    assert_int_equal(ppm_scene_file_load_v2(f->context, f->path, &options, &file), PPM_OK);
    expect_film_and_passes(file, 24, 32, 5);
    ppm_scene_file_release(file);
    assert_int_equal(f->warnings, 1);
    assert_non_null(
        strstr(f->last_warning, "parameter 'ssp' (-D ssp=9) is not used by the scene (did you mean 'spp'?)"));
    names[1] = "spp";

    /* A value that is not a number where one is needed: located at the element using it. */
    values[0] = "wide";
    assert_int_equal(ppm_scene_file_load_v2(f->context, f->path, &options, &file), PPM_ERROR_PARSE);
    assert_message_has("box.xml:8:");

    /* JSON files have no parameters. */
    values[0] = "24";
    assert_int_equal(ppm_scene_file_load_v2(f->context, PPM_TEST_DATA_DIR "/scenes/small_box.json", &options, &file),
                     PPM_ERROR_INVALID_ARGUMENT);
    assert_message_has("apply to Mitsuba XML scene files only");
}

static const char *const rough_xml =
    "<scene version=\"3.0.0\">\n"
    "  <shape type=\"sphere\">\n"
    "    <bsdf type=\"hair\"><float name=\"alpha\" value=\"0.1\"/></bsdf>\n"
    "  </shape>\n"
    "  <emitter type=\"sunsky\"><string name=\"filename\" value=\"sky\"/></emitter>\n"
    "  <emitter type=\"point\"><point name=\"position\" x=\"0\" y=\"-2\" z=\"3\"/></emitter>\n"
    "</scene>\n";

static void test_lenient_substitutes_with_warnings_and_strict_names_the_element(void **state) {
    fixture *f = *state;
    ppm_scene_file file = NULL;
    /* Strict: what the reader passes on, the builder refuses at the XML element's position. */
    assert_int_equal(ppm_scene_file_load(f->context, write_file(f, "rough.xml", rough_xml), &file), PPM_ERROR_PARSE);
    assert_null(file);
    assert_message_has("rough.xml:3:5: <bsdf>: BSDF type 'hair' is not supported by libppm");
    f->warnings = 0;

    ppm_scene_file_options options;
    ppm_scene_file_options_init(&options);
    options.lenient = 1;
    assert_int_equal(ppm_scene_file_load_v2(f->context, f->path, &options, &file), PPM_OK);
    /* One per substituted or dropped element, and a summary line that lists them again. */
    assert_int_equal(f->warnings, 3);
    if (!strstr(f->last_warning, "--lenient replaced or left out 2 elements, at ") ||
        !strstr(f->last_warning, "rough.xml:3:5: <bsdf>") || !strstr(f->last_warning, "rough.xml:5:3: <emitter>"))
        fail_msg("last warning '%s' is not the summary", f->last_warning);
    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_file_get_scene(file, &scene), PPM_OK);
    ppm_scene_release(scene);
    ppm_scene_file_release(file);
}

/* A parameter libppm refuses on a type it renders: strict reading names it; lenient reading
 * replaces the material by grey and skips the light and the shape, each with a warning. */
static void test_lenient_covers_parameter_refusals(void **state) {
    fixture *f = *state;
    static const char xml[] =
        "<scene version=\"3.0.0\">\n"
        "  <shape type=\"sphere\"><bsdf type=\"diffuse\"><float name=\"roughness\" value=\"0.3\"/>"
        "</bsdf></shape>\n"
        "  <shape type=\"sphere\"><float name=\"radius\" value=\"-2\"/></shape>\n"
        "  <emitter type=\"point\"><float name=\"size\" value=\"1\"/></emitter>\n"
        "  <emitter type=\"point\"/>\n"
        "</scene>\n";
    ppm_scene_file file = NULL;
    assert_int_equal(ppm_scene_file_load(f->context, write_file(f, "params.xml", xml), &file), PPM_ERROR_PARSE);
    assert_message_has("params.xml:4:25: emitters[0].size: point light has no parameter 'size'");
    f->warnings = 0;
    ppm_scene_file_options options;
    ppm_scene_file_options_init(&options);
    options.lenient = 1;
    assert_int_equal(ppm_scene_file_load_v2(f->context, f->path, &options, &file), PPM_OK);
    assert_int_equal(f->warnings, 4); /* the material, the shape, the light, and the summary */
    if (!strstr(f->last_warning, "--lenient replaced or left out 3 elements")) fail_msg("'%s'", f->last_warning);
    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_file_get_scene(file, &scene), PPM_OK);
    size_t geometries = 0;
    assert_int_equal(ppm_scene_get_geometry_count(scene, &geometries), PPM_OK);
    assert_int_equal(geometries, 1);
    ppm_scene_release(scene);
    ppm_scene_file_release(file);
}

static void test_scene_from_text_resolves_names_against_the_folder(void **state) {
    fixture *f = *state;
    const char *json = "{\n"
                       "  \"shapes\": [\n"
                       "    {\"type\": \"bezier\", \"filename\": \"teapot.bpt\"}\n"
                       "  ],\n"
                       "  \"emitters\": [{\"type\": \"point\", \"position\": [0, -5, 5], \"intensity\": 10}]\n"
                       "}\n";
    ppm_scene_file file = NULL;
    assert_int_equal(
        ppm_scene_file_load_memory(f->context, json, strlen(json), "inline.json", PPM_TEST_DATA_DIR, NULL, &file),
        PPM_OK);
    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_file_get_scene(file, &scene), PPM_OK);
    double lower[3], upper[3];
    assert_int_equal(ppm_scene_get_bounds(scene, lower, upper), PPM_OK);
    assert_true(upper[0] > lower[0]); /* the teapot's patches are there */
    ppm_scene_release(scene);
    ppm_scene_file_release(file);

    /* Without the folder the name does not resolve: an IO error naming the file. */
    assert_int_equal(ppm_scene_file_load_memory(f->context, json, strlen(json), NULL, f->folder, NULL, &file),
                     PPM_ERROR_IO);
    assert_message_has("teapot.bpt");

    /* Errors inside the text are located in it. */
    const char *bad = "{\n  \"shapes\": [\n    {\"type\": \"sphere\", \"radius\": -1}\n  ]\n}\n";
    assert_int_equal(ppm_scene_file_load_memory(f->context, bad, strlen(bad), NULL, NULL, NULL, &file),
                     PPM_ERROR_PARSE);
    assert_message_has("<scene text>:3:");
    assert_message_has("shapes[0].radius");

    /* XML text too. */
    assert_int_equal(ppm_scene_file_load_memory(f->context, box_xml, strlen(box_xml), "box.xml", NULL, NULL, &file),
                     PPM_OK);
    expect_film_and_passes(file, 48, 32, 5);
    ppm_scene_file_release(file);
}

/* A misspelled key or type name in a scene file is named with its likely meaning. */
static void test_misspellings_get_a_suggestion(void **state) {
    fixture *f = *state;
    const char *bad_type = "{\"bsdfs\": {\"grey\": {\"type\": \"difuse\"}}, \"shapes\": []}";
    ppm_scene_file file = NULL;
    assert_int_equal(
        ppm_scene_file_load_memory(f->context, bad_type, strlen(bad_type), "typo.json", f->folder, NULL, &file),
        PPM_ERROR_PARSE);
    assert_message_has("typo.json:1:");
    assert_message_has("'difuse'");
    assert_message_has("(did you mean 'diffuse'?)");
    const char *bad_key = "{\"bsdfs\": {\"grey\": {\"type\": \"diffuse\", \"reflectanse\": 0.5}}, \"shapes\": []}";
    assert_int_equal(
        ppm_scene_file_load_memory(f->context, bad_key, strlen(bad_key), "typo.json", f->folder, NULL, &file),
        PPM_ERROR_PARSE);
    assert_message_has(
        "bsdfs.grey.reflectanse: diffuse material has no parameter 'reflectanse' (did you mean 'reflectance'?)");
    assert_null(file);
}

/* A file that fails to load still gives the warnings met before the error: here the one
 * naming the folders in which a mesh was looked for. */
static void test_warnings_are_given_when_loading_fails(void **state) {
    fixture *f = *state;
    const char *xml = "<scene version=\"3.0.0\">\n"
                      "  <shape type=\"ply\"><string name=\"filename\" value=\"missing.ply\"/></shape>\n"
                      "</scene>\n";
    ppm_scene_file file = NULL;
    assert_int_equal(ppm_scene_file_load(f->context, write_file(f, "missing.xml", xml), &file), PPM_ERROR_IO);
    assert_null(file);
    assert_message_has("missing.ply");
    assert_int_equal(f->warnings, 1);
    if (!strstr(f->last_warning, "missing.xml:2:") || !strstr(f->last_warning, "\"missing.ply\" is in none of"))
        fail_msg("warning '%s'", f->last_warning);
}

static void test_bad_options_are_refused(void **state) {
    fixture *f = *state;
    const char *path = write_file(f, "box.xml", box_xml);
    ppm_scene_file file = NULL;
    ppm_scene_file_options options;

    ppm_scene_file_options_init(&options);
    options.size = 8;
    assert_int_equal(ppm_scene_file_load_v2(f->context, path, &options, &file), PPM_ERROR_INVALID_ARGUMENT);
    assert_message_has("ppm_scene_file_options_init");

    ppm_scene_file_options_init(&options);
    options.format = "yaml";
    assert_int_equal(ppm_scene_file_load_v2(f->context, path, &options, &file), PPM_ERROR_INVALID_ARGUMENT);
    assert_message_has("yaml");

    ppm_scene_file_options_init(&options);
    options.define_count = 1;
    assert_int_equal(ppm_scene_file_load_v2(f->context, path, &options, &file), PPM_ERROR_INVALID_ARGUMENT);
    assert_message_has("define_names");

    const char *names[] = {""};
    const char *values[] = {"1"};
    options.define_names = names;
    options.define_values = values;
    assert_int_equal(ppm_scene_file_load_v2(f->context, path, &options, &file), PPM_ERROR_INVALID_ARGUMENT);
    assert_message_has("empty");

    ppm_scene_file_options_init(&options);
    options.reserved[0] = 1;
    assert_int_equal(ppm_scene_file_load_v2(f->context, path, &options, &file), PPM_ERROR_INVALID_ARGUMENT);
    assert_message_has("reserved");

    /* A newer caller's struct: bytes beyond this library's are accepted while 0. */
    struct newer {
        ppm_scene_file_options options;
        uint64_t field;
    } newer;
    memset(&newer, 0, sizeof newer);
    newer.options.size = sizeof newer;
    assert_int_equal(ppm_scene_file_load_v2(f->context, path, &newer.options, &file), PPM_OK);
    ppm_scene_file_release(file);
    newer.field = 3;
    assert_int_equal(ppm_scene_file_load_v2(f->context, path, &newer.options, &file), PPM_ERROR_UNSUPPORTED);

    assert_int_equal(ppm_scene_file_load_memory(f->context, NULL, 3, NULL, NULL, NULL, &file),
                     PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_file_load_v2(NULL, path, NULL, &file), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_file_load_v2(f->context, NULL, NULL, &file), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_file_load_v2(f->context, path, NULL, NULL), PPM_ERROR_INVALID_ARGUMENT);
}

/* Mesh files named in an XML scene are found beside the file that names them, whatever the
 * working folder (Mitsuba resolves them so). */
static void test_xml_file_names_are_relative_to_the_scene(void **state) {
    fixture *f = *state;
    write_file(f, "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write_file(f, "part.xml",
               "<scene version=\"3.0.0\"><shape type=\"obj\"><string name=\"filename\" value=\"tri.obj\"/>"
               "</shape></scene>\n");
    const char *path = write_file(f, "scene.xml",
                                  "<scene version=\"3.0.0\">\n"
                                  "  <include filename=\"part.xml\"/>\n"
                                  "  <shape type=\"obj\"><string name=\"filename\" value=\"tri.obj\"/></shape>\n"
                                  "</scene>\n");
    assert_true(path[0] == '/'); /* an absolute path: the working folder is not the scene's */
    ppm_scene_file file = NULL;
    assert_int_equal(ppm_scene_file_load(f->context, path, &file), PPM_OK);
    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_file_get_scene(file, &scene), PPM_OK);
    size_t count = 0;
    assert_int_equal(ppm_scene_get_geometry_count(scene, &count), PPM_OK);
    assert_int_equal(count, 2);
    ppm_scene_release(scene);
    ppm_scene_file_release(file);
}

/* The hit of a ray straight down the z axis onto the scene of an XML file. */
static ppm_hit hit_from_above(fixture *f, const char *path) {
    ppm_scene_file file = NULL;
    if (ppm_scene_file_load(f->context, path, &file) != PPM_OK) fail_msg("%s", ppm_last_error_message());
    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_file_get_scene(file, &scene), PPM_OK);
    const ppm_ray ray = {{0.2, 0.2, 5}, 0, {0, 0, -1}, INFINITY};
    ppm_hit hit;
    assert_int_equal(ppm_scene_intersect(scene, &ray, 1, &hit), PPM_OK);
    ppm_scene_release(scene);
    ppm_scene_file_release(file);
    assert_true(hit.t < INFINITY);
    return hit;
}

/* Mitsuba's face_normals drops a mesh's vertex normals; a mirroring to_world keeps a
 * rectangle's normal where Mitsuba puts it (the normal transform of +z). */
static void test_face_normals_and_mirrored_rectangles(void **state) {
    fixture *f = *state;
    write_file(f, "tilted.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nvn 0.6 0 0.8\nf 1//1 2//1 3//1\n");
    const char *smooth = "<scene version=\"3.0.0\"><shape type=\"obj\">"
                         "<string name=\"filename\" value=\"tilted.obj\"/></shape></scene>\n";
    const char *flat = "<scene version=\"3.0.0\"><shape type=\"obj\">"
                       "<string name=\"filename\" value=\"tilted.obj\"/>"
                       "<boolean name=\"face_normals\" value=\"true\"/></shape></scene>\n";
    ppm_hit hit = hit_from_above(f, write_file(f, "smooth.xml", smooth));
    assert_true(fabs(hit.ns[0] - 0.6) < 1e-9 && fabs(hit.ns[2] - 0.8) < 1e-9);
    hit = hit_from_above(f, write_file(f, "flat.xml", flat));
    assert_true(fabs(hit.ns[0]) < 1e-9 && fabs(fabs(hit.ns[2]) - 1) < 1e-9);

    const char *mirrored = "<scene version=\"3.0.0\"><shape type=\"rectangle\">"
                           "<transform name=\"to_world\"><scale x=\"-1\"/></transform></shape></scene>\n";
    hit = hit_from_above(f, write_file(f, "mirrored.xml", mirrored));
    assert_true(fabs(hit.ng[2] - 1) < 1e-12); /* +z, as without the mirror */

    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_create(f->context, &scene), PPM_OK);
    const double c[3] = {0, 0, 0};
    uint32_t sphere = 0;
    assert_int_equal(ppm_scene_add_sphere(scene, c, 1, &sphere), PPM_OK);
    assert_int_equal(ppm_scene_set_mesh_face_normals(scene, sphere, 1), PPM_ERROR_INVALID_ARGUMENT);
    assert_message_has("face_normals applies to triangle meshes");
    ppm_scene_release(scene);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_xml_is_chosen_by_extension_or_content, setup, teardown),
        cmocka_unit_test_setup_teardown(test_parameters_replace_the_defaults, setup, teardown),
        cmocka_unit_test_setup_teardown(test_lenient_substitutes_with_warnings_and_strict_names_the_element, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(test_lenient_covers_parameter_refusals, setup, teardown),
        cmocka_unit_test_setup_teardown(test_scene_from_text_resolves_names_against_the_folder, setup, teardown),
        cmocka_unit_test_setup_teardown(test_warnings_are_given_when_loading_fails, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_options_are_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_misspellings_get_a_suggestion, setup, teardown),
        cmocka_unit_test_setup_teardown(test_xml_file_names_are_relative_to_the_scene, setup, teardown),
        cmocka_unit_test_setup_teardown(test_face_normals_and_mirrored_rectangles, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
