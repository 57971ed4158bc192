/* SPDX-License-Identifier: Apache-2.0 */
/* Loading .bpt and OBJ files: malformed files written to a temporary directory at test time
 * must fail with IO or PARSE and a message naming the file (and line), leave the scene as it
 * was, and valid files must load. */
#define _XOPEN_SOURCE 700

#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { max_files = 8, max_text = 1 << 14 };

typedef struct fixture {
    ppm_context context;
    ppm_scene scene;
    char dir[256];
    char paths[max_files][512];
    int file_count;
    uint32_t spheres_added; /* by check_scene_unchanged, the only geometry failed tests add */
} fixture;

static int setup(void **state) {
    fixture *f = calloc(1, sizeof *f);
    if (!f) return -1;
    const char *tmp = getenv("TMPDIR");
    snprintf(f->dir, sizeof f->dir, "%s/ppm_bpt_obj_XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
    if (!mkdtemp(f->dir) || ppm_context_create(&f->context) != PPM_OK ||
        ppm_scene_create(f->context, &f->scene) != PPM_OK) {
        ppm_context_release(f->context);
        free(f);
        return -1;
    }
    *state = f;
    return 0;
}

static int teardown(void **state) {
    fixture *f = *state;
    ppm_scene_release(f->scene);
    ppm_context_release(f->context);
    for (int i = 0; i < f->file_count; ++i) remove(f->paths[i]);
    rmdir(f->dir);
    free(f);
    return 0;
}

/* Path of `name` inside the fixture's directory (the file need not exist). */
static const char *path_of(fixture *f, const char *name) {
    assert_true(f->file_count < max_files);
    char *path = f->paths[f->file_count++];
    snprintf(path, sizeof f->paths[0], "%s/%s", f->dir, name);
    return path;
}

static const char *write_file(fixture *f, const char *name, const char *text) {
    const char *path = path_of(f, name);
    FILE *file = fopen(path, "wb");
    assert_non_null(file);
    assert_int_equal(fwrite(text, 1, strlen(text), file), strlen(text));
    assert_int_equal(fclose(file), 0);
    return path;
}

/* Growing text of a file under construction. */
typedef struct text {
    char data[max_text];
    size_t length;
} text;

static void append(text *t, const char *format, ...) {
    va_list args;
    va_start(args, format);
    const int n = vsnprintf(t->data + t->length, sizeof t->data - t->length, format, args);
    va_end(args);
    assert_true(n >= 0 && (size_t)n < sizeof t->data - t->length);
    t->length += (size_t)n;
}

/* The flat patch S(u, v) = (u, v, 0): a "3 3" line and 16 point lines. Coordinate `axis` of
 * control point `bad_point` is replaced by `token` (bad_point < 0: none). Lines end in `eol`. */
static void append_patch_with(text *t, int bad_point, int axis, const char *token, const char *eol) {
    append(t, "3 3%s", eol);
    for (int k = 0; k < 16; ++k) {
        const double xyz[3] = {(k % 4) / 3.0, (k / 4) / 3.0, 0};
        for (int a = 0; a < 3; ++a) {
            if (a) append(t, " ");
            if (k == bad_point && a == axis)
                append(t, "%s", token);
            else
                append(t, "%.17g", xyz[a]);
        }
        append(t, "%s", eol);
    }
}

static void append_patch(text *t) { append_patch_with(t, -1, 0, "", "\n"); }

/* A one-patch file whose control point `point` has `token` as coordinate `axis`. Point k
 * stands on line 3 + k. */
static const char *bpt_with_token(fixture *f, const char *name, int point, int axis, const char *token) {
    text t = {{0}, 0};
    append(&t, "1\n");
    append_patch_with(&t, point, axis, token, "\n");
    return write_file(f, name, t.data);
}

/* A one-patch file whose first line (the count) is `count`. */
static const char *bpt_with_count(fixture *f, const char *name, const char *count) {
    text t = {{0}, 0};
    append(&t, "%s\n", count);
    append_patch(&t);
    return write_file(f, name, t.data);
}

/* The call failed with `status` and the message names "path:line:". */
static void check_parse_error(ppm_status status, const char *path, int line) {
    char where[600];
    snprintf(where, sizeof where, "%s:%d:", path, line);
    assert_int_equal(status, PPM_ERROR_PARSE);
    const char *message = ppm_last_error_message();
    if (!strstr(message, where)) fail_msg("message '%s' does not contain '%s'", message, where);
}

/* A failed load added nothing: the next geometry takes the next id (0 after the first
 * failure), and the scene still commits. */
static void check_scene_unchanged(fixture *f) {
    size_t count = 0;
    assert_ppm_error(ppm_scene_get_primitive_count(f->scene, f->spheres_added, &count), PPM_ERROR_INVALID_ARGUMENT,
                     "geom_id");
    uint32_t id = 99;
    const double center[3] = {0, 0, 0};
    assert_ppm_ok(ppm_scene_add_sphere(f->scene, center, 1, &id));
    assert_int_equal(id, f->spheres_added);
    ++f->spheres_added;
    assert_ppm_ok(ppm_scene_commit(f->scene));
}

static void check_bpt_parse_error(fixture *f, const char *path, int line) {
    uint32_t id = 99;
    check_parse_error(ppm_scene_load_bpt(f->scene, path, &id), path, line);
    assert_int_equal(id, 99);
    check_scene_unchanged(f);
}

static void check_obj_parse_error(fixture *f, const char *path, int line) {
    uint32_t id = 99;
    check_parse_error(ppm_scene_load_obj(f->scene, path, &id), path, line);
    assert_int_equal(id, 99);
    check_scene_unchanged(f);
}

/* Loads `path` (.bpt or OBJ) as geometry 0 and checks its primitive count. */
static void check_loads(fixture *f, const char *path, int is_obj, size_t expected_primitives) {
    uint32_t id = 99;
    assert_ppm_ok(is_obj ? ppm_scene_load_obj(f->scene, path, &id) : ppm_scene_load_bpt(f->scene, path, &id));
    assert_int_equal(id, 0);
    size_t count = 0;
    assert_ppm_ok(ppm_scene_get_primitive_count(f->scene, id, &count));
    assert_int_equal(count, expected_primitives);
}

/* Closest hit of the ray from (x, y, 1) straight down, after a commit. */
static ppm_hit hit_from_above(ppm_scene scene, double x, double y) {
    assert_ppm_ok(ppm_scene_commit(scene));
    ppm_ray ray = {{x, y, 1}, 0, {0, 0, -1}, INFINITY};
    ppm_hit hit;
    assert_ppm_ok(ppm_scene_intersect(scene, &ray, 1, &hit));
    return hit;
}

/* .bpt: files that cannot be read -------------------------------------------------------------- */

static void test_bpt_missing_file_is_io_error_naming_path(void **state) {
    fixture *f = *state;
    const char *path = path_of(f, "missing.bpt");
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_load_bpt(f->scene, path, &id), PPM_ERROR_IO, path);
    assert_int_equal(id, 99);
    check_scene_unchanged(f);
}

static void test_bpt_directory_is_io_error(void **state) {
    fixture *f = *state;
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_load_bpt(f->scene, f->dir, &id), PPM_ERROR_IO, f->dir);
    assert_int_equal(id, 99);
    check_scene_unchanged(f);
}

/* .bpt: structure ----------------------------------------------------------------------------- */

static void test_bpt_empty_file(void **state) {
    fixture *f = *state;
    check_bpt_parse_error(f, write_file(f, "empty.bpt", ""), 1);
}

static void test_bpt_only_comments(void **state) {
    fixture *f = *state;
    const char *path = write_file(f, "comments.bpt", "# no patches here\n# none at all\n");
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_load_bpt(f->scene, path, &id), PPM_ERROR_PARSE, path);
    check_scene_unchanged(f);
}

static void test_bpt_fewer_patches_than_announced(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "2\n");
    append_patch(&t);
    /* the file ends after its last point, line 18: that is where the next patch is missing */
    check_bpt_parse_error(f, write_file(f, "short.bpt", t.data), 18);
}

static void test_bpt_cut_in_middle_of_point(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "1\n");
    append_patch(&t);
    t.length -= strlen(" 0\n"); /* drop the last z: point 15 is on line 18 */
    t.data[t.length] = '\0';
    check_bpt_parse_error(f, write_file(f, "cut.bpt", t.data), 18);
}

static void test_bpt_cut_in_middle_of_point_with_newline(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "1\n3 3\n");
    for (int k = 0; k < 10; ++k) append(&t, "0 0 0\n");
    append(&t, "0.5 0.25\n"); /* point 10 lacks z, line 13 */
    check_bpt_parse_error(f, write_file(f, "cut_newline.bpt", t.data), 13);
}

static void test_bpt_cut_after_degree_line(void **state) {
    fixture *f = *state;
    check_bpt_parse_error(f, write_file(f, "degree_only.bpt", "1\n3 3"), 2);
}

static void test_bpt_wrong_degree_line(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "1\n2 3\n");
    for (int k = 0; k < 16; ++k) append(&t, "0 0 0\n");
    const char *path = write_file(f, "degree.bpt", t.data);
    check_bpt_parse_error(f, path, 2);
    uint32_t id;
    assert_ppm_error(ppm_scene_load_bpt(f->scene, path, &id), PPM_ERROR_PARSE, "2 3");
}

static void test_bpt_wrong_degree_in_second_patch(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "2\n");
    append_patch(&t);
    append(&t, "3 2\n"); /* line 19 */
    for (int k = 0; k < 16; ++k) append(&t, "0 0 0\n");
    check_bpt_parse_error(f, write_file(f, "degree2.bpt", t.data), 19);
}

static void test_bpt_non_integer_degree(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "1\n3 x\n");
    for (int k = 0; k < 16; ++k) append(&t, "0 0 0\n");
    check_bpt_parse_error(f, write_file(f, "degree_x.bpt", t.data), 2);
}

/* .bpt: the patch count ------------------------------------------------------------------------ */

static void test_bpt_negative_count(void **state) {
    fixture *f = *state;
    check_bpt_parse_error(f, bpt_with_count(f, "negative.bpt", "-1"), 1);
}

static void test_bpt_zero_count(void **state) {
    fixture *f = *state;
    check_bpt_parse_error(f, bpt_with_count(f, "zero.bpt", "0"), 1);
}

static void test_bpt_huge_count(void **state) {
    fixture *f = *state;
    const char *path = bpt_with_count(f, "huge.bpt", "99999999999");
    check_bpt_parse_error(f, path, 1);
    uint32_t id;
    assert_ppm_error(ppm_scene_load_bpt(f->scene, path, &id), PPM_ERROR_PARSE, "10000000");
}

static void test_bpt_count_just_over_limit(void **state) {
    fixture *f = *state;
    check_bpt_parse_error(f, bpt_with_count(f, "over.bpt", "10000001"), 1);
}

static void test_bpt_count_at_limit_is_checked_against_content(void **state) {
    fixture *f = *state;
    /* allowed by the limit, but the file holds one patch: must not allocate 10 million first */
    check_bpt_parse_error(f, bpt_with_count(f, "limit.bpt", "10000000"), 18);
}

static void test_bpt_count_overflowing_integer(void **state) {
    fixture *f = *state;
    check_bpt_parse_error(f, bpt_with_count(f, "overflow.bpt", "99999999999999999999999"), 1);
}

static void test_bpt_count_not_an_integer(void **state) {
    fixture *f = *state;
    check_bpt_parse_error(f, bpt_with_count(f, "fraction.bpt", "1.5"), 1);
    check_bpt_parse_error(f, bpt_with_count(f, "word.bpt", "one"), 1);
}

/* .bpt: coordinates --------------------------------------------------------------------------- */

static void test_bpt_nan_coordinate(void **state) {
    fixture *f = *state;
    check_bpt_parse_error(f, bpt_with_token(f, "nan.bpt", 4, 1, "nan"), 7);
    check_bpt_parse_error(f, bpt_with_token(f, "NaN.bpt", 0, 0, "NaN"), 3);
}

static void test_bpt_infinite_coordinate(void **state) {
    fixture *f = *state;
    check_bpt_parse_error(f, bpt_with_token(f, "inf.bpt", 15, 2, "inf"), 18);
    check_bpt_parse_error(f, bpt_with_token(f, "minus_inf.bpt", 9, 0, "-Infinity"), 12);
}

static void test_bpt_overflowing_coordinate(void **state) {
    fixture *f = *state;
    check_bpt_parse_error(f, bpt_with_token(f, "1e999.bpt", 2, 2, "1e999"), 5);
    check_bpt_parse_error(f, bpt_with_token(f, "minus_1e999.bpt", 3, 1, "-1e999"), 6);
}

static void test_bpt_non_number_token(void **state) {
    fixture *f = *state;
    const char *path = bpt_with_token(f, "word.bpt", 6, 0, "abc");
    check_bpt_parse_error(f, path, 9);
    uint32_t id;
    assert_ppm_error(ppm_scene_load_bpt(f->scene, path, &id), PPM_ERROR_PARSE, "abc");
    check_bpt_parse_error(f, bpt_with_token(f, "suffix.bpt", 7, 1, "1.0x"), 10);
    check_bpt_parse_error(f, bpt_with_token(f, "comma.bpt", 8, 2, "1,5"), 11);
}

/* .bpt: what follows the patches -------------------------------------------------------------- */

static void test_bpt_trailing_garbage(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "1\n");
    append_patch(&t);
    append(&t, "\njunk\n"); /* line 19 is empty, junk on line 20 */
    check_bpt_parse_error(f, write_file(f, "garbage.bpt", t.data), 20);
}

static void test_bpt_extra_number_on_last_line(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "1\n");
    append_patch(&t);
    t.data[--t.length] = '\0';
    append(&t, " 7\n"); /* a fourth number on line 18 */
    check_bpt_parse_error(f, write_file(f, "extra.bpt", t.data), 18);
}

static void test_bpt_more_patches_than_announced(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "1\n");
    append_patch(&t);
    append_patch(&t); /* its degree line is line 19 */
    check_bpt_parse_error(f, write_file(f, "long.bpt", t.data), 19);
}

/* .bpt: valid files --------------------------------------------------------------------------- */

static void test_bpt_one_planar_patch_loads(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "1\n");
    append_patch(&t);
    check_loads(f, write_file(f, "plane.bpt", t.data), 0, 1);
    const ppm_hit hit = hit_from_above(f->scene, 0.25, 0.75);
    assert_int_equal(hit.geom_id, 0);
    assert_int_equal(hit.prim_id, 0);
    assert_close(hit.t, 1.0, 1e-8);
    assert_close(hit.u, 0.25, 1e-8);
    assert_close(hit.v, 0.75, 1e-8);
}

static void test_bpt_two_patches_load(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "2\n");
    append_patch(&t);
    append_patch(&t);
    check_loads(f, write_file(f, "two.bpt", t.data), 0, 2);
}

static void test_bpt_comments_are_ignored(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "# a flat patch\n1 # patch count\n\n# degree next\n3 3 # bicubic\n");
    for (int k = 0; k < 16; ++k) append(&t, "%.17g %.17g 0# point %d\n", (k % 4) / 3.0, (k / 4) / 3.0, k);
    append(&t, "# the end\n");
    check_loads(f, write_file(f, "commented.bpt", t.data), 0, 1);
    assert_int_equal(hit_from_above(f->scene, 0.5, 0.5).geom_id, 0);
}

static void test_bpt_error_line_counts_comment_lines(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "# one\n# two\n1\n3 3\n");
    for (int k = 0; k < 16; ++k) append(&t, k == 3 ? "0 nan 0 # bad\n" : "0 0 0 # ok\n");
    check_bpt_parse_error(f, write_file(f, "commented_bad.bpt", t.data), 8);
}

static void test_bpt_crlf_line_ends_are_accepted(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "1\r\n");
    append_patch_with(&t, -1, 0, "", "\r\n");
    check_loads(f, write_file(f, "crlf.bpt", t.data), 0, 1);
}

static void test_bpt_crlf_error_line(void **state) {
    fixture *f = *state;
    text t = {{0}, 0};
    append(&t, "1\r\n");
    append_patch_with(&t, 5, 0, "oops", "\r\n");
    check_bpt_parse_error(f, write_file(f, "crlf_bad.bpt", t.data), 8);
}

static void test_bpt_load_after_failed_load_gets_id_zero(void **state) {
    fixture *f = *state;
    const char *bad = bpt_with_token(f, "bad.bpt", 1, 1, "nan");
    uint32_t id = 99;
    assert_int_equal(ppm_scene_load_bpt(f->scene, bad, &id), PPM_ERROR_PARSE);
    text t = {{0}, 0};
    append(&t, "1\n");
    append_patch(&t);
    check_loads(f, write_file(f, "good.bpt", t.data), 0, 1);
}

static void test_bpt_teapot_loads(void **state) {
    fixture *f = *state;
    check_loads(f, PPM_TEAPOT, 0, 32);
    assert_ppm_ok(ppm_scene_commit(f->scene));
}

/* OBJ ----------------------------------------------------------------------------------------- */

static const char triangle_obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

static const char *obj_file(fixture *f, const char *name, const char *faces) {
    text t = {{0}, 0};
    append(&t, "%s%s", triangle_obj, faces);
    return write_file(f, name, t.data);
}

static void test_obj_missing_file_is_io_error_naming_path(void **state) {
    fixture *f = *state;
    const char *path = path_of(f, "missing.obj");
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_load_obj(f->scene, path, &id), PPM_ERROR_IO, path);
    assert_int_equal(id, 99);
    check_scene_unchanged(f);
}

static void test_obj_directory_is_io_error(void **state) {
    fixture *f = *state;
    uint32_t id = 99;
    assert_ppm_error(ppm_scene_load_obj(f->scene, f->dir, &id), PPM_ERROR_IO, f->dir);
    check_scene_unchanged(f);
}

static void test_obj_empty_file(void **state) {
    fixture *f = *state;
    const char *path = write_file(f, "empty.obj", "");
    assert_ppm_error(ppm_scene_load_obj(f->scene, path, NULL), PPM_ERROR_PARSE, path);
    check_scene_unchanged(f);
}

static void test_obj_without_faces(void **state) {
    fixture *f = *state;
    const char *path = obj_file(f, "no_faces.obj", "# vertices only\n");
    assert_ppm_error(ppm_scene_load_obj(f->scene, path, NULL), PPM_ERROR_PARSE, path);
    assert_ppm_error(ppm_scene_load_obj(f->scene, path, NULL), PPM_ERROR_PARSE, "no faces");
    check_scene_unchanged(f);
}

static void test_obj_nan_vertex(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, write_file(f, "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n"), 3);
}

static void test_obj_infinite_vertex(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, write_file(f, "inf.obj", "v 0 0 0\nv 1 1e999 0\nv 0 1 0\nf 1 2 3\n"), 2);
    check_obj_parse_error(f, write_file(f, "minus_inf.obj", "v 0 0 -inf\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), 1);
}

static void test_obj_non_number_vertex(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, write_file(f, "word.obj", "v 0 0 0\nv 1 abc 0\nv 0 1 0\nf 1 2 3\n"), 2);
}

static void test_obj_vertex_with_two_numbers(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, write_file(f, "short.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), 1);
}

static void test_obj_nan_normal_and_texcoord(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, obj_file(f, "nan_normal.obj", "vn 0 0 nan\nf 1//1 2//1 3//1\n"), 4);
    check_obj_parse_error(f, obj_file(f, "nan_uv.obj", "vt 0 0\nvt nan 0\nf 1/1 2/2 3/1\n"), 5);
}

static void test_obj_face_index_out_of_range_positive(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, obj_file(f, "positive.obj", "f 1 2 3\nf 1 2 4\n"), 5);
}

static void test_obj_face_index_out_of_range_negative(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, obj_file(f, "negative.obj", "f -1 -2 -4\n"), 4);
}

static void test_obj_face_index_zero(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, obj_file(f, "zero.obj", "f 0 1 2\n"), 4);
}

static void test_obj_face_before_its_vertices(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, write_file(f, "forward.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n"), 3);
}

static void test_obj_face_with_two_corners(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, obj_file(f, "two_corners.obj", "f 1 2\n"), 4);
}

static void test_obj_normal_index_out_of_range(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, obj_file(f, "normal_index.obj", "vn 0 0 1\nf 1//1 2//1 3//2\n"), 5);
}

static void test_obj_texcoord_index_out_of_range(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, obj_file(f, "uv_index.obj", "vt 0 0\nf 1/1 2/1 3/3\n"), 5);
}

static void test_obj_non_integer_face_index(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, obj_file(f, "word_index.obj", "f 1 2 x\n"), 4);
}

static void test_obj_valid_triangle(void **state) {
    fixture *f = *state;
    check_loads(f, obj_file(f, "triangle.obj", "f 1 2 3\n"), 1, 1);
    const ppm_hit hit = hit_from_above(f->scene, 0.2, 0.3);
    assert_int_equal(hit.geom_id, 0);
    assert_int_equal(hit.prim_id, 0);
    assert_close(hit.t, 1.0, 1e-12);
    assert_close(hit.u, 0.2, 1e-12);
    assert_close(hit.v, 0.3, 1e-12);
}

static void test_obj_negative_indices(void **state) {
    fixture *f = *state;
    check_loads(f, obj_file(f, "relative.obj", "f -3 -2 -1\n"), 1, 1);
    assert_int_equal(hit_from_above(f->scene, 0.2, 0.3).geom_id, 0);
}

static void test_obj_quad_face_is_two_triangles(void **state) {
    fixture *f = *state;
    check_loads(f, write_file(f, "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"), 1, 2);
    /* near opposite corners: in different triangles whichever diagonal splits the quad */
    const ppm_hit a = hit_from_above(f->scene, 0.1, 0.05), b = hit_from_above(f->scene, 0.9, 0.95);
    assert_int_equal(a.geom_id, 0);
    assert_int_equal(b.geom_id, 0);
    assert_int_not_equal(a.prim_id, b.prim_id);
    assert_true(a.prim_id < 2 && b.prim_id < 2);
}

static void test_obj_pentagon_is_three_triangles(void **state) {
    fixture *f = *state;
    check_loads(f, write_file(f, "pentagon.obj", "v 0 0 0\nv 1 0 0\nv 1.5 1 0\nv 0.5 2 0\nv -0.5 1 0\nf 1 2 3 4 5\n"),
                1, 3);
}

static void test_obj_objects_become_one_mesh(void **state) {
    fixture *f = *state;
    check_loads(f,
                write_file(f, "objects.obj",
                           "o first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
                           "o second\nv 0 0 -1\nv 1 0 -1\nv 0 1 -1\nf 4 5 6\n"),
                1, 2);
}

static void test_obj_comments_and_groups(void **state) {
    fixture *f = *state;
    check_loads(f, obj_file(f, "comments.obj", "# a comment\n\ng group\ns off\nf 1 2 3\n"), 1, 1);
}

static void test_obj_trailing_comments(void **state) {
    fixture *f = *state;
    check_loads(f,
                write_file(f, "trailing.obj",
                           "v 0 0 0 # origin\nv 1 0 0\nv 0 1 0\nvn 0 0 1 # up\nf 1//1 2//1 3//1 # the face\n"),
                1, 1);
    assert_close(hit_from_above(f->scene, 0.2, 0.2).ns[2], 1.0, 1e-15);
}

static void test_obj_error_line_after_trailing_comments(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, obj_file(f, "trailing_bad.obj", "f 1 2 3 # fine\nf 1 2 # two corners\n"), 5);
}

static void test_obj_normals_are_interpolated(void **state) {
    fixture *f = *state;
    check_loads(f, obj_file(f, "normals.obj", "vn 0 0 1\nvn 0.6 0 0.8\nvn 0 0.6 0.8\nf 1//1 2//2 3//3\n"), 1, 1);
    const ppm_hit hit = hit_from_above(f->scene, 0.25, 0.25);
    /* w = 0.5, u = v = 0.25: 0.5 n0 + 0.25 n1 + 0.25 n2 = (0.15, 0.15, 0.9) */
    const double length = sqrt(0.15 * 0.15 * 2 + 0.9 * 0.9);
    assert_close(hit.ns[0], 0.15 / length, 1e-12);
    assert_close(hit.ns[1], 0.15 / length, 1e-12);
    assert_close(hit.ns[2], 0.9 / length, 1e-12);
    assert_close(hit.ng[2], 1.0, 1e-15);
}

static void test_obj_normals_dropped_when_a_face_lacks_them(void **state) {
    fixture *f = *state;
    check_loads(f,
                write_file(f, "some_normals.obj",
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0.6 0 0.8\nf 1//1 2//1 3//1\nf 2 4 3\n"),
                1, 2);
    const ppm_hit hit = hit_from_above(f->scene, 0.25, 0.25);
    for (int k = 0; k < 3; ++k) assert_true(hit.ns[k] == hit.ng[k]);
}

static void test_obj_texcoords_and_normals_load(void **state) {
    fixture *f = *state;
    /* uv are kept inside the mesh; the public API reports only barycentrics, so check that
     * position/uv/normal corners load and keep the normals */
    check_loads(f, obj_file(f, "full.obj", "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 -1\nf 1/1/1 2/2/1 3/3/1\n"), 1, 1);
    const ppm_hit hit = hit_from_above(f->scene, 0.2, 0.2);
    assert_close(hit.ns[2], -1.0, 1e-15);
    assert_close(hit.ng[2], 1.0, 1e-15);
}

static void test_obj_load_after_failed_load_gets_id_zero(void **state) {
    fixture *f = *state;
    uint32_t id = 99;
    assert_int_equal(ppm_scene_load_obj(f->scene, obj_file(f, "bad.obj", "f 1 2 9\n"), &id), PPM_ERROR_PARSE);
    check_loads(f, obj_file(f, "good.obj", "f 1 2 3\n"), 1, 1);
}

/* A control character other than a tab inside a line is refused where it stands, so that no
 * part of the reader can take "v\r" for a vertex while another takes it for an unknown word
 * (face indices would then run past the vertex arrays). */
static void test_obj_carriage_return_inside_vertex_line(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, write_file(f, "cr_v.obj", "v 0 0 0\nv 1 0 0\nv\r 1 1 0\nf 1 2 3\n"), 3);
    check_obj_parse_error(f, write_file(f, "cr_v_first.obj", "v\r 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\n"), 1);
}

static void test_obj_control_character_in_normal_and_texcoord_lines(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, obj_file(f, "cr_vn.obj", "vn\r 0 0 1\nf 1//1 2//1 3//1\n"), 4);
    check_obj_parse_error(f, obj_file(f, "ff_vt.obj", "vt\f 0 0\nf 1/1 2/1 3/1\n"), 4);
    check_obj_parse_error(f, obj_file(f, "vt_in_number.obj", "vt 0\v5 0\nf 1/1 2/1 3/1\n"), 4);
}

static void test_obj_crlf_line_ends_are_accepted(void **state) {
    fixture *f = *state;
    check_loads(f, write_file(f, "crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n"), 1, 1);
}

static void test_obj_crlf_error_line(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, write_file(f, "crlf_bad.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 4\r\n"), 4);
}

static void test_obj_face_with_only_repeated_corners_is_refused(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, obj_file(f, "repeated.obj", "f 1 2 3\nf 1 1 2\n"), 5);
    check_obj_parse_error(f, obj_file(f, "repeated_quad.obj", "f 1 2 1 2\n"), 4);
}

static void test_obj_polygon_keeps_its_triangles_with_area(void **state) {
    fixture *f = *state;
    /* the fan (1 2 2) (1 2 3) has one triangle with area */
    check_loads(f, obj_file(f, "one_repeat.obj", "f 1 2 2 3\n"), 1, 1);
}

static void test_obj_vertex_colours_and_short_texcoords_load(void **state) {
    fixture *f = *state;
    check_loads(f, write_file(f, "colours.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nvt 0.5\nf 1/1 2/1 3/1\n"),
                1, 1);
}

static void test_obj_corner_with_four_parts_is_refused(void **state) {
    fixture *f = *state;
    check_obj_parse_error(f, obj_file(f, "four_parts.obj", "f 1/1/1/1 2 3\n"), 4);
}

#define TEST(name) cmocka_unit_test_setup_teardown(name, setup, teardown)

int main(void) {
    const struct CMUnitTest tests[] = {
        TEST(test_bpt_missing_file_is_io_error_naming_path),
        TEST(test_bpt_directory_is_io_error),
        TEST(test_bpt_empty_file),
        TEST(test_bpt_only_comments),
        TEST(test_bpt_fewer_patches_than_announced),
        TEST(test_bpt_cut_in_middle_of_point),
        TEST(test_bpt_cut_in_middle_of_point_with_newline),
        TEST(test_bpt_cut_after_degree_line),
        TEST(test_bpt_wrong_degree_line),
        TEST(test_bpt_wrong_degree_in_second_patch),
        TEST(test_bpt_non_integer_degree),
        TEST(test_bpt_negative_count),
        TEST(test_bpt_zero_count),
        TEST(test_bpt_huge_count),
        TEST(test_bpt_count_just_over_limit),
        TEST(test_bpt_count_at_limit_is_checked_against_content),
        TEST(test_bpt_count_overflowing_integer),
        TEST(test_bpt_count_not_an_integer),
        TEST(test_bpt_nan_coordinate),
        TEST(test_bpt_infinite_coordinate),
        TEST(test_bpt_overflowing_coordinate),
        TEST(test_bpt_non_number_token),
        TEST(test_bpt_trailing_garbage),
        TEST(test_bpt_extra_number_on_last_line),
        TEST(test_bpt_more_patches_than_announced),
        TEST(test_bpt_one_planar_patch_loads),
        TEST(test_bpt_two_patches_load),
        TEST(test_bpt_comments_are_ignored),
        TEST(test_bpt_error_line_counts_comment_lines),
        TEST(test_bpt_crlf_line_ends_are_accepted),
        TEST(test_bpt_crlf_error_line),
        TEST(test_bpt_load_after_failed_load_gets_id_zero),
        TEST(test_bpt_teapot_loads),
        TEST(test_obj_missing_file_is_io_error_naming_path),
        TEST(test_obj_directory_is_io_error),
        TEST(test_obj_empty_file),
        TEST(test_obj_without_faces),
        TEST(test_obj_nan_vertex),
        TEST(test_obj_infinite_vertex),
        TEST(test_obj_non_number_vertex),
        TEST(test_obj_vertex_with_two_numbers),
        TEST(test_obj_nan_normal_and_texcoord),
        TEST(test_obj_face_index_out_of_range_positive),
        TEST(test_obj_face_index_out_of_range_negative),
        TEST(test_obj_face_index_zero),
        TEST(test_obj_face_before_its_vertices),
        TEST(test_obj_face_with_two_corners),
        TEST(test_obj_normal_index_out_of_range),
        TEST(test_obj_texcoord_index_out_of_range),
        TEST(test_obj_non_integer_face_index),
        TEST(test_obj_valid_triangle),
        TEST(test_obj_negative_indices),
        TEST(test_obj_quad_face_is_two_triangles),
        TEST(test_obj_pentagon_is_three_triangles),
        TEST(test_obj_objects_become_one_mesh),
        TEST(test_obj_comments_and_groups),
        TEST(test_obj_trailing_comments),
        TEST(test_obj_error_line_after_trailing_comments),
        TEST(test_obj_normals_are_interpolated),
        TEST(test_obj_normals_dropped_when_a_face_lacks_them),
        TEST(test_obj_texcoords_and_normals_load),
        TEST(test_obj_load_after_failed_load_gets_id_zero),
        TEST(test_obj_carriage_return_inside_vertex_line),
        TEST(test_obj_control_character_in_normal_and_texcoord_lines),
        TEST(test_obj_crlf_line_ends_are_accepted),
        TEST(test_obj_crlf_error_line),
        TEST(test_obj_face_with_only_repeated_corners_is_refused),
        TEST(test_obj_polygon_keeps_its_triangles_with_area),
        TEST(test_obj_vertex_colours_and_short_texcoords_load),
        TEST(test_obj_corner_with_four_parts_is_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
