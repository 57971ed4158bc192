// SPDX-License-Identifier: Apache-2.0
// Ray / patch intersection against exact answers: a planar patch, a bicubic that is exactly
// the hyperbolic paraboloid z = x y, and a degree-elevated biquadratic (z = x^2 + y^2). The
// expected t, u, v come from solving the (at most quadratic) equations in closed form.
#include "geometry/patch_intersector.h"
#include "scene/ray_query.h"

#include <ppm/ppm.h>

#include "test_support.h"

#include <cfloat>
#include <cmath>
#include <vector>

using namespace ppm;

namespace {

// Bicubic control net whose surface is S(u, v) = (u, v, height(u, v)) with height given by
// its bicubic Bernstein coefficients h[i][j].
BezierPatch height_field(const double h[4][4]) {
    BezierPatch p;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) p.p[i * 4 + j] = {j / 3.0, i / 3.0, h[i][j]};
    return p;
}

// Coefficients of z = 0, z = x y, z = x^2 + y^2. For x y: the bilinear coefficients
// (i/3)(j/3) (linear precision). For x^2: the quadratic Bernstein coefficients (0, 0, 1)
// degree-elevated to (0, 0, 1/3, 1); x^2 + y^2 adds the two.
BezierPatch plane_patch() {
    const double h[4][4] = {};
    return height_field(h);
}
BezierPatch saddle_patch() {
    double h[4][4];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) h[i][j] = (i / 3.0) * (j / 3.0);
    return height_field(h);
}
BezierPatch bowl_patch() {
    const double square[4] = {0, 0, 1.0 / 3.0, 1};
    double h[4][4];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) h[i][j] = square[j] + square[i];
    return height_field(h);
}

// Smallest root t >= 0 of a t^2 + b t + c = 0 whose point (x, y) lies in [0, 1]^2.
struct Expected {
    bool hit;
    double t, u, v;
};
Expected nearest_root(double a, double b, double c, const Vec3 &o, const Vec3 &d) {
    std::vector<double> roots;
    if (std::fabs(a) < 1e-300) {
        if (b != 0) roots.push_back(-c / b);
    } else {
        const double disc = b * b - 4 * a * c;
        if (disc >= 0) {
            const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
            roots.push_back(q / a);
            if (q != 0) roots.push_back(c / q);
        }
    }
    Expected best{false, INFINITY, 0, 0};
    for (double t : roots) {
        const double x = o.x + t * d.x, y = o.y + t * d.y;
        if (t >= 0 && t < best.t && x >= 0 && x <= 1 && y >= 0 && y <= 1) best = {true, t, x, y};
    }
    return best;
}

// z = x y along o + t d:  dx dy t^2 + (ox dy + oy dx - dz) t + ox oy - oz = 0
Expected saddle_root(const Vec3 &o, const Vec3 &d) {
    return nearest_root(d.x * d.y, o.x * d.y + o.y * d.x - d.z, o.x * o.y - o.z, o, d);
}
// z = x^2 + y^2:  (dx^2 + dy^2) t^2 + (2 ox dx + 2 oy dy - dz) t + ox^2 + oy^2 - oz = 0
Expected bowl_root(const Vec3 &o, const Vec3 &d) {
    return nearest_root(d.x * d.x + d.y * d.y, 2 * (o.x * d.x + o.y * d.y) - d.z, o.x * o.x + o.y * o.y - o.z, o, d);
}
Expected plane_root(const Vec3 &o, const Vec3 &d) { return nearest_root(0, d.z, o.z, o, d); }

// Random rays from above and below towards random points over the unit square (some beyond
// it, to produce misses); compares against the closed form.
void check_random_rays(const BezierPatch &patch, Expected (*exact)(const Vec3 &, const Vec3 &), uint64_t seed) {
    test_rng rng{seed};
    int hits = 0, misses = 0;
    for (int k = 0; k < 3000; ++k) {
        const Vec3 target{-0.2 + 1.4 * test_rng_uniform(&rng), -0.2 + 1.4 * test_rng_uniform(&rng),
                          2 * test_rng_uniform(&rng) - 0.5};
        const Vec3 o{4 * test_rng_uniform(&rng) - 1.5, 4 * test_rng_uniform(&rng) - 1.5,
                     (k % 2 ? 3.0 : -3.0) * (0.5 + test_rng_uniform(&rng))};
        const Vec3 d = (target - o) * (0.5 + test_rng_uniform(&rng));
        const Expected e = exact(o, d);
        // Points within a hair of the domain edge are ambiguous at any tolerance; skip them.
        if (e.hit && (std::min({e.u, e.v, 1 - e.u, 1 - e.v}) < 1e-9)) continue;
        PatchRootQuery query;
        query.tolerance = 1e-12;
        PatchRoot root;
        const bool found = intersect_patch(patch, RayFrame::from_ray(o, d), query, root);
        assert_int_equal(found, e.hit);
        if (!found) {
            ++misses;
            continue;
        }
        ++hits;
        const double scale = std::max(1.0, e.t);
        assert_close(root.t, e.t, 1e-12 * scale);
        assert_close(root.a, e.u, 1e-10);
        assert_close(root.b, e.v, 1e-10);
    }
    print_message("%d hits and %d misses agree with the closed form\n", hits, misses);
    assert_true(hits > 500 && misses > 100);
}

void planar_patch_matches_closed_form(void **) { check_random_rays(plane_patch(), plane_root, 11); }
void hyperbolic_paraboloid_matches_closed_form(void **) { check_random_rays(saddle_patch(), saddle_root, 12); }
void elevated_quadratic_matches_closed_form(void **) { check_random_rays(bowl_patch(), bowl_root, 13); }

// Rays at 1e-3 .. 1e-9 rad to the plane still hit at the exact point. A grazing hit is
// ill-conditioned: a rounding-sized change of the ray (eps) moves it by eps / sin(angle)
// along the ray, so that is the accuracy any double-precision method can promise.
void grazing_rays_hit_the_plane(void **) {
    const BezierPatch patch = plane_patch();
    for (double angle : {1e-3, 1e-5, 1e-7, 1e-9}) {
        const Vec3 target{0.4, 0.55, 0};
        const Vec3 d{std::cos(angle) * 0.6, std::cos(angle) * 0.8, -std::sin(angle)};
        const Vec3 o = target - d * 0.5; // starts over the patch, so the hit is inside it
        PatchRootQuery query;
        query.tolerance = 1e-12;
        PatchRoot root;
        assert_true(intersect_patch(patch, RayFrame::from_ray(o, d), query, root));
        const Expected e = plane_root(o, d);
        const double conditioning = 4 * DBL_EPSILON / std::sin(angle);
        assert_close(root.t, e.t, 1e-12 + conditioning);
        assert_close(root.a, e.u, 1e-12 + conditioning);
        assert_close(root.b, e.v, 1e-12 + conditioning);
    }
}

// A ray that enters the bowl from above hits twice; the nearer root wins, tnear and tfar
// select the other one, and any_hit finds one of them.
void nearest_of_two_roots_and_ray_interval(void **) {
    const BezierPatch patch = bowl_patch();
    const Vec3 o{-0.5, 0.5, 0.6}, d{1, 0, 0}; // z = x^2 + 0.25 = 0.6 at x = +-0.5916
    const double x = std::sqrt(0.35);
    PatchRootQuery query;
    query.tolerance = 1e-12;
    PatchRoot root;
    assert_true(intersect_patch(patch, RayFrame::from_ray(o, d), query, root));
    assert_close(root.t, 0.5 + x, 1e-12);
    query.tfar = 0.5 + x - 1e-6;
    assert_false(intersect_patch(patch, RayFrame::from_ray(o, d), query, root));
    query.tfar = INFINITY;
    query.any_hit = true;
    assert_true(intersect_patch(patch, RayFrame::from_ray(o, d), query, root));

    // The saddle z = x y is crossed twice by the line x = y, z = 0.2 (x^2 = 0.2)? No: along
    // (t, t, 0.2) the surface height t^2 crosses 0.2 once in [0, 1]; a vertical ray crosses once.
    const Vec3 o2{0.3, 0.7, 5}, d2{0, 0, -1};
    query.any_hit = false;
    assert_true(intersect_patch(saddle_patch(), RayFrame::from_ray(o2, d2), query, root));
    assert_close(root.t, 5 - 0.21, 1e-12);
}

// The same through the public API: a scene with the saddle patch, default tolerance.
void scene_reports_exact_hit_and_normal(void **) {
    const BezierPatch patch = saddle_patch();
    double control[48];
    for (int k = 0; k < 16; ++k) patch.p[k].store(control + 3 * k);
    ppm_context context;
    ppm_scene scene;
    assert_int_equal(ppm_context_create(&context), PPM_OK);
    assert_int_equal(ppm_scene_create(context, &scene), PPM_OK);
    uint32_t id = 99;
    assert_int_equal(ppm_scene_add_bezier_patches(scene, control, 1, &id), PPM_OK);
    assert_int_equal(id, 0);
    assert_int_equal(ppm_scene_commit(scene), PPM_OK);
    const ppm_ray ray = {{0.25, 0.8, 3}, 0, {0, 0, -2}, INFINITY};
    ppm_hit hit;
    assert_int_equal(ppm_scene_intersect(scene, &ray, 1, &hit), PPM_OK);
    assert_close(hit.t, (3 - 0.2) / 2, 1e-15);
    assert_close(hit.u, 0.25, 1e-12);
    assert_close(hit.v, 0.8, 1e-12);
    const Vec3 n = normalize(Vec3{-0.8, -0.25, 1});
    assert_close(hit.ng[0], n.x, 1e-12);
    assert_close(hit.ng[1], n.y, 1e-12);
    assert_close(hit.ng[2], n.z, 1e-12);
    assert_int_equal(hit.geom_id, 0);
    assert_int_equal(hit.prim_id, 0);
    ppm_scene_release(scene);
    ppm_context_release(context);
}

// Embree's far limit is rounded up with next_float_up, which must agree with std::nextafter:
// one float too low and a box at the hit could be culled.
void next_float_up_matches_nextafter(void **) {
    const float specials[] = {0.0f,     -0.0f, FLT_MIN, -FLT_MIN, FLT_TRUE_MIN, -FLT_TRUE_MIN, FLT_MAX,
                              -FLT_MAX, 1.0f,  -1.0f,   INFINITY, -INFINITY,    3.5e-20f,      -7.25e12f};
    for (float f : specials) {
        const float expected = std::nextafter(f, INFINITY), actual = ppm::next_float_up(f);
        assert_memory_equal(&expected, &actual, sizeof(float));
    }
    assert_true(std::isnan(ppm::next_float_up(NAN)));
    test_rng rng{41};
    for (int i = 0; i < 100000; ++i) {
        const float f = static_cast<float>((test_rng_uniform(&rng) - 0.5) *
                                           std::ldexp(1.0, static_cast<int>(test_rng_uniform(&rng) * 200) - 100));
        assert_true(ppm::next_float_up(f) == std::nextafter(f, INFINITY));
    }
}

} // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(planar_patch_matches_closed_form),
        cmocka_unit_test(hyperbolic_paraboloid_matches_closed_form),
        cmocka_unit_test(elevated_quadratic_matches_closed_form),
        cmocka_unit_test(grazing_rays_hit_the_plane),
        cmocka_unit_test(nearest_of_two_roots_and_ray_interval),
        cmocka_unit_test(scene_reports_exact_hit_and_normal),
        cmocka_unit_test(next_float_up_matches_nextafter),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
