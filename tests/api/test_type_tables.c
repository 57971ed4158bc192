/* SPDX-License-Identifier: Apache-2.0 */
/* The plugin tables through the C API: ppm_type_count / ppm_type_name list every kind's
 * types, docs/scene-format.md lists exactly the types the tables hold, and ppm_scene_add_shape
 * builds shapes by name with Mitsuba's parameters (checked against closed-form hits). */
#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const kinds[] = {"material", "texture", "light", "shape", "mode"};

static void test_every_kind_lists_distinct_names(void **state) {
    (void)state;
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; ++k) {
        size_t count = 0;
        assert_ppm_ok(ppm_type_count(kinds[k], &count));
        assert_true(count > 0);
        for (size_t i = 0; i < count; ++i) {
            const char *name = NULL, *other = NULL;
            assert_ppm_ok(ppm_type_name(kinds[k], i, &name));
            assert_non_null(name);
            assert_true(name[0] != '\0');
            for (size_t j = 0; j < i; ++j) {
                assert_ppm_ok(ppm_type_name(kinds[k], j, &other));
                assert_string_not_equal(name, other);
            }
        }
        const char *name = NULL;
        assert_ppm_error(ppm_type_name(kinds[k], count, &name), PPM_ERROR_INVALID_ARGUMENT, "is not below");
    }
    /* The modes in number order, as checkpoints record them. */
    const char *const modes[] = {"sppm", "ppm", "pppm", "vcm", "bpt", "vm"};
    size_t count = 0;
    assert_ppm_ok(ppm_type_count("mode", &count));
    assert_int_equal(count, 6);
    for (size_t i = 0; i < count; ++i) {
        const char *name = NULL;
        assert_ppm_ok(ppm_type_name("mode", i, &name));
        assert_string_equal(name, modes[i]);
    }
}

static void test_bad_arguments_are_named(void **state) {
    (void)state;
    size_t count = 0;
    const char *name = NULL;
    assert_ppm_error(ppm_type_count(NULL, &count), PPM_ERROR_INVALID_ARGUMENT, "kind is NULL");
    assert_ppm_error(ppm_type_count("material", NULL), PPM_ERROR_INVALID_ARGUMENT, "out_count");
    assert_ppm_error(ppm_type_count("bsdf", &count), PPM_ERROR_INVALID_ARGUMENT, "unknown kind 'bsdf'");
    assert_ppm_error(ppm_type_name("shape", 0, NULL), PPM_ERROR_INVALID_ARGUMENT, "out_name");
    assert_ppm_error(ppm_type_name(NULL, 0, &name), PPM_ERROR_INVALID_ARGUMENT, "kind is NULL");
}

/* Whether `name` is a row of the table of `kind`. */
static int in_table(const char *kind, const char *name) {
    size_t count = 0;
    if (ppm_type_count(kind, &count) != PPM_OK) return 0;
    for (size_t i = 0; i < count; ++i) {
        const char *row = NULL;
        if (ppm_type_name(kind, i, &row) == PPM_OK && strcmp(row, name) == 0) return 1;
    }
    return 0;
}

/* The types docs/scene-format.md lists under `heading`: the first cells "| `name` |" of the
 * section's first table, or (quoted_row: the textures) the quoted names of a `type` row. */
static size_t documented_types(const char *doc, const char *heading, int quoted_row, char names[][32], size_t max) {
    const char *section = strstr(doc, heading);
    if (!section) fail_msg("docs/scene-format.md has no heading '%s'", heading);
    const char *end = strstr(section + strlen(heading), "\n## ");
    if (!end) end = section + strlen(section);
    size_t n = 0;
    for (const char *line = section; line && line < end; line = strchr(line, '\n'), line = line ? line + 1 : NULL) {
        if (quoted_row) {
            if (strncmp(line, "| `type` | string |", 19) != 0) continue;
            const char *eol = strchr(line, '\n');
            for (const char *q = strstr(line, "`\""); q && q < eol && n < max; q = strstr(q, "`\"")) {
                q += 2;
                const char *close = strchr(q, '"');
                snprintf(names[n++], 32, "%.*s", (int)(close - q), q);
                q = close;
            }
            break;
        }
        if (line[0] != '|') {
            if (n > 0) break; /* the end of the section's first table */
            continue;
        }
        if (strncmp(line, "| `", 3) != 0 || strncmp(line, "| `type`", 8) == 0) continue;
        const char *close = strchr(line + 3, '`');
        if (n < max) snprintf(names[n++], 32, "%.*s", (int)(close - line - 3), line + 3);
    }
    return n;
}

static void check_documented(const char *doc, const char *heading, const char *kind, int quoted_row) {
    char names[64][32];
    const size_t n = documented_types(doc, heading, quoted_row, names, 64);
    size_t count = 0;
    assert_ppm_ok(ppm_type_count(kind, &count));
    for (size_t i = 0; i < n; ++i)
        if (!in_table(kind, names[i]))
            fail_msg("%s lists %s type '%s', which no table row has", heading, kind, names[i]);
    for (size_t i = 0; i < count; ++i) {
        const char *row = NULL;
        assert_ppm_ok(ppm_type_name(kind, i, &row));
        int found = 0;
        for (size_t j = 0; j < n; ++j) found |= strcmp(names[j], row) == 0;
        if (!found)
            fail_msg("the %s table has '%s', which docs/scene-format.md (%s) does not list", kind, row, heading);
    }
}

static void test_scene_format_lists_the_tables(void **state) {
    (void)state;
    FILE *file = fopen(PPM_DOCS_DIR "/scene-format.md", "rb");
    assert_non_null(file);
    static char doc[1 << 18];
    const size_t size = fread(doc, 1, sizeof doc - 1, file);
    fclose(file);
    doc[size] = '\0';
    check_documented(doc, "\n## bsdfs\n", "material", 0);
    check_documented(doc, "\n## emitters\n", "light", 0);
    check_documented(doc, "\n## shapes\n", "shape", 0);
    check_documented(doc, "\n## bsdfs\n", "texture", 1); /* the texture table of that section */
}

typedef scene_fixture fixture;

static ppm_param numbers(const char *name, const double *values, size_t count) {
    ppm_param p = {name, PPM_PARAM_NUMBERS, values, count, NULL, 0};
    return p;
}

/* The distance along +y from (0, -10, 0) to the first hit, or -1 on a miss. */
static double hit_along_y(ppm_scene scene, double x, double z) {
    ppm_ray ray = {{x, -10, z}, 0, {0, 1, 0}, INFINITY};
    ppm_hit hit;
    assert_ppm_ok(ppm_scene_intersect(scene, &ray, 1, &hit));
    return hit.geom_id == PPM_INVALID_ID ? -1 : hit.t;
}

static void test_shapes_by_name_are_placed_as_mitsuba_places_them(void **state) {
    fixture *f = *state;
    /* A sphere of radius 2 at the origin, moved 3 along +x by to_world. */
    const double radius = 2, center[3] = {0, 0, 0};
    const double to_world[16] = {1, 0, 0, 3, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const ppm_param sphere[] = {numbers("radius", &radius, 1), numbers("center", center, 3),
                                numbers("to_world", to_world, 16)};
    uint32_t geom = PPM_INVALID_ID;
    assert_ppm_ok(ppm_scene_add_shape(f->scene, "sphere", sphere, 3, &geom));
    assert_int_equal(geom, 0);
    /* Mitsuba's rectangle [-1, 1]^2 scaled by 4 and turned to face -y, at y = 5. */
    const double rect_world[16] = {4, 0, 0, -20, 0, 0, -4, 5, 0, 4, 0, 0, 0, 0, 0, 1};
    const ppm_param rectangle[] = {numbers("to_world", rect_world, 16)};
    assert_ppm_ok(ppm_scene_add_shape(f->scene, "rectangle", rectangle, 1, &geom));
    assert_int_equal(geom, 1);
    assert_ppm_ok(ppm_scene_commit(f->scene));
    assert_true(fabs(hit_along_y(f->scene, 3, 0) - 8) < 1e-9); /* the sphere's front at y = -2 */
    assert_true(fabs(hit_along_y(f->scene, 3 + 1.5, 0) - (10 - sqrt(4 - 2.25))) < 1e-9);
    assert_true(fabs(hit_along_y(f->scene, -20, 3.9) - 15) < 1e-9); /* the rectangle at y = 5 */
    assert_true(hit_along_y(f->scene, -20, 4.1) < 0);               /* beyond its edge */
}

static void test_shape_parameters_are_checked_before_anything_is_added(void **state) {
    fixture *f = *state;
    const double radius = -1, one = 1;
    const ppm_param bad_radius[] = {numbers("radius", &radius, 1)};
    const ppm_param misspelt[] = {numbers("radiuss", &one, 1)};
    const ppm_param no_edges[] = {numbers("origin", (const double[3]){0, 0, 0}, 3)};
    const double p[3] = {0, 0, 0};
    const ppm_param no_length[] = {numbers("p0", p, 3), numbers("p1", p, 3)};
    uint32_t geom = 7;
    assert_ppm_error(ppm_scene_add_shape(NULL, "sphere", NULL, 0, &geom), PPM_ERROR_INVALID_ARGUMENT, "scene is NULL");
    assert_ppm_error(ppm_scene_add_shape(f->scene, NULL, NULL, 0, &geom), PPM_ERROR_INVALID_ARGUMENT, "NULL");
    assert_ppm_error(ppm_scene_add_shape(f->scene, "spere", NULL, 0, &geom), PPM_ERROR_INVALID_ARGUMENT,
                     "unknown shape type 'spere'");
    assert_ppm_error(ppm_scene_add_shape(f->scene, "sphere", bad_radius, 1, &geom), PPM_ERROR_INVALID_ARGUMENT,
                     "sphere shape: parameter 'radius' must be > 0");
    assert_ppm_error(ppm_scene_add_shape(f->scene, "sphere", misspelt, 1, &geom), PPM_ERROR_INVALID_ARGUMENT,
                     "did you mean 'radius'?");
    assert_ppm_error(ppm_scene_add_shape(f->scene, "quad", no_edges, 1, &geom), PPM_ERROR_INVALID_ARGUMENT,
                     "parameter 'edge_u' must be given");
    assert_ppm_error(ppm_scene_add_shape(f->scene, "cylinder", no_length, 2, &geom), PPM_ERROR_INVALID_ARGUMENT,
                     "p0 and p1 are equal");
    assert_ppm_error(ppm_scene_add_shape(f->scene, "obj", NULL, 0, &geom), PPM_ERROR_INVALID_ARGUMENT,
                     "parameter 'filename' must be given");
    assert_int_equal(geom, 7);
    size_t count = 99;
    assert_ppm_ok(ppm_scene_get_geometry_count(f->scene, &count));
    assert_int_equal(count, 0);
}

/* A renderer describes the geometries of its scene when it was made: one added later is
 * refused by name instead of being rendered without a material. */
static void test_a_renderer_refuses_geometry_added_after_it(void **state) {
    fixture *f = *state;
    assert_ppm_ok(ppm_scene_add_shape(f->scene, "sphere", NULL, 0, NULL));
    assert_ppm_ok(ppm_scene_commit(f->scene));
    const ppm_camera camera = {{0, -5, 0}, {0, 0, 0}, {0, 0, 1}, 40, 8, 8, 0, 0, 0.01};
    ppm_renderer renderer = NULL;
    assert_ppm_ok(ppm_renderer_create(f->scene, &camera, &renderer));
    assert_ppm_ok(ppm_scene_add_shape(f->scene, "cube", NULL, 0, NULL));
    assert_ppm_ok(ppm_scene_commit(f->scene));
    assert_ppm_error(ppm_renderer_render_pass(renderer), PPM_ERROR_INVALID_OPERATION, "create a new renderer");
    ppm_renderer_release(renderer);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_kind_lists_distinct_names),
        cmocka_unit_test(test_bad_arguments_are_named),
        cmocka_unit_test(test_scene_format_lists_the_tables),
        cmocka_unit_test_setup_teardown(test_shapes_by_name_are_placed_as_mitsuba_places_them, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_shape_parameters_are_checked_before_anything_is_added, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(test_a_renderer_refuses_geometry_added_after_it, scene_fixture_setup,
                                        scene_fixture_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
