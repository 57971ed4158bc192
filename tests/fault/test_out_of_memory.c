/* SPDX-License-Identifier: Apache-2.0 */
/* Allocation failure: under an address-space limit (RLIMIT_AS, what `ulimit -v` sets), inputs
 * whose arrays do not fit (a 2^28-pixel film, a huge mesh or patch set) give
 * PPM_ERROR_OUT_OF_MEMORY with a message naming the object and its size, and the process
 * stays usable: the same renderer fails the same way again, and a small render succeeds.
 * Skipped in sanitizer builds, whose runtime reserves terabytes of address space and aborts on
 * huge requests instead of failing them. */
#include <ppm/ppm.h>

#include "test_support.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define SANITIZED 1
#endif
#endif

static const char *const small_box = PPM_TEST_DATA_DIR "/scenes/small_box.json";

/* Room for the test's own work beyond what the process has mapped when it starts. */
static const unsigned long long headroom = 2ull << 30;

typedef struct fixture {
    ppm_context context;
    ppm_scene_file file;
    ppm_scene scene;
} fixture;

static int setup(void **state) {
    fixture *f = calloc(1, sizeof *f);
    assert_non_null(f);
    assert_int_equal(ppm_context_create(&f->context), PPM_OK);
    assert_int_equal(ppm_context_set_int(f->context, "threads", 2), PPM_OK);
    assert_int_equal(ppm_scene_file_load(f->context, small_box, &f->file), PPM_OK);
    assert_int_equal(ppm_scene_file_get_scene(f->file, &f->scene), PPM_OK);
    *state = f;
    return 0;
}

static int teardown(void **state) {
    fixture *f = *state;
    ppm_scene_release(f->scene);
    ppm_scene_file_release(f->file);
    ppm_context_release(f->context);
    free(f);
    return 0;
}

static void assert_message_names(const char *fragment) {
    const char *message = ppm_last_error_message();
    print_message("message: %s\n", message);
    assert_non_null(strstr(message, fragment));
    assert_non_null(strstr(message, " bytes ("));
}

/* A small render from scratch: the process is still usable. */
static void assert_small_render_works(fixture *f) {
    ppm_renderer r = NULL;
    assert_int_equal(ppm_scene_file_create_renderer(f->file, &r), PPM_OK);
    assert_int_equal(ppm_renderer_set_int(r, "photons_per_pass", 2000), PPM_OK);
    assert_int_equal(ppm_render_pass(r), PPM_OK);
    float pixel[3 * 64 * 48];
    assert_int_equal(ppm_renderer_get_layer(r, "radiance", pixel, 3 * 64 * 48), PPM_OK);
    ppm_renderer_release(r);
}

static void huge_film(fixture *f, const char *mode, const char *object) {
    ppm_camera camera;
    assert_int_equal(ppm_scene_file_get_camera(f->file, &camera), PPM_OK);
    camera.width = 16384; /* 2^28 pixels, the largest film allowed */
    camera.height = 16384;
    ppm_renderer r = NULL;
    assert_int_equal(ppm_renderer_create(f->scene, &camera, &r), PPM_OK);
    assert_int_equal(ppm_renderer_set_string(r, "mode", mode), PPM_OK);
    assert_int_equal(ppm_renderer_set_int(r, "photons_per_pass", 1000), PPM_OK);
    for (int attempt = 0; attempt < 2; ++attempt) {
        assert_int_equal(ppm_render_pass(r), PPM_ERROR_OUT_OF_MEMORY);
        assert_message_names(object);
    }
    int64_t passes = -1;
    assert_int_equal(ppm_renderer_get_int(r, "passes", &passes), PPM_OK);
    assert_int_equal(passes, 0);
    ppm_renderer_release(r);
    assert_small_render_works(f);
}

static void sppm_film_too_large(void **state) {
    huge_film(*state, "sppm", "out of memory for the film of 16384 x 16384 pixels: ");
}

static void ppm_film_too_large(void **state) {
    huge_film(*state, "ppm",
              "out of memory for the first PPM pass's hit points (at least this, one per pixel of the film of 16384 x "
              "16384 pixels): ");
}

static void mesh_too_large(void **state) {
    fixture *f = *state;
    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_create(f->context, &scene), PPM_OK);
    /* The arrays are copied after their room is allocated, so small ones are never read. */
    const double positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t indices[3] = {0, 1, 2};
    uint32_t id = 0;
    assert_int_equal(ppm_scene_add_triangle_mesh(scene, positions, 4000000000u, indices, 1, NULL, NULL, &id),
                     PPM_ERROR_OUT_OF_MEMORY);
    assert_message_names("out of memory for a mesh of 4000000000 vertices and 1 triangles: ");
    assert_int_equal(ppm_scene_add_triangle_mesh(scene, positions, 3, indices, 1, NULL, NULL, &id), PPM_OK);
    ppm_scene_release(scene);
    assert_small_render_works(f);
}

static void patches_too_large(void **state) {
    fixture *f = *state;
    ppm_scene scene = NULL;
    assert_int_equal(ppm_scene_create(f->context, &scene), PPM_OK);
    static double control_points[16 * 3];
    uint32_t id = 0;
    /* The limit of 10^7 patches takes 3.8 GB, more than the headroom. */
    assert_int_equal(ppm_scene_add_bezier_patches(scene, control_points, 10000000, &id), PPM_ERROR_OUT_OF_MEMORY);
    assert_message_names("out of memory for 10000000 Bezier patches: ");
    ppm_scene_release(scene);
    assert_small_render_works(f);
}

/* Caps the address space at what is mapped now plus the headroom. */
static int limit_address_space(void) {
    FILE *statm = fopen("/proc/self/statm", "r");
    unsigned long long pages = 0;
    if (!statm || fscanf(statm, "%llu", &pages) != 1) return -1;
    fclose(statm);
    const unsigned long long cap = pages * 4096ull + headroom;
    const struct rlimit limit = {cap, cap};
    if (setrlimit(RLIMIT_AS, &limit) != 0) return -1;
    printf("address space limited to %.2f GiB\n", (double)cap / (1ull << 30));
    return 0;
}

int main(void) {
#ifdef SANITIZED
    printf("skipped: sanitizer builds reserve huge address space; RLIMIT_AS cannot be tested there\n");
    return 77; /* ctest's SKIP_RETURN_CODE */
#else
    /* A context first, so that its threads and pools are mapped before the limit is taken. */
    ppm_context warm = NULL;
    if (ppm_context_create(&warm) != PPM_OK || limit_address_space() != 0) {
        fprintf(stderr, "cannot set up the address-space limit\n");
        return 1;
    }
    ppm_context_release(warm);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(sppm_film_too_large, setup, teardown),
        cmocka_unit_test_setup_teardown(ppm_film_too_large, setup, teardown),
        cmocka_unit_test_setup_teardown(mesh_too_large, setup, teardown),
        cmocka_unit_test_setup_teardown(patches_too_large, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
#endif
}
