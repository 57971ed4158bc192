/* SPDX-License-Identifier: Apache-2.0 */
#include "test_support.h"

#include <ppm/ppm.h>

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

double test_rng_uniform(test_rng *rng) {
    uint64_t z = (rng->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

void _assert_close(double a, double b, double tolerance, const char *a_text, const char *b_text, const char *file,
                   int line) {
    if (fabs(a - b) <= tolerance) return;
    print_error("%s = %.17g and %s = %.17g differ by %.3g > %.3g\n", a_text, a, b_text, b, fabs(a - b), tolerance);
    _fail(file, line);
}

int scene_fixture_setup(void **state) {
    scene_fixture *f = calloc(1, sizeof *f);
    if (!f) return -1;
    if (ppm_context_create(&f->context) != PPM_OK || ppm_scene_create(f->context, &f->scene) != PPM_OK) {
        ppm_context_release(f->context);
        free(f);
        return -1;
    }
    *state = f;
    return 0;
}

int scene_fixture_teardown(void **state) {
    scene_fixture *f = *state;
    ppm_scene_release(f->scene);
    ppm_context_release(f->context);
    free(f);
    return 0;
}

int test_make_folder(char *out, size_t size, const char *prefix) {
    const char *tmp = getenv("TMPDIR");
    const int n = snprintf(out, size, "%s/%sXXXXXX", tmp && tmp[0] ? tmp : "/tmp", prefix);
    if (n < 0 || (size_t)n >= size) return -1;
    return mkdtemp(out) ? 0 : -1;
}

int test_quick(void) {
    const char *quick = getenv("PPM_TEST_QUICK");
    return quick && *quick && strcmp(quick, "0") != 0;
}

void test_remove_folder(const char *path) {
    DIR *dir = opendir(path);
    if (dir) {
        struct dirent *entry;
        char file[1024];
        while ((entry = readdir(dir)))
            if (strcmp(entry->d_name, ".") && strcmp(entry->d_name, "..")) {
                snprintf(file, sizeof file, "%s/%s", path, entry->d_name);
                remove(file);
            }
        closedir(dir);
    }
    rmdir(path);
}
