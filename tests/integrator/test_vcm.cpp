// SPDX-License-Identifier: Apache-2.0
// The bidirectional modes (vcm, bpt, vm):
//  - the MIS weights of all techniques that can make a path sum to one, on random paths with
//    random densities, specular vertices among them (vcm_mis.h, with and without merging);
//  - a furnace (closed box of emitting diffuse walls, a glass and a mirror sphere inside)
//    shows L = Le / (1 - albedo) everywhere, in every mode;
//  - a point light over a diffuse plane gives the analytic rho/pi I cos / d^2 per pixel;
//  - the modes agree with sppm on a box with a glass ball under an area light;
//  - the image is the same bits for 1 and 2 threads, and for passes split between two
//    renderers and merged as partials; a thin lens camera works without light tracing;
//  - a film of more pixels than the light subpaths of a pass shares them correctly.
#include "integrator/vcm/vcm_mis.h"
#include "settings/render_settings.h"

#include "api_asserts.h"
#include "test_support.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

using namespace ppm;

namespace {

// ---- MIS weights -------------------------------------------------------------------------

// A random full path y_0 (on an area light) ... y_n (the camera) with everything the weights
// read: squared segment lengths, the cosines at each vertex towards its neighbours, each
// surface vertex's BSDF densities in both directions (continuation included) and whether it
// is specular, and the light's and camera's densities.
struct RandomPath {
    int n = 0;                        // segments
    std::vector<double> d2;           // d2[i]: segment y_i - y_{i+1}
    std::vector<double> cos_prev;     // at y_j towards y_{j-1}
    std::vector<double> cos_next;     // at y_j towards y_{j+1} (y_0: the light's cosine)
    std::vector<double> light_to_cam; // at y_j: density of sampling y_{j+1} arriving from y_{j-1}
    std::vector<double> cam_to_light; // at y_j: density of sampling y_{j-1} arriving from y_{j+1}
    std::vector<bool> specular;
    double emission = 0, direct = 0, pick = 0; // the light's (emission, direct with pick)
    double camera_pdf_w = 0;
};

RandomPath random_path(test_rng &rng, int n) {
    const auto u = [&](double lo, double hi) { return lo + (hi - lo) * test_rng_uniform(&rng); };
    RandomPath p;
    p.n = n;
    p.d2.resize(n);
    p.cos_prev.resize(n + 1);
    p.cos_next.resize(n + 1);
    p.light_to_cam.resize(n + 1);
    p.cam_to_light.resize(n + 1);
    p.specular.assign(n + 1, false);
    for (int i = 0; i < n; ++i) p.d2[i] = u(0.05, 5.0);
    for (int j = 0; j <= n; ++j) {
        p.cos_prev[j] = u(0.05, 1.0);
        p.cos_next[j] = u(0.05, 1.0);
        p.light_to_cam[j] = u(0.05, 3.0);
        p.cam_to_light[j] = u(0.05, 3.0);
        if (j > 0 && j < n) p.specular[j] = test_rng_uniform(&rng) < 0.25;
        // A specular lobe's density is the same both ways (vcm_vertex.h).
        if (p.specular[j]) p.cam_to_light[j] = p.light_to_cam[j];
    }
    p.pick = u(0.1, 1.0);
    const double area = u(0.1, 4.0);
    p.direct = p.pick / area;
    p.emission = p.direct * p.cos_next[0] / M_PI;
    p.camera_pdf_w = u(100, 10000);
    return p;
}

// The light subpath's state at y_j (after arriving), j >= 1.
SubpathMis light_state(const MisFactors &f, const RandomPath &p, int j) {
    SubpathMis m = SubpathMis::light_start(f, p.emission, p.direct, p.cos_next[0], false, true);
    for (int k = 1;; ++k) {
        m.arrive(p.d2[k - 1], p.cos_prev[k]);
        if (k == j) return m;
        m.scatter(f, p.specular[k], p.cos_next[k], p.light_to_cam[k], p.cam_to_light[k]);
    }
}

// The camera subpath's state at y_j (after arriving), j <= n - 1; j = 0 is the light.
SubpathMis camera_state(const MisFactors &f, const RandomPath &p, int j) {
    SubpathMis m = SubpathMis::camera_start(f, p.camera_pdf_w);
    for (int k = p.n - 1;; --k) {
        m.arrive(p.d2[k], k == 0 ? p.cos_next[0] : p.cos_next[k]);
        if (k == j) return m;
        m.scatter(f, p.specular[k], p.cos_prev[k], p.cam_to_light[k], p.light_to_cam[k]);
    }
}

// The sum of the weights of every technique that can make the path.
double weight_sum(const MisFactors &f, const RandomPath &p, bool connect, bool merge) {
    const int n = p.n;
    double sum = 0;
    // The camera subpath hits the light (a camera subpath of one segment is weighted 1 and
    // has no other technique: n >= 2 here).
    sum += mis_emitter_hit(camera_state(f, p, 0), p.direct, p.emission);
    if (connect) {
        // Next event at y_1.
        if (!p.specular[1]) {
            const double direct_pdf_w = p.direct / p.pick * p.d2[0] / p.cos_next[0];
            sum += mis_next_event(f, camera_state(f, p, 1), p.cam_to_light[1], p.light_to_cam[1], p.pick, direct_pdf_w,
                                  p.emission / p.pick, p.cos_next[0], p.cos_prev[1]);
        }
        // Connections between light vertex y_{s-1} and camera vertex y_s.
        for (int s = 2; s <= n - 1; ++s) {
            if (p.specular[s - 1] || p.specular[s]) continue;
            const double camera_fwd_a = p.cam_to_light[s] * p.cos_next[s - 1] / p.d2[s - 1];
            const double light_fwd_a = p.light_to_cam[s - 1] * p.cos_prev[s] / p.d2[s - 1];
            sum += mis_connection(f, camera_state(f, p, s), light_state(f, p, s - 1), camera_fwd_a, p.light_to_cam[s],
                                  light_fwd_a, p.cam_to_light[s - 1]);
        }
        // Light tracing from y_{n-1}.
        if (!p.specular[n - 1]) {
            const double camera_pdf_a = p.camera_pdf_w * p.cos_next[n - 1] / p.d2[n - 1];
            sum += mis_light_trace(f, light_state(f, p, n - 1), camera_pdf_a, p.cam_to_light[n - 1]);
        }
    }
    if (merge)
        for (int j = 1; j <= n - 1; ++j)
            if (!p.specular[j])
                sum += mis_merge(f, camera_state(f, p, j), light_state(f, p, j), p.cam_to_light[j], p.light_to_cam[j]);
    return sum;
}

void check_weights(bool connect, bool merge) {
    test_rng rng{7};
    double worst = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const int n = 2 + trial % 7;
        const RandomPath p = random_path(rng, n);
        const MisFactors f = MisFactors::make(0.001 + 0.05 * test_rng_uniform(&rng), 4096, connect, merge);
        const double sum = weight_sum(f, p, connect, merge);
        worst = std::fmax(worst, std::fabs(sum - 1));
        if (std::fabs(sum - 1) > 1e-9) std::printf("path of %d segments: weights sum to %.12f\n", n, sum);
        assert_true(std::fabs(sum - 1) <= 1e-9);
    }
    std::printf("connect %d merge %d: largest |sum - 1| over 2000 paths %.2g\n", connect, merge, worst);
}

void mis_weights_sum_to_one(void **) { check_weights(true, true); }
void mis_weights_sum_to_one_without_merging(void **) { check_weights(true, false); }

// ---- Renders -----------------------------------------------------------------------------

constexpr int kSize = 24;

void add_box(ppm_scene scene, double albedo, double le, double half) {
    const double rgb[3] = {albedo, albedo, albedo}, emit[3] = {le, le, le};
    uint32_t wall = 0;
    assert_ppm_ok(ppm_scene_add_diffuse_material(scene, rgb, &wall));
    for (int axis = 0; axis < 3; ++axis)
        for (int side = -1; side <= 1; side += 2) {
            const int a = (axis + 1) % 3, b = (axis + 2) % 3;
            double origin[3] = {0, 0, 0}, eu[3] = {0, 0, 0}, ev[3] = {0, 0, 0};
            origin[axis] = side * half;
            origin[a] = -half;
            origin[b] = -half;
            // Normals edge_u x edge_v point inwards.
            if (side < 0) {
                eu[a] = 2 * half;
                ev[b] = 2 * half;
            } else {
                eu[b] = 2 * half;
                ev[a] = 2 * half;
            }
            uint32_t id = 0;
            assert_ppm_ok(ppm_scene_add_quad(scene, origin, eu, ev, &id));
            assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, wall));
            if (le > 0) assert_ppm_ok(ppm_scene_set_geometry_emission(scene, id, emit));
        }
}

void add_sphere(ppm_scene scene, const double centre[3], double radius, uint32_t material) {
    uint32_t id = 0;
    assert_ppm_ok(ppm_scene_add_sphere(scene, centre, radius, &id));
    assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, material));
}

ppm_camera box_camera() {
    ppm_camera camera;
    std::memset(&camera, 0, sizeof camera);
    camera.origin[2] = -0.9;
    camera.target[2] = 1;
    camera.up[1] = 1;
    camera.fov = 70;
    camera.width = camera.height = kSize;
    return camera;
}

std::vector<float> render(ppm_scene scene, const ppm_camera &camera, const char *mode, int passes, int seed = 0,
                          double initial_radius = 0) {
    ppm_renderer r = nullptr;
    assert_ppm_ok(ppm_renderer_create(scene, &camera, &r));
    assert_ppm_ok(ppm_renderer_set_double(r, "initial_radius", initial_radius));
    assert_ppm_ok(ppm_renderer_set_string(r, "mode", mode));
    assert_ppm_ok(ppm_renderer_set_int(r, "seed", seed));
    // The photon modes' count; the bidirectional ones keep theirs, one light subpath per pixel.
    if (std::strcmp(mode, "sppm") == 0) assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 20000));
    for (int i = 0; i < passes; ++i) assert_ppm_ok(ppm_render_pass(r));
    std::vector<float> rgb(3 * camera.width * camera.height);
    assert_ppm_ok(ppm_renderer_get_layer(r, "radiance", rgb.data(), rgb.size()));
    ppm_renderer_release(r);
    return rgb;
}

double mean(const std::vector<float> &rgb) {
    double sum = 0;
    for (float v : rgb) sum += v;
    return sum / rgb.size();
}

const char *const kModes[] = {"vcm", "bpt", "vm"};

// Radiance Le / (1 - albedo) from every wall and through both lossless spheres.
void furnace_in_every_mode(void **state) {
    scene_fixture *f = static_cast<scene_fixture *>(*state);
    const double albedo = 0.5, le = 1.0;
    add_box(f->scene, albedo, le, 1.0);
    uint32_t glass = 0, mirror = 0;
    const double white[3] = {1, 1, 1};
    assert_ppm_ok(ppm_scene_add_dielectric_material(f->scene, 1.5, 1.0, &glass));
    assert_ppm_ok(ppm_scene_add_mirror_material(f->scene, white, &mirror));
    const double c1[3] = {-0.4, 0, 0.3}, c2[3] = {0.45, 0.1, 0.4};
    add_sphere(f->scene, c1, 0.35, glass);
    add_sphere(f->scene, c2, 0.3, mirror);
    assert_ppm_ok(ppm_scene_commit(f->scene));
    const double expected = le / (1 - albedo);
    for (const char *mode : kModes) {
        const double m = mean(render(f->scene, box_camera(), mode, 8));
        std::printf("furnace %s: mean %.4f, expected %.4f (ratio %.4f)\n", mode, m, expected, m / expected);
        assert_close(m, expected, 0.02 * expected);
    }
}

// A point light of intensity I at height h over a diffuse plane of albedo rho, seen from
// above: each pixel shows rho / pi I cos(theta) / d^2 at its point of the plane (averaged over
// 4 x 4 points of the pixel here).
void point_light_over_a_plane(void **state) {
    scene_fixture *f = static_cast<scene_fixture *>(*state);
    const double rho = 0.6, intensity = 2.0, h = 1.0;
    const double rgb[3] = {rho, rho, rho}, i3[3] = {intensity, intensity, intensity};
    uint32_t floor_material = 0, id = 0;
    assert_ppm_ok(ppm_scene_add_diffuse_material(f->scene, rgb, &floor_material));
    const double origin[3] = {-50, -50, 0}, eu[3] = {100, 0, 0}, ev[3] = {0, 100, 0};
    assert_ppm_ok(ppm_scene_add_quad(f->scene, origin, eu, ev, &id));
    assert_ppm_ok(ppm_scene_set_geometry_material(f->scene, id, floor_material));
    const double light[3] = {0.3, 0, h};
    assert_ppm_ok(ppm_scene_add_point_light(f->scene, light, i3, nullptr));
    assert_ppm_ok(ppm_scene_commit(f->scene));
    ppm_camera camera;
    std::memset(&camera, 0, sizeof camera);
    camera.origin[2] = 2.5;
    camera.target[0] = 0.0;
    camera.up[1] = 1;
    camera.fov = 60;
    camera.width = camera.height = kSize;
    // The camera looks down -z with left = up x forward = -x and up' = forward x left = +y
    // (camera.h), so the film's local (lx, ly) meets the plane at (-2.5 lx, 2.5 ly).
    const double t = std::tan(M_PI / 6);
    double expected = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int s = 0; s < 16; ++s) {
                const double fx = x + (s % 4 + 0.5) / 4, fy = y + (s / 4 + 0.5) / 4;
                const double lx = (1 - 2 * fx / kSize) * t, ly = (1 - 2 * fy / kSize) * t;
                const double px = -lx * 2.5, py = ly * 2.5;
                const double dx = light[0] - px, dy = light[1] - py, d2 = dx * dx + dy * dy + h * h;
                expected += rho / M_PI * intensity * (h / std::sqrt(d2)) / d2 / 16;
            }
    expected /= kSize * kSize;
    for (const char *mode : kModes) {
        const double m = mean(render(f->scene, camera, mode, 16));
        std::printf("point light %s: mean %.5f, expected %.5f (ratio %.4f)\n", mode, m, expected, m / expected);
        assert_close(m, expected, 0.02 * expected);
    }
}

// Every mode converges to the image sppm makes, on a box with a glass ball under an area light.
void modes_agree_with_sppm(void **state) {
    scene_fixture *f = static_cast<scene_fixture *>(*state);
    add_box(f->scene, 0.6, 0.0, 1.0);
    const double lamp_origin[3] = {-0.3, 0.99, -0.3}, eu[3] = {0.6, 0, 0}, ev[3] = {0, 0, 0.6}, le[3] = {8, 8, 8};
    uint32_t lamp = 0, glass = 0;
    assert_ppm_ok(ppm_scene_add_quad(f->scene, lamp_origin, eu, ev, &lamp));
    assert_ppm_ok(ppm_scene_set_geometry_emission(f->scene, lamp, le));
    assert_ppm_ok(ppm_scene_add_dielectric_material(f->scene, 1.5, 1.0, &glass));
    const double c[3] = {0, -0.6, 0.3};
    add_sphere(f->scene, c, 0.4, glass);
    assert_ppm_ok(ppm_scene_commit(f->scene));
    // A radius of a few pixels: vm's one light subpath per pixel and pass leaves few photons
    // within a pixel's footprint.
    const double radius = 0.05;
    const double reference = mean(render(f->scene, box_camera(), "sppm", 32, 0, radius));
    for (const char *mode : kModes) {
        // vm's image mean rests on few photons per pass (its standard deviation at 128 passes
        // is ~ 1 %): more passes.
        const int passes = std::strcmp(mode, "vm") == 0 ? 512 : 128;
        const double m = mean(render(f->scene, box_camera(), mode, passes, 0, radius));
        std::printf("glass box %s: mean %.4f, sppm %.4f (ratio %.4f)\n", mode, m, reference, m / reference);
        assert_close(m, reference, 0.03 * reference);
    }
}

void same_bits_for_any_threads_and_split_passes(void **state) {
    scene_fixture *f = static_cast<scene_fixture *>(*state);
    add_box(f->scene, 0.5, 1.0, 1.0);
    uint32_t glass = 0;
    assert_ppm_ok(ppm_scene_add_dielectric_material(f->scene, 1.5, 1.0, &glass));
    const double c[3] = {0, 0, 0.3};
    add_sphere(f->scene, c, 0.4, glass);
    assert_ppm_ok(ppm_scene_commit(f->scene));
    assert_ppm_ok(ppm_context_set_int(f->context, "threads", 1));
    const std::vector<float> one = render(f->scene, box_camera(), "vcm", 4);
    assert_ppm_ok(ppm_context_set_int(f->context, "threads", 2));
    const std::vector<float> two = render(f->scene, box_camera(), "vcm", 4);
    assert_memory_equal(one.data(), two.data(), one.size() * sizeof(float));
    const std::vector<float> other_seed = render(f->scene, box_camera(), "vcm", 4, 1);
    assert_memory_not_equal(one.data(), other_seed.data(), one.size() * sizeof(float));

    // Passes 0 and 2 in one renderer, 1 and 3 in another, merged: the same image.
    const ppm_camera camera = box_camera();
    ppm_renderer a = nullptr, b = nullptr;
    assert_ppm_ok(ppm_renderer_create(f->scene, &camera, &a));
    assert_ppm_ok(ppm_renderer_create(f->scene, &camera, &b));
    for (ppm_renderer r : {a, b}) assert_ppm_ok(ppm_renderer_set_string(r, "mode", "vcm"));
    assert_ppm_ok(ppm_render_pass_index(a, 0));
    assert_ppm_ok(ppm_render_pass_index(a, 2));
    assert_ppm_ok(ppm_render_pass_index(b, 3));
    assert_ppm_ok(ppm_render_pass_index(b, 1));
    ppm_partial partial = nullptr;
    assert_ppm_ok(ppm_renderer_get_partial(b, &partial));
    assert_ppm_ok(ppm_renderer_merge_partial(a, partial));
    ppm_partial_release(partial);
    std::vector<float> merged(one.size());
    assert_ppm_ok(ppm_renderer_get_layer(a, "radiance", merged.data(), merged.size()));
    assert_memory_equal(one.data(), merged.data(), one.size() * sizeof(float));
    ppm_renderer_release(a);
    ppm_renderer_release(b);
}

// Through a thin lens light subpaths are not connected to the camera; the other techniques'
// weights must then still sum to one: the furnace stays at Le / (1 - albedo).
void thin_lens_furnace(void **state) {
    scene_fixture *f = static_cast<scene_fixture *>(*state);
    add_box(f->scene, 0.5, 1.0, 1.0);
    assert_ppm_ok(ppm_scene_commit(f->scene));
    ppm_camera camera = box_camera();
    camera.aperture_radius = 0.05;
    camera.focus_distance = 1;
    for (const char *mode : {"vcm", "bpt"}) {
        const double m = mean(render(f->scene, camera, mode, 8));
        std::printf("thin lens furnace %s: mean %.4f, expected 2 (ratio %.4f)\n", mode, m, m / 2);
        assert_close(m, 2.0, 0.02 * 2.0);
    }
}

// The automatic count of paths per pass (photons_per_pass 0): one light subpath per pixel up
// to the cap in the bidirectional modes, kPhotonsPerPixel photon paths per pixel within the
// bounds in the photon modes; an explicit count wins in every mode.
void automatic_paths_per_pass(void **) {
    RenderSettings s;
    assert_int_equal(s.photons_per_pass, 0);
    assert_true(s.mode == RenderSettings::Mode::Vcm);
    assert_int_equal(s.paths_per_pass(1000), 1000);
    assert_int_equal(s.paths_per_pass(std::uint64_t(1) << 24), kMaxLightSubpathsPerPass);
    s.mode = RenderSettings::Mode::Sppm;
    assert_int_equal(s.paths_per_pass(100000), kPhotonsPerPixel * 100000);
    assert_int_equal(s.paths_per_pass(10), kMinAutoPhotons);
    assert_int_equal(s.paths_per_pass(std::uint64_t(1) << 28), kMaxAutoPhotons);
    s.photons_per_pass = 777;
    assert_int_equal(s.paths_per_pass(100000), 777);
    s.mode = RenderSettings::Mode::Bpt;
    assert_int_equal(s.paths_per_pass(100000), 777);
}

// A film of more pixels than the light subpaths of a pass (RenderSettings::paths_per_pass): camera
// subpaths past the last light subpath connect to light subpath (pixel mod count), and the
// weights count the light subpaths traced. The furnace must stay at Le / (1 - albedo) on the
// rows whose camera subpaths share light subpaths too.
void more_pixels_than_light_subpaths(void **state) {
    scene_fixture *f = static_cast<scene_fixture *>(*state);
    add_box(f->scene, 0.5, 1.0, 1.0);
    assert_ppm_ok(ppm_scene_commit(f->scene));
    ppm_camera camera = box_camera();
    camera.width = 640, camera.height = 512;
    const std::uint64_t pixels = std::uint64_t(camera.width) * camera.height;
    assert_true(pixels > kMaxLightSubpathsPerPass);
    ppm_renderer r = nullptr;
    assert_ppm_ok(ppm_renderer_create(f->scene, &camera, &r));
    assert_ppm_ok(ppm_render_pass(r)); // the default mode, vcm
    int64_t emitted = 0;
    assert_ppm_ok(ppm_renderer_get_int(r, "photons_emitted", &emitted));
    assert_int_equal(emitted, kMaxLightSubpathsPerPass);
    std::vector<float> rgb(3 * pixels);
    assert_ppm_ok(ppm_renderer_get_layer(r, "radiance", rgb.data(), rgb.size()));
    ppm_renderer_release(r);
    const std::size_t shared_from = 3 * kMaxLightSubpathsPerPass;
    const double all = mean(rgb);
    const double shared = mean(std::vector<float>(rgb.begin() + shared_from, rgb.end()));
    std::printf("wide furnace: mean %.4f, of the pixels sharing light subpaths %.4f, expected 2\n", all, shared);
    assert_close(all, 2.0, 0.02 * 2.0);
    assert_close(shared, 2.0, 0.02 * 2.0);
}

} // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(mis_weights_sum_to_one),
        cmocka_unit_test(mis_weights_sum_to_one_without_merging),
        cmocka_unit_test(automatic_paths_per_pass),
        cmocka_unit_test_setup_teardown(furnace_in_every_mode, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(point_light_over_a_plane, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(modes_agree_with_sppm, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(same_bits_for_any_threads_and_split_passes, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(thin_lens_furnace, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(more_pixels_than_light_subpaths, scene_fixture_setup, scene_fixture_teardown),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
