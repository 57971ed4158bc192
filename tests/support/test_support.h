// SPDX-License-Identifier: Apache-2.0
/* Helpers shared by the cmocka tests. */
#ifndef PPM_TEST_SUPPORT_H
#define PPM_TEST_SUPPORT_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* cmocka 1.1.5's header has no C++ guards of its own. */
#include <cmocka.h>

/* cmocka fixture: a fresh context and an empty scene per test (*state points to it). */
typedef struct scene_fixture {
    struct ppm_context_t *context;
    struct ppm_scene_t *scene;
} scene_fixture;
int scene_fixture_setup(void **state);
int scene_fixture_teardown(void **state);

/* Deterministic random numbers (splitmix64) so failures reproduce. */
typedef struct test_rng {
    uint64_t state;
} test_rng;
double test_rng_uniform(test_rng *rng); /* [0, 1) */

/* Asserts |a - b| <= tolerance with a message naming both values. */
#define assert_close(a, b, tolerance)                                                                                  \
    _assert_close((double)(a), (double)(b), (double)(tolerance), #a, #b, __FILE__, __LINE__)
void _assert_close(double a, double b, double tolerance, const char *a_text, const char *b_text, const char *file,
                   int line);

/* True when PPM_TEST_QUICK is set and not "0": the sanitizer builds, whose tests run the same
 * library calls but may leave out repetitions of the test's own arithmetic that the Release
 * run does in full. */
int test_quick(void);

/* A new empty folder $TMPDIR/<prefix>XXXXXX (TMPDIR defaults to /tmp); its path goes into out.
 * Returns 0, or -1 if it cannot be made. */
int test_make_folder(char *out, size_t size, const char *prefix);
/* Removes the files in a folder made by test_make_folder (not recursive), then the folder. */
void test_remove_folder(const char *path);

#ifdef __cplusplus
}
#endif

#endif
