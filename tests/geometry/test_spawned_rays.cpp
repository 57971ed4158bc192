// SPDX-License-Identifier: Apache-2.0
// Rays spawned from a patch surface (chord_slope.h): the chord slope bound of a sub-patch
// holds for chords measured on the original patch, `leaves_for_good` accepts steep rays and
// declines shallow ones, and a scene query told where its ray starts (the renderer's spawned
// rays) answers exactly as the same query without that hint, on the teapot, while the hint
// settles most of the sub-patches the rays start on.
#include "api/api_support.h"
#include "geometry/bezier.h"
#include "geometry/chord_slope.h"
#include "io/bpt_reader.h"
#include "scene/patch_geometry.h"
#include "scene/spawn.h"

#include <ppm/ppm.h>

#include "test_support.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

using namespace ppm;

namespace {

constexpr int kPerEdge = 12; // the scene's default presplit

Vec3 random_unit(test_rng &rng) {
    const double z = 2 * test_rng_uniform(&rng) - 1, phi = 2 * M_PI * test_rng_uniform(&rng);
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

ControlGrid sub_patch_grid(const BezierPatch &patch, double u0, double u1, double v0, double v1) {
    ControlGrid grid;
    sub_patch_soa(patch, IntervalMatrix::of(u0, u1), IntervalMatrix::of(v0, v1), grid.x, grid.y, grid.z);
    grid.derivative_bound = grid.bound_derivatives();
    return grid;
}

// Every teapot sub-patch (12 x 12 per patch): where a bound is proven, random chords of the
// original patch over the sub-patch's domain rise no more steeply than it allows. Most
// sub-patches get a bound (all but those at the collapsed lid apex and bottom), and a
// useful one (the renderer's shortcut needs rays steeper than the slope).
void chord_slope_bound_holds_on_teapot_sub_patches(void **) {
    const std::vector<BezierPatch> patches = read_bpt_file(PPM_TEAPOT);
    test_rng rng{7};
    int proven = 0, total = 0;
    std::vector<double> slopes;
    double worst_ratio = 0; // largest sampled chord slope / bound
    for (const BezierPatch &patch : patches)
        for (int row = 0; row < kPerEdge; ++row)
            for (int column = 0; column < kPerEdge; ++column) {
                ++total;
                const double u0 = double(column) / kPerEdge, u1 = double(column + 1) / kPerEdge;
                const double v0 = double(row) / kPerEdge, v1 = double(row + 1) / kPerEdge;
                const SurfaceDerivatives centre = evaluate_derivatives(patch, 0.5 * (u0 + u1), 0.5 * (v0 + v1));
                const Vec3 c = cross(centre.du, centre.dv);
                if (!(length(c) > 0)) continue;
                const Vec3 n = normalize(c);
                const double slope = chord_slope_bound(sub_patch_grid(patch, u0, u1, v0, v1), n);
                if (!(slope < INFINITY)) continue;
                ++proven;
                slopes.push_back(slope);
                for (int k = 0; k < 40; ++k) {
                    const double ua = u0 + (u1 - u0) * test_rng_uniform(&rng),
                                 va = v0 + (v1 - v0) * test_rng_uniform(&rng);
                    const double ub = u0 + (u1 - u0) * test_rng_uniform(&rng),
                                 vb = v0 + (v1 - v0) * test_rng_uniform(&rng);
                    if (std::max(std::fabs(ua - ub), std::fabs(va - vb)) < 1e-3 * (u1 - u0)) continue;
                    const Vec3 chord = evaluate(patch, ub, vb) - evaluate(patch, ua, va);
                    const double rise = std::fabs(dot(n, chord)), run = length(cross(chord, n));
                    // Evaluation rounds at ~1e-15 of the teapot's size (~4): far below these chords.
                    assert_true(rise <= slope * run + 1e-13);
                    if (run > 0) worst_ratio = std::max(worst_ratio, rise / run / slope);
                }
            }
    std::sort(slopes.begin(), slopes.end());
    const double median = slopes[slopes.size() / 2];
    std::printf("chord slope bound: %d of %d teapot sub-patches proven, median slope %.3f, "
                "steepest sampled chord %.2f of its bound\n",
                proven, total, median, worst_ratio);
    assert_true(proven >= total * 9 / 10);
    assert_true(median < 0.5);
}

void chord_slope_bound_of_flat_and_collapsed_patches(void **) {
    BezierPatch flat, collapsed;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            flat.p[i * 4 + j] = {j / 3.0, i / 3.0, 2.0};
            // Row 0 collapses to one point, as at the teapot's lid apex.
            collapsed.p[i * 4 + j] = {(j / 3.0) * (i / 3.0), i / 3.0, 1.0 - (i / 3.0)};
        }
    const Vec3 up{0, 0, 1};
    assert_true(chord_slope_bound(sub_patch_grid(flat, 0, 1, 0, 1), up) < 1e-12);
    // Tilted by 45 degrees about the x axis: chords along y rise by 1 per 1 of run.
    const double slope_tilted = chord_slope_bound(sub_patch_grid(flat, 0, 1, 0, 1), normalize(Vec3{0, 1, 1}));
    assert_true(slope_tilted >= 1 && slope_tilted < 1.01);
    assert_true(chord_slope_bound(sub_patch_grid(collapsed, 0, 1, 0, 1), normalize(Vec3{0, 1, 1})) == INFINITY);
}

void leaves_for_good_cases(void **) {
    const Vec3 n{0, 0, 1};
    const Vec3 offset{0, 0, 1e-8};
    assert_true(leaves_for_good(n, 0.5, offset, 1e-14, Vec3{0.3, 0.2, 1}));
    assert_true(leaves_for_good(n, 0.5, offset, 1e-14, Vec3{0, 1, 0.55}));        // rises 0.55 per 1: steeper
    assert_false(leaves_for_good(n, 0.5, offset, 1e-14, Vec3{0, 1, 0.45}));       // shallower than the bound
    assert_false(leaves_for_good(n, 0.5, offset, 1e-14, Vec3{0, 0, -1}));         // back through the surface
    assert_false(leaves_for_good(n, 0.5, offset, 2e-8, Vec3{0, 0, 1}));           // offset within its error
    assert_false(leaves_for_good(n, 0.5, Vec3{1e-8, 0, 1e-9}, 0, Vec3{0, 0, 1})); // offset along the plane
    assert_false(leaves_for_good(n, INFINITY, offset, 0, Vec3{0, 0, 1}));
    // Mirrored: both below the plane.
    assert_true(leaves_for_good(n, 0.5, offset * -1.0, 1e-14, Vec3{0.1, 0, -1}));
}

struct TeapotScene {
    ppm_context context = nullptr;
    ppm_scene scene = nullptr;
    uint32_t id = 0;
    TeapotScene() {
        assert_int_equal(ppm_context_create(&context), PPM_OK);
        assert_int_equal(ppm_scene_create(context, &scene), PPM_OK);
        assert_int_equal(ppm_scene_load_bpt(scene, PPM_TEAPOT, &id), PPM_OK);
        assert_int_equal(ppm_scene_commit(scene), PPM_OK);
    }
    ~TeapotScene() {
        ppm_scene_release(scene);
        ppm_context_release(context);
    }
    const Scene &internal() const { return *scene; }
};

bool same_hit(const ppm_hit &a, const ppm_hit &b) {
    return a.geom_id == b.geom_id && a.prim_id == b.prim_id && std::memcmp(&a.t, &b.t, sizeof a.t) == 0 &&
           std::memcmp(&a.u, &b.u, sizeof a.u) == 0 && std::memcmp(&a.v, &b.v, sizeof a.v) == 0;
}

// Rays leaving random teapot hits in random directions (steep, grazing and back into the
// surface): told where they start or not, the scene finds the same hits, bit for bit, and the
// same occlusion. The shortcut must settle the start sub-patch for most of them.
void hint_changes_no_answer_on_the_teapot(void **) {
    TeapotScene teapot;
    const Scene &scene = teapot.internal();
    const PatchGeometry &patches = dynamic_cast<const PatchGeometry &>(scene.geometry(teapot.id));
    const PatchGeometry::Data &data = patches.data();
    assert_int_equal(data.per_edge, kPerEdge);
    const Vec3 centre = scene.bounds().center();
    const double radius = 0.5 * scene.bounds().diagonal();
    test_rng rng{2026};
    int spawned = 0, settled = 0, hits = 0;
    for (int i = 0; i < 6000; ++i) {
        ppm_ray probe;
        const Vec3 from = centre + random_unit(rng) * (2 * radius);
        const Vec3 to = centre + random_unit(rng) * (0.3 * radius);
        from.store(probe.org);
        (to - from).store(probe.dir);
        probe.tnear = 0;
        probe.tfar = INFINITY;
        ppm_hit start;
        scene.intersect(probe, start);
        if (start.geom_id == PPM_INVALID_ID) continue;
        const Vec3 ng = Vec3::from(start.ng);
        for (int k = 0; k < 4; ++k) {
            Vec3 dir = random_unit(rng);
            if (k == 3) { // grazing: 1e-3 off the tangent plane
                dir = normalize(dir - ng * dot(dir, ng));
                dir = normalize(dir + ng * (test_rng_uniform(&rng) < 0.5 ? 1e-3 : -1e-3));
            }
            const ppm_ray ray = spawn_ray(start, dir);
            ppm_hit plain, hinted;
            scene.intersect(ray, plain);
            scene.intersect(ray, hinted, true, RayHints{&start});
            assert_true(same_hit(plain, hinted));
            assert_true(scene.occluded(ray) == scene.occluded(ray, RayHints{&start}));
            ++spawned;
            hits += plain.geom_id != PPM_INVALID_ID;

            // Did the shortcut apply to the sub-patch holding the start point?
            const int column = std::min(int(start.u * kPerEdge), kPerEdge - 1);
            const int row = std::min(int(start.v * kPerEdge), kPerEdge - 1);
            const PatchGeometry::SubPatch &sub =
                data.sub_patches[start.prim_id * kPerEdge * kPerEdge + row * kPerEdge + column];
            const Vec3 n{sub.normal[0], sub.normal[1], sub.normal[2]}; // as test_sub_patch passes it
            const double error = 64 * DBL_EPSILON * (*data.magnitudes)[start.prim_id];
            settled += leaves_for_good(n, sub.chord_slope, Vec3::from(ray.org) - Vec3::from(start.p), error, dir);
        }
    }
    std::printf("%d spawned rays (%d hit the teapot again): the start sub-patch was settled "
                "without a search for %d\n",
                spawned, hits, settled);
    assert_true(spawned > 10000);
    assert_true(hits > spawned / 10);
    assert_true(settled > spawned / 2);
}

} // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(chord_slope_bound_holds_on_teapot_sub_patches),
        cmocka_unit_test(chord_slope_bound_of_flat_and_collapsed_patches),
        cmocka_unit_test(leaves_for_good_cases),
        cmocka_unit_test(hint_changes_no_answer_on_the_teapot),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
