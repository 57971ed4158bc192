/* SPDX-License-Identifier: Apache-2.0 */
/* Shading normals in every mode (shading/shading_normals.h): a diffuse plane whose vertex
 * normals all lean 30 degrees away from its geometric normal, under a point light, seen from
 * above. Mitsuba's convention, which the camera paths follow, gives each point
 * rho/pi I max(0, l . ns) / d^2 (l towards the light, ns the shading normal); light paths
 * must reach the same through Veach's correction, although their flux lands per geometric
 * area. Without it the photon modes would show rho/pi I (l . ng) / d^2, half as bright again
 * where the normal leans away from the light. */
#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

enum { kSize = 16 };
static const double kRho = 0.6, kIntensity = 2.0, kHeight = 1.0, kLean = 30 * M_PI / 180;
static const double kLight[3] = {0.3, -0.4, 1.0};

/* A plane of two triangles [-50, 50]^2 at z = 0 whose four vertex normals are (0, sin, cos)
 * of the lean: the shading normal leans towards +y everywhere. */
static void build_leaning_plane(ppm_scene scene) {
    const double positions[12] = {-50, -50, 0, 50, -50, 0, 50, 50, 0, -50, 50, 0};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    double normals[12];
    for (int v = 0; v < 4; ++v) {
        normals[3 * v] = 0;
        normals[3 * v + 1] = sin(kLean);
        normals[3 * v + 2] = cos(kLean);
    }
    const double rgb[3] = {kRho, kRho, kRho}, intensity[3] = {kIntensity, kIntensity, kIntensity};
    uint32_t material = 0, id = 0;
    assert_ppm_ok(ppm_scene_add_diffuse_material(scene, rgb, &material));
    assert_ppm_ok(ppm_scene_add_triangle_mesh(scene, positions, 4, indices, 2, normals, NULL, &id));
    assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, material));
    assert_ppm_ok(ppm_scene_add_point_light(scene, kLight, intensity, NULL));
    assert_ppm_ok(ppm_scene_commit(scene));
}

static ppm_camera top_camera(void) {
    ppm_camera camera;
    memset(&camera, 0, sizeof camera);
    camera.origin[2] = 2.5;
    camera.up[1] = 1;
    camera.fov = 60;
    camera.width = camera.height = kSize;
    return camera;
}

/* The image mean the shading normal gives (cos_with = ns) or the geometric one (ng), over
 * 4 x 4 points of each pixel. The camera looks down -z with left = -x and up' = +y
 * (camera.h), so the film's local (lx, ly) meets the plane at (-2.5 lx, 2.5 ly). */
static double expected_mean(int shading) {
    const double t = tan(M_PI / 6), ns[3] = {0, sin(kLean), cos(kLean)};
    double sum = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int s = 0; s < 16; ++s) {
                const double fx = x + (s % 4 + 0.5) / 4, fy = y + (s / 4 + 0.5) / 4;
                const double px = -(1 - 2 * fx / kSize) * t * 2.5, py = (1 - 2 * fy / kSize) * t * 2.5;
                const double l[3] = {kLight[0] - px, kLight[1] - py, kHeight};
                const double d2 = l[0] * l[0] + l[1] * l[1] + l[2] * l[2], d = sqrt(d2);
                const double cos_l = shading ? fmax(0.0, (l[1] * ns[1] + l[2] * ns[2]) / d) : l[2] / d;
                sum += kRho / M_PI * kIntensity * cos_l / d2 / 16;
            }
    return sum / (kSize * kSize);
}

static double render_mean(ppm_scene scene, const char *mode, int passes, int photons_only) {
    const ppm_camera camera = top_camera();
    ppm_renderer r = NULL;
    assert_ppm_ok(ppm_renderer_create(scene, &camera, &r));
    assert_ppm_ok(ppm_renderer_set_string(r, "mode", mode));
    if (photons_only) {
        assert_ppm_ok(ppm_renderer_set_int(r, "direct_lighting", 0));
        assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 50000));
    }
    for (int i = 0; i < passes; ++i) assert_ppm_ok(ppm_renderer_render_pass(r));
    float rgb[3 * kSize * kSize];
    assert_ppm_ok(ppm_renderer_get_layer(r, "radiance", rgb, 3 * kSize * kSize));
    ppm_renderer_release(r);
    double sum = 0;
    for (int i = 0; i < 3 * kSize * kSize; ++i) sum += rgb[i];
    return sum / (3 * kSize * kSize);
}

static void every_mode_reads_the_shading_normal_as_the_camera_paths_do(void **state) {
    scene_fixture *f = *state;
    build_leaning_plane(f->scene);
    const double expected = expected_mean(1), geometric = expected_mean(0);
    print_message("leaning shading normal: expected mean %.5f (with the geometric normal %.5f)\n", expected, geometric);
    assert_true(geometric > 1.15 * expected); /* the two conventions are far apart here */
    /* The photon modes with photons only (no shadow rays at the camera vertex), and the
     * bidirectional ones: light tracing, connections and merging. */
    const struct {
        const char *mode;
        int passes, photons_only;
    } runs[] = {{"sppm", 64, 1}, {"pppm", 64, 1}, {"vcm", 128, 0}, {"bpt", 128, 0}, {"vm", 256, 0}};
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; ++i) {
        const double m = render_mean(f->scene, runs[i].mode, runs[i].passes, runs[i].photons_only);
        print_message("  %s%s: mean %.5f, ratio %.4f\n", runs[i].mode, runs[i].photons_only ? " (photons only)" : "", m,
                      m / expected);
        assert_close(m, expected, 0.03 * expected);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(every_mode_reads_the_shading_normal_as_the_camera_paths_do, scene_fixture_setup,
                                        scene_fixture_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
