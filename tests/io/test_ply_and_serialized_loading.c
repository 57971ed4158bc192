/* SPDX-License-Identifier: Apache-2.0 */
/* PLY and Mitsuba serialized meshes through the C API: a square written to a file loads,
 * is hit where it lies, reports what it skips through the warning callback, and damaged or
 * missing files are refused with their name in the message. */
#include <ppm/ppm.h>

#include "test_support.h"

#include <zlib.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

static char folder[4096];
static char warnings[4096];

static void collect_warning(void *user_data, const char *message) {
    size_t *count = user_data;
    ++*count;
    strncat(warnings, message, sizeof warnings - strlen(warnings) - 2);
    strcat(warnings, "\n");
}

static void write_file(const char *path, const void *data, size_t size) {
    FILE *file = fopen(path, "wb");
    assert_non_null(file);
    assert_int_equal(fwrite(data, 1, size, file), size);
    assert_int_equal(fclose(file), 0);
}

/* The square [0, 2] x [0, 2] at z = 1, as a quad, with a colour per vertex. */
static const char square_ply[] = "ply\n"
                                 "format ascii 1.0\n"
                                 "element vertex 4\n"
                                 "property float x\nproperty float y\nproperty float z\n"
                                 "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                                 "element face 1\n"
                                 "property list uchar int vertex_indices\n"
                                 "end_header\n"
                                 "0 0 1 255 0 0\n2 0 1 0 255 0\n2 2 1 0 0 255\n0 2 1 9 9 9\n"
                                 "4 0 1 2 3\n";

/* The cube [-1, 1]^3 without normals, two triangles a side, wound outwards. */
static const char cube_ply[] = "ply\nformat ascii 1.0\nelement vertex 8\n"
                               "property float x\nproperty float y\nproperty float z\n"
                               "element face 12\nproperty list uchar int vertex_indices\nend_header\n"
                               "-1 -1 -1\n-1 -1 1\n-1 1 -1\n-1 1 1\n1 -1 -1\n1 -1 1\n1 1 -1\n1 1 1\n"
                               "3 0 1 3\n3 0 3 2\n3 4 6 7\n3 4 7 5\n3 0 4 5\n3 0 5 1\n"
                               "3 2 3 7\n3 2 7 6\n3 0 2 6\n3 0 6 4\n3 1 5 7\n3 1 7 3\n";

/* Traces a ray down the z axis at (x, y) and returns the hit distance (INFINITY on a miss). */
static double hit_distance(ppm_scene scene, double x, double y) {
    ppm_ray ray = {{x, y, 5}, 0, {0, 0, -1}, INFINITY};
    ppm_hit hit;
    assert_int_equal(ppm_scene_intersect(scene, &ray, 1, &hit), PPM_OK);
    return hit.geom_id == PPM_INVALID_ID ? INFINITY : hit.t;
}

static void ply_file_loads_is_hit_and_warns_of_colours(void **state) {
    scene_fixture *f = *state;
    size_t count = 0;
    warnings[0] = '\0';
    assert_int_equal(ppm_context_set_warning_callback(f->context, collect_warning, &count), PPM_OK);
    char path[4200];
    snprintf(path, sizeof path, "%s/square.ply", folder);
    write_file(path, square_ply, strlen(square_ply));
    uint32_t id = 99;
    assert_int_equal(ppm_scene_load_ply(f->scene, path, &id), PPM_OK);
    assert_int_equal(id, 0);
    assert_int_equal(count, 1);
    assert_non_null(strstr(warnings, "square.ply: vertex colours are ignored"));
    assert_int_equal(ppm_scene_commit(f->scene), PPM_OK);
    assert_close(hit_distance(f->scene, 0.5, 1.5), 4.0, 1e-12);
    assert_close(hit_distance(f->scene, 1.5, 0.5), 4.0, 1e-12);
    assert_true(isinf(hit_distance(f->scene, 2.5, 0.5)));
}

/* A mesh file without normals shades with Mitsuba's computed vertex normals, from the placed
 * positions: on the cube stretched to [-2, 2] x [-1, 1]^2 each corner still meets three
 * right angles, so near the corner (2, 1, 1) the shading normal is the diagonal
 * (1, 1, 1) / sqrt(3), not the object normal carried by the transform, normalize(1/2, 1, 1).
 * face_normals makes it flat. */
static void ply_file_without_normals_shades_with_mitsubas_vertex_normals(void **state) {
    scene_fixture *f = *state;
    char path[4200];
    snprintf(path, sizeof path, "%s/cube.ply", folder);
    write_file(path, cube_ply, strlen(cube_ply));
    uint32_t id = 0;
    assert_int_equal(ppm_scene_load_ply(f->scene, path, &id), PPM_OK);
    const double stretch[16] = {2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    assert_int_equal(ppm_scene_set_geometry_transform(f->scene, id, stretch), PPM_OK);
    assert_int_equal(ppm_scene_commit(f->scene), PPM_OK);
    const ppm_ray ray = {{10, 0.9999, 0.9999}, 0, {-1, 0, 0}, INFINITY};
    ppm_hit hit;
    assert_int_equal(ppm_scene_intersect(f->scene, &ray, 1, &hit), PPM_OK);
    assert_int_equal(hit.geom_id, id);
    assert_true(fabs(hit.t - 8) < 1e-9);
    for (int a = 0; a < 3; ++a) assert_true(fabs(hit.ns[a] - 1 / sqrt(3.0)) < 1e-3);
    assert_true(hit.ng[0] > 0.999999);

    assert_int_equal(ppm_scene_set_mesh_face_normals(f->scene, id, 1), PPM_OK);
    assert_int_equal(ppm_scene_commit(f->scene), PPM_OK);
    assert_int_equal(ppm_scene_intersect(f->scene, &ray, 1, &hit), PPM_OK);
    for (int a = 0; a < 3; ++a) assert_true(hit.ns[a] == hit.ng[a]);
}

static void damaged_or_missing_ply_files_are_refused_by_name(void **state) {
    scene_fixture *f = *state;
    char path[4200];
    snprintf(path, sizeof path, "%s/bad.ply", folder);
    char text[sizeof square_ply];
    memcpy(text, square_ply, sizeof square_ply);
    strstr(text, "4 0 1 2 3")[8] = '7'; /* the last corner becomes vertex 7 of 4 */
    write_file(path, text, strlen(text));
    assert_int_equal(ppm_scene_load_ply(f->scene, path, NULL), PPM_ERROR_PARSE);
    assert_non_null(strstr(ppm_last_error_message(), "bad.ply:"));
    assert_non_null(strstr(ppm_last_error_message(), "vertex index 7 is out of range"));
    assert_int_equal(ppm_scene_load_ply(f->scene, "/nonexistent/mesh.ply", NULL), PPM_ERROR_IO);
    assert_non_null(strstr(ppm_last_error_message(), "/nonexistent/mesh.ply"));
    assert_int_equal(ppm_scene_load_ply(f->scene, NULL, NULL), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_load_ply(NULL, path, NULL), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_load_serialized(f->scene, NULL, 0, NULL), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_context_set_warning_callback(NULL, collect_warning, NULL), PPM_ERROR_INVALID_ARGUMENT);
}

static void put(unsigned char **at, const void *value, size_t size) {
    memcpy(*at, value, size);
    *at += size;
}

/* The same square as a version 4 serialized file with one mesh, single precision. */
static size_t serialized_square(unsigned char *out, size_t capacity) {
    unsigned char body[512], *at = body;
    const uint32_t flags = 0x1000;
    const uint64_t vertices = 4, triangles = 2;
    put(&at, &flags, 4);
    put(&at, "square", 7);
    put(&at, &vertices, 8);
    put(&at, &triangles, 8);
    const float positions[12] = {0, 0, 1, 2, 0, 1, 2, 2, 1, 0, 2, 1};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    put(&at, positions, sizeof positions);
    put(&at, indices, sizeof indices);
    const uint16_t header[2] = {0x041C, 4};
    memcpy(out, header, 4);
    uLongf size = capacity - 4 - 12;
    assert_int_equal(compress(out + 4, &size, body, (uLong)(at - body)), Z_OK);
    unsigned char *end = out + 4 + size;
    const uint64_t offset = 0;
    const uint32_t count = 1;
    put(&end, &offset, 8);
    put(&end, &count, 4);
    return (size_t)(end - out);
}

static void serialized_file_loads_and_a_wrong_index_is_refused(void **state) {
    scene_fixture *f = *state;
    unsigned char bytes[1024];
    const size_t size = serialized_square(bytes, sizeof bytes);
    char path[4200];
    snprintf(path, sizeof path, "%s/square.serialized", folder);
    write_file(path, bytes, size);
    assert_int_equal(ppm_scene_load_serialized(f->scene, path, 1, NULL), PPM_ERROR_PARSE);
    assert_non_null(strstr(ppm_last_error_message(), "square.serialized"));
    assert_non_null(strstr(ppm_last_error_message(), "shape_index 1 is out of range"));
    assert_int_equal(ppm_scene_load_serialized(f->scene, path, 0, NULL), PPM_OK);
    assert_int_equal(ppm_scene_commit(f->scene), PPM_OK);
    assert_close(hit_distance(f->scene, 1.5, 0.5), 4.0, 1e-12);
}

/* A JSON scene file naming both mesh files, and a point light placed by to_world. */
static void scene_files_take_ply_and_serialized_shapes(void **state) {
    scene_fixture *f = *state;
    char path[4200];
    snprintf(path, sizeof path, "%s/square.ply", folder);
    write_file(path, square_ply, strlen(square_ply));
    unsigned char bytes[1024];
    const size_t size = serialized_square(bytes, sizeof bytes);
    snprintf(path, sizeof path, "%s/square.serialized", folder);
    write_file(path, bytes, size);
    const char *scene_text =
        "{ \"emitters\": [{ \"type\": \"point\", \"to_world\": { \"translate\": [1, 1, 3] } }],\n"
        "  \"shapes\": [{ \"type\": \"ply\", \"filename\": \"square.ply\" },\n"
        "    { \"type\": \"serialized\", \"filename\": \"square.serialized\", \"shape_index\": 0,\n"
        "      \"to_world\": { \"translate\": [10, 0, 0] } }] }\n";
    snprintf(path, sizeof path, "%s/meshes.json", folder);
    write_file(path, scene_text, strlen(scene_text));
    ppm_context_set_warning_callback(f->context, NULL, NULL);
    ppm_scene_file file = NULL;
    assert_int_equal(ppm_scene_file_load(f->context, path, &file), PPM_OK);
    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_file_get_scene(file, &scene), PPM_OK);
    assert_close(hit_distance(scene, 1.5, 0.5), 4.0, 1e-12);
    assert_close(hit_distance(scene, 11.5, 0.5), 4.0, 1e-12); /* the serialized square, moved */
    ppm_scene_release(scene);
    ppm_scene_file_release(file);

    /* A shape_index beyond the file's meshes is located at the shape. */
    const char *bad_index = "{ \"shapes\": [{ \"type\": \"serialized\", \"filename\": \"square.serialized\",\n"
                            "  \"shape_index\": 2 }] }\n";
    write_file(path, bad_index, strlen(bad_index));
    assert_int_equal(ppm_scene_file_load(f->context, path, &file), PPM_ERROR_PARSE);
    assert_non_null(strstr(ppm_last_error_message(), "meshes.json:1:50: shapes[0].filename"));
    assert_non_null(strstr(ppm_last_error_message(), "shape_index 2 is out of range"));
}

/* Mitsuba's cube, [-1, 1]^3 placed by to_world, with outward face normals. */
static void the_cube_shape_is_mitsubas_cube(void **state) {
    scene_fixture *f = *state;
    const char *scene_text = "{ \"shapes\": [{ \"type\": \"cube\",\n"
                             "  \"to_world\": [{ \"scale\": 2 }, { \"translate\": [0, 0, 5] }] }] }\n";
    char path[4200];
    snprintf(path, sizeof path, "%s/cube.json", folder);
    write_file(path, scene_text, strlen(scene_text));
    ppm_scene_file file = NULL;
    assert_int_equal(ppm_scene_file_load(f->context, path, &file), PPM_OK);
    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_file_get_scene(file, &scene), PPM_OK);
    /* Down the z axis from z = 20: the top face at z = 7. */
    const struct {
        double org[3], dir[3], t, normal[3];
    } rays[] = {
        {{0.5, -0.3, 20}, {0, 0, -1}, 13, {0, 0, 1}}, {{0.5, -0.3, -20}, {0, 0, 1}, 23, {0, 0, -1}},
        {{-20, 1.5, 4}, {1, 0, 0}, 18, {-1, 0, 0}},   {{1, 20, 6}, {0, -1, 0}, 18, {0, 1, 0}},
        {{3, 0, 4}, {0, 1, 0}, INFINITY, {0, 0, 0}},
    };
    for (size_t i = 0; i < sizeof rays / sizeof rays[0]; ++i) {
        ppm_ray ray = {{rays[i].org[0], rays[i].org[1], rays[i].org[2]},
                       0,
                       {rays[i].dir[0], rays[i].dir[1], rays[i].dir[2]},
                       INFINITY};
        ppm_hit hit;
        assert_int_equal(ppm_scene_intersect(scene, &ray, 1, &hit), PPM_OK);
        if (isinf(rays[i].t)) {
            assert_int_equal(hit.geom_id, PPM_INVALID_ID);
            continue;
        }
        assert_close(hit.t, rays[i].t, 1e-12);
        for (int a = 0; a < 3; ++a) {
            assert_close(hit.ng[a], rays[i].normal[a], 1e-12);
            assert_close(hit.ns[a], rays[i].normal[a], 1e-12);
        }
    }
    ppm_scene_release(scene);
    ppm_scene_file_release(file);
}

static int setup(void **state) {
    if (test_make_folder(folder, sizeof folder, "ppm-mesh-files-") != 0) return -1;
    return scene_fixture_setup(state);
}

static int teardown(void **state) {
    test_remove_folder(folder);
    return scene_fixture_teardown(state);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(ply_file_loads_is_hit_and_warns_of_colours, setup, teardown),
        cmocka_unit_test_setup_teardown(ply_file_without_normals_shades_with_mitsubas_vertex_normals, setup, teardown),
        cmocka_unit_test_setup_teardown(damaged_or_missing_ply_files_are_refused_by_name, setup, teardown),
        cmocka_unit_test_setup_teardown(serialized_file_loads_and_a_wrong_index_is_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(scene_files_take_ply_and_serialized_shapes, setup, teardown),
        cmocka_unit_test_setup_teardown(the_cube_shape_is_mitsubas_cube, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
