/* SPDX-License-Identifier: Apache-2.0 */
/* Checkpoints: a render stopped and resumed equals the uninterrupted render bit for bit, and
 * every kind of wrong checkpoint is refused with a message that says why. */
#include <ppm/ppm.h>

#include "test_support.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *const small_box = PPM_TEST_DATA_DIR "/scenes/small_box.json";

typedef struct fixture {
    ppm_context context;
    ppm_scene_file file;
    char folder[256];
    char path[320];
} fixture;

static int setup(void **state) {
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    assert_int_equal(ppm_context_create(&f->context), PPM_OK);
    assert_int_equal(ppm_scene_file_load(f->context, small_box, &f->file), PPM_OK);
    assert_int_equal(test_make_folder(f->folder, sizeof f->folder, "ppm-checkpoint-test-"), 0);
    snprintf(f->path, sizeof f->path, "%s/render.ppmckpt", f->folder);
    *state = f;
    return 0;
}

static int teardown(void **state) {
    fixture *f = *state;
    test_remove_folder(f->folder);
    ppm_scene_file_release(f->file);
    ppm_context_release(f->context);
    free(f);
    return 0;
}

static ppm_renderer new_renderer(fixture *f, const char *mode) {
    ppm_renderer r = NULL;
    assert_int_equal(ppm_scene_file_create_renderer(f->file, &r), PPM_OK);
    assert_int_equal(ppm_renderer_set_string(r, "mode", mode), PPM_OK);
    assert_int_equal(ppm_renderer_set_int(r, "photons_per_pass", 5000), PPM_OK);
    return r;
}

static void run_passes(ppm_renderer r, int passes) {
    for (int i = 0; i < passes; ++i) assert_int_equal(ppm_render_pass(r), PPM_OK);
}

static void assert_same_layer(ppm_renderer a, ppm_renderer b, const char *layer, size_t count) {
    float *x = malloc(count * sizeof *x), *y = malloc(count * sizeof *y);
    assert_int_equal(ppm_renderer_get_layer(a, layer, x, count), PPM_OK);
    assert_int_equal(ppm_renderer_get_layer(b, layer, y, count), PPM_OK);
    double sum = 0;
    for (size_t i = 0; i < count; ++i) sum += x[i];
    assert_true(sum > 0); /* a real image, not two black ones */
    assert_memory_equal(x, y, count * sizeof *x);
    free(x);
    free(y);
}

static void check_resume_equals_uninterrupted(fixture *f, const char *mode) {
    ppm_renderer whole = new_renderer(f, mode);
    run_passes(whole, 5);

    ppm_renderer first = new_renderer(f, mode);
    run_passes(first, 2);
    assert_int_equal(ppm_renderer_save_checkpoint(first, f->path), PPM_OK);
    ppm_renderer_release(first);

    ppm_renderer resumed = new_renderer(f, mode);
    assert_int_equal(ppm_renderer_load_checkpoint(resumed, f->path), PPM_OK);
    int64_t passes = 0, emitted = 0;
    assert_int_equal(ppm_renderer_get_int(resumed, "passes", &passes), PPM_OK);
    assert_int_equal(passes, 2);
    assert_int_equal(ppm_renderer_get_int(resumed, "photons_emitted", &emitted), PPM_OK);
    assert_int_equal(emitted, 10000);
    run_passes(resumed, 3);

    const size_t pixels = 64 * 48;
    assert_same_layer(whole, resumed, "radiance", pixels * 3);
    assert_same_layer(whole, resumed, "radius", pixels);
    assert_same_layer(whole, resumed, "photons", pixels);
    ppm_renderer_release(whole);
    ppm_renderer_release(resumed);
}

static void test_resume_equals_uninterrupted_sppm(void **state) { check_resume_equals_uninterrupted(*state, "sppm"); }
static void test_resume_equals_uninterrupted_ppm(void **state) { check_resume_equals_uninterrupted(*state, "ppm"); }

static void test_checkpoint_before_any_pass(void **state) {
    fixture *f = *state;
    ppm_renderer r = new_renderer(f, "sppm");
    assert_int_equal(ppm_renderer_save_checkpoint(r, f->path), PPM_OK);
    ppm_renderer fresh = new_renderer(f, "sppm");
    assert_int_equal(ppm_renderer_load_checkpoint(fresh, f->path), PPM_OK);
    run_passes(fresh, 1);
    run_passes(r, 1);
    assert_same_layer(r, fresh, "radiance", 64 * 48 * 3);
    ppm_renderer_release(r);
    ppm_renderer_release(fresh);
}

static long file_size(const char *path) {
    FILE *file = fopen(path, "rb");
    assert_non_null(file);
    fseek(file, 0, SEEK_END);
    const long size = ftell(file);
    fclose(file);
    return size;
}

static void rewrite_byte(const char *path, long offset, int delta) {
    FILE *file = fopen(path, "r+b");
    assert_non_null(file);
    fseek(file, offset, SEEK_SET);
    const int byte = fgetc(file);
    fseek(file, offset, SEEK_SET);
    fputc((byte + delta) & 0xFF, file);
    fclose(file);
}

static void expect_load_error(fixture *f, const char *path, ppm_status status, const char *fragment) {
    ppm_renderer r = new_renderer(f, "sppm");
    const ppm_status got = ppm_renderer_load_checkpoint(r, path);
    if (got != status || !strstr(ppm_last_error_message(), fragment))
        fail_msg("status %d (expected %d), message '%s' (expected '%s')", got, status, ppm_last_error_message(),
                 fragment);
    int64_t passes = -1;
    assert_int_equal(ppm_renderer_get_int(r, "passes", &passes), PPM_OK);
    assert_int_equal(passes, 0); /* a refused checkpoint changes nothing */
    run_passes(r, 1);
    ppm_renderer_release(r);
}

static void test_bad_checkpoints_are_refused(void **state) {
    fixture *f = *state;
    ppm_renderer r = new_renderer(f, "sppm");
    run_passes(r, 1);
    assert_int_equal(ppm_renderer_save_checkpoint(r, f->path), PPM_OK);
    /* Loading is only for a fresh renderer. */
    assert_int_equal(ppm_renderer_load_checkpoint(r, f->path), PPM_ERROR_INVALID_OPERATION);
    ppm_renderer_release(r);

    char other[320];
    snprintf(other, sizeof other, "%s/other", f->folder);
    expect_load_error(f, "/nonexistent/render.ppmckpt", PPM_ERROR_IO, "/nonexistent/render.ppmckpt");
    expect_load_error(f, small_box, PPM_ERROR_PARSE, "not a libppm checkpoint");

    /* A flipped bit in the statistics fails the checksum; a cut file is truncated. */
    char command[800];
    const long size = file_size(f->path);
    snprintf(command, sizeof command, "cp '%s' '%s'", f->path, other);
    assert_int_equal(system(command), 0);
    rewrite_byte(other, size / 2, 1);
    expect_load_error(f, other, PPM_ERROR_PARSE, "corrupt");
    assert_int_equal(truncate(other, size - 100), 0);
    expect_load_error(f, other, PPM_ERROR_PARSE, "checkpoint");
    assert_int_equal(truncate(other, 10), 0);
    expect_load_error(f, other, PPM_ERROR_PARSE, "truncated");
    /* Another version. */
    snprintf(command, sizeof command, "cp '%s' '%s'", f->path, other);
    assert_int_equal(system(command), 0);
    rewrite_byte(other, 8, 1);
    expect_load_error(f, other, PPM_ERROR_PARSE, "version 2");

    /* The checkpoint of another render: settings and camera are named. */
    ppm_renderer seeded = new_renderer(f, "sppm");
    assert_int_equal(ppm_renderer_set_int(seeded, "seed", 99), PPM_OK);
    assert_int_equal(ppm_renderer_load_checkpoint(seeded, f->path), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(ppm_last_error_message(), "seed is 7, this renderer's is 99"));
    ppm_renderer_release(seeded);
    ppm_renderer ppm_mode = new_renderer(f, "ppm");
    assert_int_equal(ppm_renderer_load_checkpoint(ppm_mode, f->path), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(ppm_last_error_message(), "mode is sppm"));
    ppm_renderer_release(ppm_mode);

    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_file_get_scene(f->file, &scene), PPM_OK);
    ppm_camera camera;
    assert_int_equal(ppm_scene_file_get_camera(f->file, &camera), PPM_OK);
    camera.fov += 1;
    ppm_renderer moved = NULL;
    assert_int_equal(ppm_renderer_create(scene, &camera, &moved), PPM_OK);
    assert_int_equal(ppm_renderer_set_string(moved, "mode", "sppm"), PPM_OK);
    assert_int_equal(ppm_renderer_set_int(moved, "seed", 7), PPM_OK);
    assert_int_equal(ppm_renderer_load_checkpoint(moved, f->path), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(ppm_last_error_message(), "camera differs"));
    ppm_renderer_release(moved);
    ppm_scene_release(scene);

    /* Unwritable target: an IO error, and no temporary file left behind. */
    ppm_renderer w = new_renderer(f, "sppm");
    assert_int_equal(ppm_renderer_save_checkpoint(w, "/nonexistent/dir/x.ppmckpt"), PPM_ERROR_IO);
    assert_int_equal(ppm_renderer_save_checkpoint(w, NULL), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_renderer_save_checkpoint(NULL, f->path), PPM_ERROR_INVALID_ARGUMENT);
    ppm_renderer_release(w);
}

/* Crafted checkpoints: the checksum only proves that a file is as written, so a file whose
 * checksum was recomputed after an edit must still be refused when its numbers could not
 * have come from a render. Layout: 96 header bytes (passes at 72, photons emitted at 80, slot
 * count at 88), then one u32 pixel per slot, then 8 doubles per slot (N, R^2, tau rgb, direct
 * rgb), then the FNV-1a hash of everything before it. */
enum { header_bytes = 96, passes_at = 72, emitted_at = 80, slots_at = 88 };

static unsigned char *read_all(const char *path, size_t *size) {
    FILE *file = fopen(path, "rb");
    assert_non_null(file);
    fseek(file, 0, SEEK_END);
    *size = (size_t)ftell(file);
    fseek(file, 0, SEEK_SET);
    unsigned char *bytes = malloc(*size);
    assert_non_null(bytes);
    assert_int_equal(fread(bytes, 1, *size, file), *size);
    fclose(file);
    return bytes;
}

/* Writes the first `size` bytes of `bytes` and their FNV-1a hash to `path`. */
static void write_with_checksum(const char *path, const unsigned char *bytes, size_t size) {
    uint64_t hash = 14695981039346656037ull;
    for (size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
    FILE *file = fopen(path, "wb");
    assert_non_null(file);
    assert_int_equal(fwrite(bytes, 1, size, file), size);
    assert_int_equal(fwrite(&hash, sizeof hash, 1, file), 1);
    fclose(file);
}

/* Renders `passes` passes, saves the checkpoint to f->path and returns the path of the
 * crafted copy the test writes. */
static const char *save_after(fixture *f, int passes, char crafted[320]) {
    ppm_renderer r = new_renderer(f, "sppm");
    run_passes(r, passes);
    assert_int_equal(ppm_renderer_save_checkpoint(r, f->path), PPM_OK);
    ppm_renderer_release(r);
    snprintf(crafted, 320, "%s/crafted.ppmckpt", f->folder);
    return crafted;
}

/* Writes the saved checkpoint to `out` with `count` bytes at `at` replaced (when count > 0),
 * its first `keep` bytes only (0: all but the old checksum), and a recomputed checksum. */
static void craft(fixture *f, const char *out, size_t at, const void *value, size_t count, size_t keep) {
    size_t size;
    unsigned char *bytes = read_all(f->path, &size);
    assert_true(at + count <= size - 8);
    memcpy(bytes + at, value, count);
    write_with_checksum(out, bytes, keep ? keep : size - 8);
    free(bytes);
}

/* Offset of field 0..7 of slot `slot`'s statistics in the saved checkpoint. */
static size_t statistic_at(fixture *f, size_t slot, int field) {
    size_t size;
    unsigned char *bytes = read_all(f->path, &size);
    uint64_t slots;
    memcpy(&slots, bytes + slots_at, sizeof slots);
    free(bytes);
    assert_true(slot < slots);
    return header_bytes + slots * 4 + (slot * 8 + (size_t)field) * sizeof(double);
}

static void craft_statistic(fixture *f, const char *out, size_t slot, int field, double value) {
    craft(f, out, statistic_at(f, slot, field), &value, sizeof value, 0);
}

/* The saved header with its counts (passes, photons emitted) replaced; with `no_slots`, the
 * slot count is 0 and the statistics are cut off. */
static void craft_counts(fixture *f, const char *out, uint64_t passes, uint64_t emitted, int no_slots) {
    const uint64_t counts[3] = {passes, emitted, 0};
    craft(f, out, passes_at, counts, no_slots ? sizeof counts : 2 * sizeof(uint64_t), no_slots ? header_bytes : 0);
}

static void test_implausible_statistics_are_refused(void **state) {
    fixture *f = *state;
    char path[320];
    const char *crafted = save_after(f, 2, path);
    /* The untouched statistics re-hashed load: the crafting itself is right. */
    craft(f, crafted, 0, "", 0, 0);
    ppm_renderer fine = new_renderer(f, "sppm");
    assert_int_equal(ppm_renderer_load_checkpoint(fine, crafted), PPM_OK);
    ppm_renderer_release(fine);

    const size_t slot = 64 * 24 + 32; /* a pixel in the middle of the image */
    craft_statistic(f, crafted, slot, 0, NAN);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "pixel slot 1568: photon count N = nan");
    craft_statistic(f, crafted, slot, 0, -1);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "photon count N = -1");
    craft_statistic(f, crafted, slot, 0, 1e300);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "photon count N = 1e+300 (must lie in [0, photons emitted x 1000])");
    craft_statistic(f, crafted, slot, 1, -0.5);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "radius squared = -0.5");
    craft_statistic(f, crafted, slot, 1, 1e300);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "radius squared = 1e+300");
    craft_statistic(f, crafted, slot, 1, INFINITY);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "radius squared = inf");
    craft_statistic(f, crafted, slot, 3, NAN);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "flux tau = nan");
    craft_statistic(f, crafted, slot, 2, 1e300);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "radiance");
    craft_statistic(f, crafted, slot, 7, -2);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "direct light = -2");
    craft_statistic(f, crafted, slot, 5, 1e300);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "radiance");
}

static void test_counts_that_disagree_are_refused(void **state) {
    fixture *f = *state;
    char path[320];
    const char *crafted = save_after(f, 1, path);
    /* Passes recorded without statistics are refused, not dropped. */
    craft_counts(f, crafted, 3, 15000, 1);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "3 passes recorded but no pixel statistics");
    craft_counts(f, crafted, 0, 5000, 1);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "no pass recorded, but 5000 photons emitted");
}

/* Flux in a slot without a radius: the next pass gives the slot the initial radius and
 * keeps the flux, so a crafted flux would become an infinite pixel. */
static void test_flux_without_radius_is_refused(void **state) {
    fixture *f = *state;
    char path[320];
    const char *crafted = save_after(f, 1, path);
    const double values[3] = {0, 0, 1e30}; /* N, R^2, tau red */
    craft(f, crafted, statistic_at(f, 7, 0), values, sizeof values, 0);
    expect_load_error(f, crafted, PPM_ERROR_PARSE,
                      "pixel slot 7: flux tau = 1e+30 (must be 0 where no radius was set)");
}

/* Counts beyond int64_t, which ppm_renderer_get_int would report as negative, with the
 * statistics kept so that only the counts are wrong. */
static void test_counts_beyond_int64_are_refused(void **state) {
    fixture *f = *state;
    char path[320];
    const char *crafted = save_after(f, 1, path);
    craft_counts(f, crafted, UINT64_MAX, UINT64_MAX, 0);
    expect_load_error(f, crafted, PPM_ERROR_PARSE, "18446744073709551615 photons emitted, more than 2^63 - 1");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_resume_equals_uninterrupted_sppm, setup, teardown),
        cmocka_unit_test_setup_teardown(test_resume_equals_uninterrupted_ppm, setup, teardown),
        cmocka_unit_test_setup_teardown(test_checkpoint_before_any_pass, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_checkpoints_are_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_implausible_statistics_are_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_counts_that_disagree_are_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_counts_beyond_int64_are_refused, setup, teardown),
        cmocka_unit_test_setup_teardown(test_flux_without_radius_is_refused, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
