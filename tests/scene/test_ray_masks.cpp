// SPDX-License-Identifier: Apache-2.0
// Embree masks (Scene::ray_mask): a ray leaving a quad, and a shadow ray running to an area
// light, skip that geometry before any callback. The masks must change no answer: a stack of
// 40 parallel quads (more than Embree's 32 mask bits, so the last ones are skipped by their
// callback instead) gives every ray leaving one of them the next quad it crosses, with and
// without the hint, and a shadow ray is blocked by every other light and blocker in its way,
// never by the light it runs to.
#include "api/api_support.h"
#include "scene/spawn.h"

#include <ppm/ppm.h>

#include "test_support.h"

#include <cmath>
#include <cstring>

using namespace ppm;

namespace {

constexpr int kLayers = 40;          // quads z = 0 .. 39, each [-5, 5]^2
constexpr double kLightZ = 45;       // the light [-2, 2]^2 facing down
constexpr double kSecondLightZ = 43; // a second light [0, 2] x [-2, 2] facing down
constexpr double kBlockerZ = 42;     // a plain quad [-2, 0] x [0, 2]

struct StackScene {
    ppm_context context = nullptr;
    ppm_scene scene = nullptr;
    uint32_t light = 0, second_light = 0;
    StackScene() {
        assert_int_equal(ppm_context_create(&context), PPM_OK);
        assert_int_equal(ppm_scene_create(context, &scene), PPM_OK);
        uint32_t id = 0;
        for (int k = 0; k < kLayers; ++k) {
            const double origin[3] = {-5, -5, double(k)}, eu[3] = {10, 0, 0}, ev[3] = {0, 10, 0};
            assert_int_equal(ppm_scene_add_quad(scene, origin, eu, ev, &id), PPM_OK);
        }
        const double radiance[3] = {1, 1, 1};
        const double lo[3] = {-2, -2, kLightZ}, ly[3] = {0, 4, 0}, lx[3] = {4, 0, 0};
        assert_int_equal(ppm_scene_add_quad(scene, lo, ly, lx, &light), PPM_OK); // normal -z
        assert_int_equal(ppm_scene_set_geometry_emission(scene, light, radiance), PPM_OK);
        const double so[3] = {0, -2, kSecondLightZ}, sy[3] = {0, 4, 0}, sx[3] = {2, 0, 0};
        assert_int_equal(ppm_scene_add_quad(scene, so, sy, sx, &second_light), PPM_OK);
        assert_int_equal(ppm_scene_set_geometry_emission(scene, second_light, radiance), PPM_OK);
        const double bo[3] = {-2, 0, kBlockerZ}, bx[3] = {2, 0, 0}, by[3] = {0, 2, 0};
        assert_int_equal(ppm_scene_add_quad(scene, bo, bx, by, &id), PPM_OK);
        assert_int_equal(ppm_scene_commit(scene), PPM_OK);
    }
    ~StackScene() {
        ppm_scene_release(scene);
        ppm_context_release(context);
    }
    const Scene &internal() const { return *scene; }
};

bool identical(const ppm_hit &a, const ppm_hit &b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The hit on layer k at (x, y), found by a ray from just above it.
ppm_hit hit_on_layer(const Scene &scene, int k, double x, double y) {
    ppm_ray probe{{x, y, k + 0.5}, 0, {0, 0, -1}, INFINITY};
    ppm_hit hit;
    scene.intersect(probe, hit);
    assert_int_equal(hit.geom_id, uint32_t(k));
    return hit;
}

// From every layer, rays up and down at random slopes: the next layer along the ray, or
// the light, blocker or nothing past the top layer, as the plain ray (offset origin only)
// finds it; the hinted ray must agree, and where the crossing of the next layer lies on it,
// that layer must be the answer.
void rays_leaving_quads_meet_the_next_layer(void **) {
    StackScene s;
    const Scene &scene = s.internal();
    test_rng rng{41};
    int checked = 0;
    for (int k = 0; k < kLayers; ++k)
        for (int i = 0; i < 50; ++i) {
            const double x = 8 * test_rng_uniform(&rng) - 4, y = 8 * test_rng_uniform(&rng) - 4;
            const ppm_hit start = hit_on_layer(scene, k, x, y);
            const double up = i % 2 == 0 ? 1.0 : -1.0;
            const Vec3 dir = normalize(
                Vec3{test_rng_uniform(&rng) - 0.5, test_rng_uniform(&rng) - 0.5, up * (0.05 + test_rng_uniform(&rng))});
            const ppm_ray ray = spawn_ray(start, dir);
            ppm_hit plain, hinted;
            scene.intersect(ray, plain);
            scene.intersect(ray, hinted, true, RayHints{&start});
            assert_true(identical(plain, hinted));
            assert_true(scene.occluded(ray) == scene.occluded(ray, RayHints{&start}));
            const int next = k + int(up);
            if (next < 0 || next >= kLayers) continue;
            const double t = (next - start.p[2]) / dir.z;
            const double cx = start.p[0] + t * dir.x, cy = start.p[1] + t * dir.y;
            if (std::fabs(cx) > 4.99 || std::fabs(cy) > 4.99) continue; // off the stack's edge
            assert_int_equal(hinted.geom_id, uint32_t(next));
            assert_true(std::fabs(hinted.p[2] - next) < 1e-9);
            ++checked;
        }
    assert_true(checked > kLayers * 20);
}

// Shadow rays from the top layer to points on the light, stopping short of them as the
// renderer's do: blocked exactly when they cross the second light or the blocker, whether or
// not they name the light they run to.
void shadow_rays_skip_only_their_light(void **) {
    StackScene s;
    const Scene &scene = s.internal();
    test_rng rng{43};
    int blocked = 0, free = 0;
    for (int i = 0; i < 2000; ++i) {
        const double x = 8 * test_rng_uniform(&rng) - 4, y = 8 * test_rng_uniform(&rng) - 4;
        const ppm_hit start = hit_on_layer(scene, kLayers - 1, x, y);
        const Vec3 target{4 * test_rng_uniform(&rng) - 2, 4 * test_rng_uniform(&rng) - 2, kLightZ};
        const Vec3 to = target - Vec3::from(start.p);
        const double distance = length(to);
        const Vec3 dir = to / distance;
        const ppm_ray ray = spawn_ray(start, dir, distance * (1 - 1e-7) - 8 * start.p_error);
        // Where the ray crosses the second light's and the blocker's planes.
        auto crossing = [&](double z, double &cx, double &cy) {
            const double t = (z - start.p[2]) / dir.z;
            cx = start.p[0] + t * dir.x;
            cy = start.p[1] + t * dir.y;
        };
        double lx, ly, bx, by;
        crossing(kSecondLightZ, lx, ly);
        crossing(kBlockerZ, bx, by);
        const double margin = 1e-6;
        const bool through_second = lx > margin && lx < 2 - margin && std::fabs(ly) < 2 - margin;
        const bool through_blocker = bx > -2 + margin && bx < -margin && by > margin && by < 2 - margin;
        const bool near_edge = std::fabs(lx) < margin || std::fabs(lx - 2) < margin ||
                               std::fabs(std::fabs(ly) - 2) < margin || std::fabs(bx + 2) < margin ||
                               std::fabs(bx) < margin || std::fabs(by) < margin || std::fabs(by - 2) < margin;
        if (near_edge) continue;
        const bool expected = through_second || through_blocker;
        assert_true(scene.occluded(ray, RayHints{&start, s.light}) == expected);
        assert_true(scene.occluded(ray, RayHints{&start}) == expected);
        assert_true(scene.occluded(ray, RayHints{nullptr, s.light}) == expected);
        // Naming the other light hides that one instead (not a call the renderer makes: it
        // shows the skip is per geometry).
        assert_true(scene.occluded(ray, RayHints{&start, s.second_light}) == through_blocker);
        (expected ? blocked : free)++;
    }
    assert_true(blocked > 200);
    assert_true(free > 200);
}

} // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(rays_leaving_quads_meet_the_next_layer),
        cmocka_unit_test(shadow_rays_skip_only_their_light),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
