/* SPDX-License-Identifier: Apache-2.0 */
/* Partial renders ("pppm" mode): passes rendered apart, in any order and with any thread
 * count, merge into the same bits as one renderer rendering them all; every kind of wrong
 * partial (corrupt, truncated, foreign, overlapping) is refused with a message saying why. */
#include <ppm/ppm.h>

#include "test_support.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *const small_box = PPM_TEST_DATA_DIR "/scenes/small_box.json";
enum { width = 64, height = 48, pixels = width * height, photons = 4000 };

typedef struct fixture {
    ppm_context one_thread, two_threads;
    ppm_scene_file file_1, file_2; /* the same scene on either context */
    char folder[256];
} fixture;

static int setup(void **state) {
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    assert_int_equal(ppm_context_create(&f->one_thread), PPM_OK);
    assert_int_equal(ppm_context_set_int(f->one_thread, "threads", 1), PPM_OK);
    assert_int_equal(ppm_context_create(&f->two_threads), PPM_OK);
    assert_int_equal(ppm_context_set_int(f->two_threads, "threads", 2), PPM_OK);
    assert_int_equal(ppm_scene_file_load(f->one_thread, small_box, &f->file_1), PPM_OK);
    assert_int_equal(ppm_scene_file_load(f->two_threads, small_box, &f->file_2), PPM_OK);
    assert_int_equal(test_make_folder(f->folder, sizeof f->folder, "ppm-partial-test-"), 0);
    *state = f;
    return 0;
}

static int teardown(void **state) {
    fixture *f = *state;
    test_remove_folder(f->folder);
    ppm_scene_file_release(f->file_1);
    ppm_scene_file_release(f->file_2);
    ppm_context_release(f->one_thread);
    ppm_context_release(f->two_threads);
    free(f);
    return 0;
}

static ppm_renderer new_renderer(ppm_scene_file file) {
    ppm_renderer r = NULL;
    assert_int_equal(ppm_scene_file_create_renderer(file, &r), PPM_OK);
    assert_int_equal(ppm_renderer_set_string(r, "mode", "pppm"), PPM_OK);
    assert_int_equal(ppm_renderer_set_int(r, "photons_per_pass", photons), PPM_OK);
    return r;
}

static void path_in(const fixture *f, const char *name, char out[320]) { snprintf(out, 320, "%s/%s", f->folder, name); }

static float *layer_of_renderer(ppm_renderer r, const char *layer, size_t count) {
    float *out = malloc(count * sizeof *out);
    assert_non_null(out);
    assert_int_equal(ppm_renderer_get_layer(r, layer, out, count), PPM_OK);
    return out;
}

static float *layer_of_partial(ppm_partial p, const char *layer, size_t count) {
    float *out = malloc(count * sizeof *out);
    assert_non_null(out);
    assert_int_equal(ppm_partial_get_layer(p, layer, out, count), PPM_OK);
    return out;
}

static void assert_same_floats(float *a, float *b, size_t count) {
    double sum = 0;
    for (size_t i = 0; i < count; ++i) sum += a[i];
    assert_true(sum > 0); /* a real image, not two black ones */
    assert_memory_equal(a, b, count * sizeof *a);
    free(a);
    free(b);
}

static int64_t partial_int(ppm_partial p, const char *key) {
    int64_t value = -1;
    assert_int_equal(ppm_partial_get_int(p, key, &value), PPM_OK);
    return value;
}

/* Renders the given pass indices into a new renderer on `file` and saves its partial. */
static void render_part(ppm_scene_file file, const uint64_t *indices, int count, const char *path) {
    ppm_renderer r = new_renderer(file);
    for (int i = 0; i < count; ++i) assert_int_equal(ppm_render_pass_index(r, indices[i]), PPM_OK);
    assert_int_equal(ppm_renderer_save_partial(r, path), PPM_OK);
    ppm_renderer_release(r);
}

static void test_merged_parts_equal_one_render(void **state) {
    fixture *f = *state;
    ppm_renderer whole = new_renderer(f->file_2);
    for (int i = 0; i < 6; ++i) assert_int_equal(ppm_render_pass(whole), PPM_OK);

    /* Three parts, each on its own thread count and in its own order. */
    char a[320], b[320], c[320];
    path_in(f, "a.ppmpart", a), path_in(f, "b.ppmpart", b), path_in(f, "c.ppmpart", c);
    const uint64_t part_a[] = {5, 0}, part_b[] = {4, 2, 3}, part_c[] = {1};
    render_part(f->file_1, part_a, 2, a);
    render_part(f->file_2, part_b, 3, b);
    render_part(f->file_1, part_c, 1, c);

    /* Merged in two orders. */
    ppm_partial pa = NULL, pb = NULL, pc = NULL, other_order = NULL;
    assert_int_equal(ppm_partial_load(a, &pa), PPM_OK);
    assert_int_equal(ppm_partial_load(b, &pb), PPM_OK);
    assert_int_equal(ppm_partial_load(c, &pc), PPM_OK);
    assert_int_equal(ppm_partial_load(c, &other_order), PPM_OK);
    assert_int_equal(partial_int(pa, "passes"), 2);
    assert_int_equal(partial_int(pa, "pass_ranges"), 2);
    assert_int_equal(ppm_partial_merge(pa, pb), PPM_OK);
    assert_int_equal(ppm_partial_merge(pa, pc), PPM_OK);
    assert_int_equal(ppm_partial_merge(other_order, pb), PPM_OK);
    ppm_partial pa_again = NULL;
    assert_int_equal(ppm_partial_load(a, &pa_again), PPM_OK);
    assert_int_equal(ppm_partial_merge(other_order, pa_again), PPM_OK);
    assert_int_equal(partial_int(pa, "passes"), 6);
    assert_int_equal(partial_int(pa, "pass_ranges"), 1);
    assert_int_equal(partial_int(pa, "photons_emitted"), 6 * photons);
    uint64_t ranges[4] = {0};
    size_t range_count = 0;
    assert_int_equal(ppm_partial_get_passes(pa, ranges, 4, &range_count), PPM_OK);
    assert_int_equal(range_count, 1);
    assert_int_equal(ranges[0], 0);
    assert_int_equal(ranges[1], 6);

    const char *layers[] = {"radiance", "radius", "photons"};
    const size_t counts[] = {3 * pixels, pixels, pixels};
    for (int l = 0; l < 3; ++l) {
        assert_same_floats(layer_of_renderer(whole, layers[l], counts[l]), layer_of_partial(pa, layers[l], counts[l]),
                           counts[l]);
        assert_same_floats(layer_of_partial(other_order, layers[l], counts[l]),
                           layer_of_partial(pa, layers[l], counts[l]), counts[l]);
    }
    /* The merged files are the same bytes too, however they were put together. */
    const void *x = NULL, *y = NULL, *w = NULL;
    size_t x_size = 0, y_size = 0, w_size = 0;
    ppm_partial from_whole = NULL;
    assert_int_equal(ppm_renderer_get_partial(whole, &from_whole), PPM_OK);
    assert_int_equal(ppm_partial_serialize(pa, &x, &x_size), PPM_OK);
    assert_int_equal(ppm_partial_serialize(other_order, &y, &y_size), PPM_OK);
    assert_int_equal(ppm_partial_serialize(from_whole, &w, &w_size), PPM_OK);
    assert_int_equal(x_size, y_size);
    assert_int_equal(x_size, w_size);
    assert_memory_equal(x, y, x_size);
    assert_memory_equal(x, w, x_size);

    /* A partial read back from memory is the same partial. */
    ppm_partial copy = NULL;
    assert_int_equal(ppm_partial_load_memory(x, x_size, &copy), PPM_OK);
    assert_same_floats(layer_of_partial(copy, "radiance", 3 * pixels), layer_of_partial(pa, "radiance", 3 * pixels),
                       3 * pixels);

    /* A renderer takes partials and goes on with the passes that are missing. */
    ppm_renderer resumed = new_renderer(f->file_1);
    assert_int_equal(ppm_renderer_merge_partial(resumed, pb), PPM_OK);
    assert_int_equal(ppm_renderer_merge_partial(resumed, pa_again), PPM_OK);
    int64_t passes = 0;
    assert_int_equal(ppm_renderer_get_int(resumed, "passes", &passes), PPM_OK);
    assert_int_equal(passes, 5);
    assert_int_equal(ppm_render_pass(resumed), PPM_OK); /* the lowest missing: pass 1 */
    assert_int_equal(ppm_render_pass(whole), PPM_OK);   /* pass 6 */
    assert_int_equal(ppm_render_pass(resumed), PPM_OK); /* pass 6 */
    assert_same_floats(layer_of_renderer(whole, "radiance", 3 * pixels),
                       layer_of_renderer(resumed, "radiance", 3 * pixels), 3 * pixels);

    ppm_renderer_release(resumed);
    ppm_partial_release(copy);
    ppm_partial_release(from_whole);
    ppm_partial_release(pa);
    ppm_partial_release(pb);
    ppm_partial_release(pc);
    ppm_partial_release(pa_again);
    ppm_partial_release(other_order);
    ppm_renderer_release(whole);
}

/* A checkpoint of a pppm render is a partial: resuming gives the uninterrupted image. */
static void test_checkpoint_resumes_pppm(void **state) {
    fixture *f = *state;
    char path[320];
    path_in(f, "render.ppmckpt", path);
    ppm_renderer whole = new_renderer(f->file_2);
    for (int i = 0; i < 4; ++i) assert_int_equal(ppm_render_pass(whole), PPM_OK);
    ppm_renderer first = new_renderer(f->file_1);
    for (int i = 0; i < 2; ++i) assert_int_equal(ppm_render_pass(first), PPM_OK);
    assert_int_equal(ppm_renderer_save_checkpoint(first, path), PPM_OK);
    ppm_renderer_release(first);
    ppm_renderer resumed = new_renderer(f->file_2);
    assert_int_equal(ppm_renderer_load_checkpoint(resumed, path), PPM_OK);
    for (int i = 0; i < 2; ++i) assert_int_equal(ppm_render_pass(resumed), PPM_OK);
    assert_same_floats(layer_of_renderer(whole, "radiance", 3 * pixels),
                       layer_of_renderer(resumed, "radiance", 3 * pixels), 3 * pixels);
    ppm_renderer_release(resumed);
    ppm_renderer_release(whole);
}

static void expect_load_error(const char *path, ppm_status status, const char *fragment) {
    ppm_partial p = NULL;
    const ppm_status got = ppm_partial_load(path, &p);
    if (got != status || !strstr(ppm_last_error_message(), fragment))
        fail_msg("status %d (expected %d), message '%s' (expected '%s')", got, status, ppm_last_error_message(),
                 fragment);
    assert_null(p);
}

static void copy_file(const char *from, const char *to) {
    char command[800];
    snprintf(command, sizeof command, "cp '%s' '%s'", from, to);
    assert_int_equal(system(command), 0);
}

static void flip_byte(const char *path, long offset) {
    FILE *file = fopen(path, "r+b");
    assert_non_null(file);
    fseek(file, offset, SEEK_SET);
    const int byte = fgetc(file);
    fseek(file, offset, SEEK_SET);
    fputc((byte + 1) & 0xFF, file);
    fclose(file);
}

static long file_size(const char *path) {
    FILE *file = fopen(path, "rb");
    assert_non_null(file);
    fseek(file, 0, SEEK_END);
    const long size = ftell(file);
    fclose(file);
    return size;
}

static void expect_merge_error(ppm_partial into, ppm_partial from, const char *fragment_1, const char *fragment_2) {
    const int64_t passes = partial_int(into, "passes");
    assert_int_equal(ppm_partial_merge(into, from), PPM_ERROR_INVALID_ARGUMENT);
    const char *message = ppm_last_error_message();
    if (!strstr(message, fragment_1) || !strstr(message, fragment_2))
        fail_msg("message '%s' (expected '%s' and '%s')", message, fragment_1, fragment_2);
    assert_int_equal(partial_int(into, "passes"), passes); /* unchanged */
}

static void test_bad_partials_are_refused(void **state) {
    fixture *f = *state;
    char good[320], bad[320], seeded[320], overlapping[320];
    path_in(f, "good.ppmpart", good), path_in(f, "bad.ppmpart", bad);
    path_in(f, "seeded.ppmpart", seeded), path_in(f, "overlapping.ppmpart", overlapping);
    const uint64_t passes_0_2[] = {0, 1, 2}, passes_2_3[] = {2, 3};
    render_part(f->file_1, passes_0_2, 3, good);
    render_part(f->file_1, passes_2_3, 2, overlapping);

    expect_load_error("/nonexistent/part.ppmpart", PPM_ERROR_IO, "/nonexistent/part.ppmpart");
    expect_load_error(small_box, PPM_ERROR_PARSE, "not a libppm partial render");
    const long size = file_size(good);
    copy_file(good, bad);
    flip_byte(bad, size / 2);
    expect_load_error(bad, PPM_ERROR_PARSE, "checksum");
    copy_file(good, bad);
    assert_int_equal(truncate(bad, size - 100), 0);
    expect_load_error(bad, PPM_ERROR_PARSE, "bad.ppmpart");
    assert_int_equal(truncate(bad, 12), 0);
    expect_load_error(bad, PPM_ERROR_PARSE, "truncated");
    copy_file(good, bad);
    flip_byte(bad, 8);
    expect_load_error(bad, PPM_ERROR_PARSE, "version 2");

    /* Another render (seed), overlapping passes, another mode, another scene. */
    ppm_renderer r = new_renderer(f->file_1);
    assert_int_equal(ppm_renderer_set_int(r, "seed", 99), PPM_OK);
    assert_int_equal(ppm_render_pass(r), PPM_OK);
    assert_int_equal(ppm_renderer_save_partial(r, seeded), PPM_OK);
    ppm_renderer_release(r);
    ppm_partial g = NULL, s = NULL, o = NULL;
    assert_int_equal(ppm_partial_load(good, &g), PPM_OK);
    assert_int_equal(ppm_partial_load(seeded, &s), PPM_OK);
    assert_int_equal(ppm_partial_load(overlapping, &o), PPM_OK);
    expect_merge_error(g, s, "seed is 99, the other's is 7", "seeded.ppmpart");
    expect_merge_error(g, o, "both hold pass 2", "overlapping.ppmpart");
    assert_int_equal(ppm_partial_merge(g, g), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_partial_merge(g, NULL), PPM_ERROR_INVALID_ARGUMENT);

    ppm_renderer sppm = NULL;
    assert_int_equal(ppm_scene_file_create_renderer(f->file_1, &sppm), PPM_OK);
    assert_int_equal(ppm_renderer_merge_partial(sppm, g), PPM_ERROR_INVALID_OPERATION);
    assert_non_null(strstr(ppm_last_error_message(), "pppm"));
    assert_int_equal(ppm_render_pass_index(sppm, 3), PPM_ERROR_INVALID_OPERATION);
    assert_int_equal(ppm_renderer_save_partial(sppm, bad), PPM_ERROR_INVALID_OPERATION);
    ppm_renderer_release(sppm);

    ppm_renderer holder = new_renderer(f->file_1);
    assert_int_equal(ppm_renderer_save_partial(holder, bad), PPM_ERROR_INVALID_OPERATION); /* no pass yet */
    assert_int_equal(ppm_render_pass_index(holder, 1), PPM_OK);
    assert_int_equal(ppm_render_pass_index(holder, 1), PPM_ERROR_INVALID_OPERATION);
    assert_int_equal(ppm_render_pass_index(holder, (uint64_t)1 << 32), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_renderer_set_int(holder, "photons_per_pass", 100), PPM_ERROR_INVALID_OPERATION);
    assert_int_equal(ppm_renderer_merge_partial(holder, g), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(ppm_last_error_message(), "holds pass 1"));
    ppm_renderer_release(holder);

    /* pass_total, and the passes a merge is missing. */
    assert_int_equal(ppm_partial_set_int(g, "pass_total", 10), PPM_OK);
    assert_int_equal(partial_int(g, "pass_total"), 10);
    assert_int_equal(ppm_partial_set_int(g, "pass_total", -1), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_partial_set_int(g, "passes", 3), PPM_ERROR_INVALID_ARGUMENT);
    int64_t unused = 0;
    assert_int_equal(ppm_partial_get_int(g, "nonsense", &unused), PPM_ERROR_INVALID_ARGUMENT);
    size_t count = 0;
    assert_int_equal(ppm_partial_get_passes(g, NULL, 0, &count), PPM_OK);
    assert_int_equal(count, 1);
    uint64_t too_small[1];
    assert_int_equal(ppm_partial_get_passes(g, too_small, 1, &count), PPM_ERROR_INVALID_ARGUMENT);
    float one[1];
    assert_int_equal(ppm_partial_get_layer(g, "radiance", one, 1), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_partial_get_layer(g, "nonsense", one, 1), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_partial_save(g, "/nonexistent/dir/x.ppmpart"), PPM_ERROR_IO);
    const unsigned char junk[16] = {0};
    ppm_partial from_junk = NULL;
    assert_int_equal(ppm_partial_load_memory(junk, sizeof junk, &from_junk), PPM_ERROR_PARSE);
    assert_int_equal(ppm_partial_load_memory(NULL, 4, &from_junk), PPM_ERROR_INVALID_ARGUMENT);
    ppm_partial_release(g);
    ppm_partial_release(s);
    ppm_partial_release(o);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_merged_parts_equal_one_render, setup, teardown),
        cmocka_unit_test_setup_teardown(test_checkpoint_resumes_pppm, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_partials_are_refused, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
