/* SPDX-License-Identifier: Apache-2.0 */
/* Checkpoint writes that fail (disk full, I/O error, at each step of the atomic write) return
 * PPM_ERROR_IO naming the file and the reason, leave the previous checkpoint byte for byte,
 * and leave no temporary file. The faults come from the fault shim linked into this test
 * (fault_shim.c), configured through its environment variables. */
#include <ppm/ppm.h>

#include "test_support.h"

#include <dirent.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* From the fault shim: re-reads PPM_FAULT_* and restarts its counts. */
void ppm_fault_reset(void);

static const char *const small_box = PPM_TEST_DATA_DIR "/scenes/small_box.json";

typedef struct fixture {
    ppm_context context;
    ppm_scene_file file;
    ppm_renderer renderer; /* one pass done, its checkpoint saved at `path` */
    char folder[256];
    char path[320];
    char *previous; /* the bytes of that checkpoint */
    size_t previous_size;
} fixture;

static char *read_file(const char *path, size_t *size) {
    FILE *in = fopen(path, "rb");
    if (!in) return NULL;
    char *data = NULL;
    size_t used = 0, capacity = 0;
    for (;;) {
        if (used == capacity) {
            capacity = capacity ? 2 * capacity : 65536;
            data = realloc(data, capacity);
            assert_non_null(data);
        }
        const size_t n = fread(data + used, 1, capacity - used, in);
        if (n == 0) break;
        used += n;
    }
    fclose(in);
    *size = used;
    return data;
}

static void faults_off(void) {
    unsetenv("PPM_FAULT_OPS");
    unsetenv("PPM_FAULT_NTH");
    unsetenv("PPM_FAULT_BYTES");
    unsetenv("PPM_FAULT_ERRNO");
    unsetenv("PPM_FAULT_PATH");
    ppm_fault_reset();
}

/* Faults for files in the fixture's folder only: OPS, and NTH or BYTES (NULL: unset). */
static void faults_on(const fixture *f, const char *ops, const char *nth, const char *bytes, const char *error) {
    faults_off();
    /* The shim sees paths with symbolic links resolved. */
    char folder[PATH_MAX];
    assert_non_null(realpath(f->folder, folder));
    setenv("PPM_FAULT_PATH", folder, 1);
    setenv("PPM_FAULT_OPS", ops, 1);
    if (nth) setenv("PPM_FAULT_NTH", nth, 1);
    if (bytes) setenv("PPM_FAULT_BYTES", bytes, 1);
    setenv("PPM_FAULT_ERRNO", error, 1);
    ppm_fault_reset();
}

static int setup(void **state) {
    faults_off();
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    assert_int_equal(ppm_context_create(&f->context), PPM_OK);
    assert_int_equal(ppm_scene_file_load(f->context, small_box, &f->file), PPM_OK);
    assert_int_equal(ppm_scene_file_create_renderer(f->file, &f->renderer), PPM_OK);
    assert_int_equal(ppm_renderer_set_int(f->renderer, "photons_per_pass", 2000), PPM_OK);
    assert_int_equal(ppm_render_pass(f->renderer), PPM_OK);
    assert_int_equal(test_make_folder(f->folder, sizeof f->folder, "ppm-fault-checkpoint-"), 0);
    snprintf(f->path, sizeof f->path, "%s/render.ppmckpt", f->folder);
    assert_int_equal(ppm_renderer_save_checkpoint(f->renderer, f->path), PPM_OK);
    f->previous = read_file(f->path, &f->previous_size);
    assert_non_null(f->previous);
    /* A second pass, so that a successful save would change the file. */
    assert_int_equal(ppm_render_pass(f->renderer), PPM_OK);
    *state = f;
    return 0;
}

static int teardown(void **state) {
    fixture *f = *state;
    faults_off();
    test_remove_folder(f->folder);
    free(f->previous);
    ppm_renderer_release(f->renderer);
    ppm_scene_file_release(f->file);
    ppm_context_release(f->context);
    free(f);
    return 0;
}

/* The folder holds exactly `expected` entries besides . and .. (no temporary file). */
static void assert_folder_holds(const char *folder, int expected) {
    DIR *dir = opendir(folder);
    assert_non_null(dir);
    int count = 0;
    for (struct dirent *e; (e = readdir(dir)) != NULL;) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        print_message("in the folder: %s\n", e->d_name);
        ++count;
    }
    closedir(dir);
    assert_int_equal(count, expected);
}

/* The save fails with IO and a message naming the file and `reason`; the previous
 * checkpoint is intact (same bytes, and it loads) and nothing else is in the folder. */
static void check_failed_save(fixture *f, const char *reason) {
    assert_int_equal(ppm_renderer_save_checkpoint(f->renderer, f->path), PPM_ERROR_IO);
    const char *message = ppm_last_error_message();
    print_message("message: %s\n", message);
    assert_non_null(strstr(message, f->path));
    assert_non_null(strstr(message, reason));
    faults_off();

    size_t size = 0;
    char *now = read_file(f->path, &size);
    assert_non_null(now);
    assert_int_equal(size, f->previous_size);
    assert_memory_equal(now, f->previous, size);
    free(now);
    assert_folder_holds(f->folder, 1);

    ppm_renderer loaded = NULL;
    assert_int_equal(ppm_scene_file_create_renderer(f->file, &loaded), PPM_OK);
    assert_int_equal(ppm_renderer_set_int(loaded, "photons_per_pass", 2000), PPM_OK);
    assert_int_equal(ppm_renderer_load_checkpoint(loaded, f->path), PPM_OK);
    int64_t passes = 0;
    assert_int_equal(ppm_renderer_get_int(loaded, "passes", &passes), PPM_OK);
    assert_int_equal(passes, 1);
    ppm_renderer_release(loaded);

    /* The same renderer saves once the disk works again: the failure left no state behind. */
    assert_int_equal(ppm_renderer_save_checkpoint(f->renderer, f->path), PPM_OK);
    now = read_file(f->path, &size);
    assert_non_null(now);
    assert_true(size != f->previous_size || memcmp(now, f->previous, size) != 0);
    free(now);
    assert_folder_holds(f->folder, 1);
}

static void disk_full_at_the_first_byte(void **state) {
    fixture *f = *state;
    faults_on(f, "write", NULL, "0", "ENOSPC");
    check_failed_save(f, "No space left on device");
}

static void disk_full_midway(void **state) {
    fixture *f = *state;
    /* The write is cut short after 10000 bytes and the next one fails: a torn temporary file. */
    faults_on(f, "write", NULL, "10000", "ENOSPC");
    check_failed_save(f, "No space left on device");
}

static void write_io_error(void **state) {
    fixture *f = *state;
    faults_on(f, "write", "1", NULL, "EIO");
    check_failed_save(f, "Input/output error");
}

static void fsync_io_error(void **state) {
    fixture *f = *state;
    faults_on(f, "fsync", "1", NULL, "EIO");
    check_failed_save(f, "Input/output error");
}

static void close_io_error(void **state) {
    fixture *f = *state;
    faults_on(f, "close", "1", NULL, "EIO");
    check_failed_save(f, "Input/output error");
}

static void rename_fails(void **state) {
    fixture *f = *state;
    faults_on(f, "rename", "1", NULL, "EDQUOT");
    check_failed_save(f, "quota exceeded");
}

/* With no previous checkpoint, a failed save creates nothing at all. */
static void nothing_created_when_first_save_fails(void **state) {
    fixture *f = *state;
    char path[400];
    snprintf(path, sizeof path, "%s/other.ppmckpt", f->folder);
    faults_on(f, "write", NULL, "100", "ENOSPC");
    assert_int_equal(ppm_renderer_save_checkpoint(f->renderer, path), PPM_ERROR_IO);
    assert_non_null(strstr(ppm_last_error_message(), path));
    faults_off();
    assert_folder_holds(f->folder, 1); /* only render.ppmckpt */
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(disk_full_at_the_first_byte, setup, teardown),
        cmocka_unit_test_setup_teardown(disk_full_midway, setup, teardown),
        cmocka_unit_test_setup_teardown(write_io_error, setup, teardown),
        cmocka_unit_test_setup_teardown(fsync_io_error, setup, teardown),
        cmocka_unit_test_setup_teardown(close_io_error, setup, teardown),
        cmocka_unit_test_setup_teardown(rename_fails, setup, teardown),
        cmocka_unit_test_setup_teardown(nothing_created_when_first_save_fails, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
