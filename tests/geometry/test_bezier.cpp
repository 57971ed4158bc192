// SPDX-License-Identifier: Apache-2.0
// Bezier patch math against analytic answers: Bernstein basis, evaluation, derivatives,
// De Casteljau splitting, normals (including the limit normal at collapsed edges).
#include "geometry/bezier.h"
#include "io/bpt_reader.h"

#include "test_support.h"

#include <cmath>

using namespace ppm;

namespace {

// Control net of the map (u, v) -> a + u b + v c (+ twist u v w): bilinear maps are
// reproduced exactly by a bicubic with control points at (j/3, i/3) (linear precision).
BezierPatch bilinear_patch(Vec3 a, Vec3 b, Vec3 c, Vec3 w) {
    BezierPatch p;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            const double u = j / 3.0, v = i / 3.0;
            p.p[i * 4 + j] = a + b * u + c * v + w * (u * v);
        }
    return p;
}

// A curved, asymmetric test patch with no special structure.
BezierPatch wavy_patch() {
    BezierPatch p;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) p.p[i * 4 + j] = {j + 0.1 * i * i, i - 0.2 * j, std::sin(1.0 + i * 1.7 + j * 0.9)};
    return p;
}

void assert_vec_close(const Vec3 &a, const Vec3 &b, double tolerance) {
    assert_close(a.x, b.x, tolerance);
    assert_close(a.y, b.y, tolerance);
    assert_close(a.z, b.z, tolerance);
}

void bernstein_is_a_partition_of_unity_with_zero_sum_derivative(void **) {
    for (double t = 0; t <= 1.0; t += 0.0625) {
        double b[4], d[4];
        bernstein3(t, b);
        bernstein3_derivative(t, d);
        assert_close(b[0] + b[1] + b[2] + b[3], 1.0, 1e-15);
        assert_close(d[0] + d[1] + d[2] + d[3], 0.0, 1e-14);
        // B_1 = 3 t (1-t)^2 analytically
        assert_close(b[1], 3 * t * (1 - t) * (1 - t), 1e-15);
        assert_close(d[2], 6 * t - 9 * t * t, 1e-14);
    }
}

void evaluation_reproduces_bilinear_maps(void **) {
    const Vec3 a{1, 2, 3}, b{0.5, -1, 2}, c{2, 0.25, -1}, w{0.3, 0.7, -0.2};
    const BezierPatch p = bilinear_patch(a, b, c, w);
    test_rng rng{1};
    for (int k = 0; k < 200; ++k) {
        const double u = test_rng_uniform(&rng), v = test_rng_uniform(&rng);
        const SurfaceDerivatives d = evaluate_derivatives(p, u, v);
        assert_vec_close(d.p, a + b * u + c * v + w * (u * v), 1e-14);
        assert_vec_close(d.du, b + w * v, 1e-13);
        assert_vec_close(d.dv, c + w * u, 1e-13);
        assert_vec_close(mixed_derivative(p, u, v), w, 1e-13);
        const SecondDerivatives second = second_derivatives(p, u, v);
        assert_vec_close(second.uu, {0, 0, 0}, 1e-12);
        assert_vec_close(second.uv, w, 1e-13);
        assert_vec_close(second.vv, {0, 0, 0}, 1e-12);
    }
}

void corners_interpolate_control_points(void **) {
    const BezierPatch p = wavy_patch();
    assert_vec_close(evaluate(p, 0, 0), p.at(0, 0), 0);
    assert_vec_close(evaluate(p, 1, 0), p.at(0, 3), 0);
    assert_vec_close(evaluate(p, 0, 1), p.at(3, 0), 0);
    assert_vec_close(evaluate(p, 1, 1), p.at(3, 3), 0);
    // Corner tangents: dS/du(0,0) = 3 (P01 - P00)
    assert_vec_close(evaluate_derivatives(p, 0, 0).du, (p.at(0, 1) - p.at(0, 0)) * 3.0, 1e-14);
    assert_vec_close(evaluate_derivatives(p, 0, 0).dv, (p.at(1, 0) - p.at(0, 0)) * 3.0, 1e-14);
}

void derivatives_match_central_differences(void **) {
    const BezierPatch p = wavy_patch();
    const double h = 1e-5;
    test_rng rng{2};
    for (int k = 0; k < 100; ++k) {
        const double u = 0.01 + 0.98 * test_rng_uniform(&rng), v = 0.01 + 0.98 * test_rng_uniform(&rng);
        const SurfaceDerivatives d = evaluate_derivatives(p, u, v);
        const Vec3 du = (evaluate(p, u + h, v) - evaluate(p, u - h, v)) / (2 * h);
        const Vec3 dv = (evaluate(p, u, v + h) - evaluate(p, u, v - h)) / (2 * h);
        assert_vec_close(d.du, du, 1e-8);
        assert_vec_close(d.dv, dv, 1e-8);
        const Vec3 duu = (evaluate_derivatives(p, u + h, v).du - evaluate_derivatives(p, u - h, v).du) / (2 * h);
        const Vec3 dvv = (evaluate_derivatives(p, u, v + h).dv - evaluate_derivatives(p, u, v - h).dv) / (2 * h);
        assert_vec_close(second_derivatives(p, u, v).uu, duu, 1e-7);
        assert_vec_close(second_derivatives(p, u, v).vv, dvv, 1e-7);
    }
}

void split_halves_reproduce_the_parent(void **) {
    const BezierPatch p = wavy_patch();
    test_rng rng{3};
    for (int k = 0; k < 50; ++k) {
        const double t = 0.05 + 0.9 * test_rng_uniform(&rng);
        BezierPatch left, right, below, above;
        split_u(p, t, left, right);
        split_v(p, t, below, above);
        const double s = test_rng_uniform(&rng), v = test_rng_uniform(&rng);
        assert_vec_close(evaluate(left, s, v), evaluate(p, t * s, v), 1e-13);
        assert_vec_close(evaluate(right, s, v), evaluate(p, t + (1 - t) * s, v), 1e-13);
        assert_vec_close(evaluate(below, v, s), evaluate(p, v, t * s), 1e-13);
        assert_vec_close(evaluate(above, v, s), evaluate(p, v, t + (1 - t) * s), 1e-13);
    }
}

void sub_patch_reproduces_its_domain(void **) {
    const BezierPatch p = wavy_patch();
    const double u0 = 0.2, u1 = 0.65, v0 = 0.4, v1 = 0.9;
    const BezierPatch q = sub_patch(p, u0, u1, v0, v1);
    test_rng rng{4};
    for (int k = 0; k < 100; ++k) {
        const double a = test_rng_uniform(&rng), b = test_rng_uniform(&rng);
        assert_vec_close(evaluate(q, a, b), evaluate(p, u0 + a * (u1 - u0), v0 + b * (v1 - v0)), 1e-13);
    }
    // Full-domain sub-patch is the patch itself.
    const BezierPatch same = sub_patch(p, 0, 1, 0, 1);
    for (int k = 0; k < 16; ++k) assert_vec_close(same.p[k], p.p[k], 0);
}

// The interval matrices cut the same sub-patch as De Casteljau, to rounding; over [0, 1]
// they are the identity.
void interval_matrices_cut_the_same_sub_patch(void **) {
    const BezierPatch p = wavy_patch();
    const double u0 = 0.2, u1 = 0.65, v0 = 0.4, v1 = 0.9;
    const BezierPatch q = sub_patch(p, u0, u1, v0, v1);
    double x[16], y[16], z[16];
    sub_patch_soa(p, IntervalMatrix::of(u0, u1), IntervalMatrix::of(v0, v1), x, y, z);
    for (int k = 0; k < 16; ++k) assert_vec_close(Vec3{x[k], y[k], z[k]}, q.p[k], 1e-14);
    sub_patch_soa(p, IntervalMatrix::of(0, 1), IntervalMatrix::of(0, 1), x, y, z);
    for (int k = 0; k < 16; ++k) assert_vec_close(Vec3{x[k], y[k], z[k]}, p.p[k], 0);
    // Each row of weights sums to one (affine invariance).
    const IntervalMatrix m = IntervalMatrix::of(0.25, 0.5);
    for (const auto &row : m.w) assert_true(std::fabs(row[0] + row[1] + row[2] + row[3] - 1) < 1e-15);
}

void control_hull_bounds_the_surface(void **) {
    const BezierPatch p = wavy_patch();
    const Box3 box = control_bounds(p);
    test_rng rng{5};
    for (int k = 0; k < 500; ++k) {
        const Vec3 s = evaluate(p, test_rng_uniform(&rng), test_rng_uniform(&rng));
        assert_true(s.x >= box.lower.x && s.x <= box.upper.x);
        assert_true(s.y >= box.lower.y && s.y <= box.upper.y);
        assert_true(s.z >= box.lower.z && s.z <= box.upper.z);
    }
}

void normal_of_hyperbolic_paraboloid_is_analytic(void **) {
    // z = x y over [0,1]^2: normal direction (-y, -x, 1).
    const BezierPatch p = bilinear_patch({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
    test_rng rng{6};
    for (int k = 0; k < 100; ++k) {
        const double u = test_rng_uniform(&rng), v = test_rng_uniform(&rng);
        assert_vec_close(geometric_normal(p, u, v), normalize(Vec3{-v, -u, 1}), 1e-14);
    }
}

// A dome whose v = 0 row collapses to its apex, like the teapot lid: the limit normal at the
// apex is the axis, and it is the limit of the normals nearby.
void collapsed_edge_gives_the_limit_normal(void **) {
    BezierPatch dome;
    const double radius[4] = {0, 0.6, 0.9, 1.0}, height[4] = {1, 1, 0.6, 0};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            const double angle = 0.5 * M_PI * j / 3.0;
            dome.p[i * 4 + j] = {radius[i] * std::cos(angle), radius[i] * std::sin(angle), height[i]};
        }
    assert_true(length(evaluate_derivatives(dome, 0.3, 0).du) < 1e-14); // collapsed: dS/du = 0
    for (double u : {0.0, 0.3, 0.5, 1.0}) {
        const Vec3 n = geometric_normal(dome, u, 0);
        assert_true(is_finite(n));
        assert_close(std::fabs(n.z), 1.0, 1e-12);
        assert_vec_close(n, geometric_normal(dome, u, 1e-7), 1e-6);
    }
}

void teapot_apex_and_bottom_normals_are_vertical(void **) {
    const std::vector<BezierPatch> teapot = read_bpt_file(PPM_TEAPOT);
    assert_int_equal(teapot.size(), 32);
    for (int index : {20, 21, 22, 23, 28, 29, 30, 31})
        for (double u : {0.0, 0.25, 0.5, 0.75, 1.0}) {
            const Vec3 n = geometric_normal(teapot[index], u, 0);
            assert_true(is_finite(n));
            assert_close(std::fabs(n.z), 1.0, 1e-9);
        }
}

void fully_degenerate_patch_has_no_normal(void **) {
    BezierPatch point;
    for (Vec3 &p : point.p) p = {1, 2, 3};
    const Vec3 n = geometric_normal(point, 0.5, 0.5);
    assert_true(n.x == 0 && n.y == 0 && n.z == 0);
}

} // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(bernstein_is_a_partition_of_unity_with_zero_sum_derivative),
        cmocka_unit_test(evaluation_reproduces_bilinear_maps),
        cmocka_unit_test(corners_interpolate_control_points),
        cmocka_unit_test(derivatives_match_central_differences),
        cmocka_unit_test(split_halves_reproduce_the_parent),
        cmocka_unit_test(sub_patch_reproduces_its_domain),
        cmocka_unit_test(interval_matrices_cut_the_same_sub_patch),
        cmocka_unit_test(control_hull_bounds_the_surface),
        cmocka_unit_test(normal_of_hyperbolic_paraboloid_is_analytic),
        cmocka_unit_test(collapsed_edge_gives_the_limit_normal),
        cmocka_unit_test(teapot_apex_and_bottom_normals_are_vertical),
        cmocka_unit_test(fully_degenerate_patch_has_no_normal),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
