/* SPDX-License-Identifier: Apache-2.0 */
/* Analytic answers through the public API: spheres, quads, triangle meshes and Bezier
 * patches, with transforms, materials, batches and ppm_hit_spawn_ray. */
#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef scene_fixture fixture;

static ppm_ray make_ray(double ox, double oy, double oz, double dx, double dy, double dz) {
    ppm_ray ray = {{ox, oy, oz}, 0, {dx, dy, dz}, INFINITY};
    return ray;
}

static ppm_hit trace(ppm_scene scene, ppm_ray ray) {
    ppm_hit hit;
    assert_ppm_ok(ppm_scene_intersect(scene, &ray, 1, &hit));
    uint8_t occluded = 7;
    assert_ppm_ok(ppm_scene_occluded(scene, &ray, 1, &occluded));
    assert_int_equal(occluded, hit.geom_id != PPM_INVALID_ID);
    return hit;
}

static void assert_miss(ppm_hit hit) {
    if (hit.geom_id != PPM_INVALID_ID) fail_msg("expected a miss, got geometry %u at t = %.17g", hit.geom_id, hit.t);
    assert_true(isinf(hit.t));
}

static void assert_vector_close(const double a[3], double x, double y, double z, double tolerance) {
    assert_close(a[0], x, tolerance);
    assert_close(a[1], y, tolerance);
    assert_close(a[2], z, tolerance);
}

static uint32_t add_sphere(ppm_scene scene, double x, double y, double z, double radius) {
    const double center[3] = {x, y, z};
    uint32_t id = PPM_INVALID_ID;
    assert_ppm_ok(ppm_scene_add_sphere(scene, center, radius, &id));
    return id;
}

static uint32_t add_quad(ppm_scene scene, const double o[3], const double eu[3], const double ev[3]) {
    uint32_t id = PPM_INVALID_ID;
    assert_ppm_ok(ppm_scene_add_quad(scene, o, eu, ev, &id));
    return id;
}

/* Quad [x0, x0 + w] x [y0, y0 + h] in the plane z. */
static uint32_t add_xy_quad(ppm_scene scene, double x0, double y0, double z, double w, double h) {
    const double o[3] = {x0, y0, z}, eu[3] = {w, 0, 0}, ev[3] = {0, h, 0};
    return add_quad(scene, o, eu, ev);
}

/* Flat patch S(u, v) = (x0 + u, y0 + v, z) (linear precision of the Bernstein basis). */
static void flat_patch(double points[48], double x0, double y0, double z) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double *p = points + 3 * (4 * i + j);
            p[0] = x0 + j / 3.0;
            p[1] = y0 + i / 3.0;
            p[2] = z;
        }
}

/* The saddle S(u, v) = (u, v, u v) over [0, 1]^2. */
static void saddle_patch(double points[48]) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double *p = points + 3 * (4 * i + j);
            p[0] = j / 3.0;
            p[1] = i / 3.0;
            p[2] = (i / 3.0) * (j / 3.0);
        }
}

static void commit(ppm_scene scene) { assert_ppm_ok(ppm_scene_commit(scene)); }

/* Spheres ---------------------------------------------------------------------------------- */

static void test_sphere_ray_through_center(void **state) {
    fixture *f = *state;
    const double c[3] = {1000, -2000, 500}, r = 3;
    add_sphere(f->scene, c[0], c[1], c[2], r);
    commit(f->scene);
    /* from c + 100 * (3, 4, 12) / 13 towards the centre: t = 100 - r */
    const double n[3] = {3 / 13.0, 4 / 13.0, 12 / 13.0};
    const ppm_hit hit =
        trace(f->scene, make_ray(c[0] + 100 * n[0], c[1] + 100 * n[1], c[2] + 100 * n[2], -n[0], -n[1], -n[2]));
    assert_int_equal(hit.geom_id, 0);
    assert_close(hit.t, 97.0, 97.0 * 1e-12);
    assert_vector_close(hit.p, c[0] + r * n[0], c[1] + r * n[1], c[2] + r * n[2], 1e-9);
    assert_vector_close(hit.ng, n[0], n[1], n[2], 1e-12);
    assert_vector_close(hit.ns, n[0], n[1], n[2], 1e-12);
}

static void test_sphere_t_is_in_units_of_dir_length(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(0, 0, 5, 0, 0, -4)); /* |dir| = 4: t = 4 / 4 */
    assert_close(hit.t, 1.0, 1e-15);
    assert_vector_close(hit.p, 0, 0, 1, 1e-15);
}

static void test_sphere_exact_distance_on_axis(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(5, 0, 0, -1, 0, 0));
    assert_true(hit.t == 4.0);
    assert_int_equal(hit.prim_id, 0);
    assert_true(hit.p_error > 0 && hit.p_error < 1e-6);
}

static void test_sphere_near_tangent_ray_hits(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    commit(f->scene);
    const double y = 1 - 1e-6;
    const ppm_hit hit = trace(f->scene, make_ray(-5, y, 0, 1, 0, 0));
    assert_int_equal(hit.geom_id, 0);
    assert_close(hit.t, 5 - sqrt((1 - y) * (1 + y)), 1e-9);
    assert_close(hit.ng[1], y, 1e-9);
}

static void test_sphere_near_tangent_ray_misses(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    commit(f->scene);
    assert_miss(trace(f->scene, make_ray(-5, 1 + 1e-6, 0, 1, 0, 0)));
    assert_miss(trace(f->scene, make_ray(-5, 0, -(1 + 1e-6), 1, 0, 0)));
}

static void test_sphere_ray_from_inside_hits_far_side(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(0.1, 0.2, 0.3, 1, 0, 0));
    const double x = sqrt(1 - 0.2 * 0.2 - 0.3 * 0.3);
    assert_int_equal(hit.geom_id, 0);
    assert_close(hit.t, x - 0.1, 1e-12);
    assert_vector_close(hit.p, x, 0.2, 0.3, 1e-12);
    assert_vector_close(hit.ng, x, 0.2, 0.3, 1e-12); /* outward, not flipped towards the ray */
}

/* (u, v) of the hit of a ray shot at the unit sphere's point in direction (theta, phi). */
static void check_sphere_uv(ppm_scene scene, double theta, double phi, double u, double v) {
    const double n[3] = {sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta)};
    const ppm_hit hit = trace(scene, make_ray(5 * n[0], 5 * n[1], 5 * n[2], -n[0], -n[1], -n[2]));
    assert_int_equal(hit.geom_id, 0);
    assert_close(hit.u, u, 1e-12);
    assert_close(hit.v, v, 1e-12);
}

static void test_sphere_uv_on_equator(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    commit(f->scene);
    assert_close(trace(f->scene, make_ray(5, 0, 0, -1, 0, 0)).u, 0.0, 0.0); /* +x: u = 0 exactly */
    assert_close(trace(f->scene, make_ray(5, 0, 0, -1, 0, 0)).v, 0.5, 1e-15);
    check_sphere_uv(f->scene, M_PI / 2, M_PI / 2, 0.25, 0.5);     /* +y */
    check_sphere_uv(f->scene, M_PI / 2, M_PI, 0.5, 0.5);          /* -x */
    check_sphere_uv(f->scene, M_PI / 2, 3 * M_PI / 2, 0.75, 0.5); /* -y */
}

static void test_sphere_uv_poles_and_general_point(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    commit(f->scene);
    assert_close(trace(f->scene, make_ray(0, 0, 5, 0, 0, -1)).v, 0.0, 1e-15); /* +z */
    assert_close(trace(f->scene, make_ray(0, 0, -5, 0, 0, 1)).v, 1.0, 1e-15); /* -z */
    check_sphere_uv(f->scene, M_PI / 3, M_PI / 6, 1.0 / 12, 1.0 / 3);
    check_sphere_uv(f->scene, 2 * M_PI / 3, 5 * M_PI / 4, 5.0 / 8, 2.0 / 3);
}

static void test_sphere_uv_of_offset_sphere(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 10, -3, 2, 2);
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(10, 5, 2, 0, -1, 0)); /* +y side */
    assert_close(hit.t, 6.0, 1e-12);
    assert_close(hit.u, 0.25, 1e-12);
    assert_close(hit.v, 0.5, 1e-12);
}

static void test_sphere_tnear_tfar(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    commit(f->scene);
    ppm_ray ray = make_ray(-5, 0, 0, 1, 0, 0); /* roots t = 4 and t = 6 */
    ray.tnear = 4.5;
    assert_close(trace(f->scene, ray).t, 6.0, 1e-12);
    ray.tnear = 6.1;
    assert_miss(trace(f->scene, ray));
    ray.tnear = 0;
    ray.tfar = 3.9;
    assert_miss(trace(f->scene, ray));
    ray.tfar = 4.0; /* [tnear, tfar] is closed */
    assert_true(trace(f->scene, ray).t == 4.0);
    ray.tnear = 4.0;
    ray.tfar = 5.9;
    assert_true(trace(f->scene, ray).t == 4.0);
}

/* Quads ------------------------------------------------------------------------------------ */

static const double quad_o[3] = {1, 1, 1}, quad_u[3] = {2, 0, 0}, quad_v[3] = {0, 3, 0};

static void test_quad_hit_inside(void **state) {
    fixture *f = *state;
    add_quad(f->scene, quad_o, quad_u, quad_v);
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(1.5, 2.5, 5, 0, 0, -1));
    assert_int_equal(hit.geom_id, 0);
    assert_int_equal(hit.prim_id, 0);
    assert_close(hit.t, 4.0, 1e-15);
    assert_close(hit.u, 0.25, 1e-15);
    assert_close(hit.v, 0.5, 1e-15);
    assert_vector_close(hit.p, 1.5, 2.5, 1, 1e-15);
    assert_vector_close(hit.ng, 0, 0, 1, 0);
    assert_vector_close(hit.ns, 0, 0, 1, 0);
}

static void test_quad_miss_outside(void **state) {
    fixture *f = *state;
    add_quad(f->scene, quad_o, quad_u, quad_v);
    commit(f->scene);
    assert_miss(trace(f->scene, make_ray(3 + 1e-9, 2, 5, 0, 0, -1)));
    assert_miss(trace(f->scene, make_ray(2, 1 - 1e-9, 5, 0, 0, -1)));
    assert_miss(trace(f->scene, make_ray(0.5, 0.5, 5, 0, 0, -1)));
    assert_miss(trace(f->scene, make_ray(2, 2, 5, 0, 0, 1))); /* pointing away */
}

static void test_quad_edges_and_corners_hit(void **state) {
    fixture *f = *state;
    add_quad(f->scene, quad_o, quad_u, quad_v);
    commit(f->scene);
    const double points[][4] = {/* x, y, expected u, v */
                                {1, 2.5, 0, 0.5}, {3, 2.5, 1, 0.5}, {2, 1, 0.5, 0}, {2, 4, 0.5, 1},
                                {1, 1, 0, 0},     {3, 4, 1, 1},     {3, 1, 1, 0},   {1, 4, 0, 1}};
    for (size_t i = 0; i < sizeof points / sizeof points[0]; ++i) {
        const ppm_hit hit = trace(f->scene, make_ray(points[i][0], points[i][1], 5, 0, 0, -1));
        assert_int_equal(hit.geom_id, 0);
        assert_close(hit.u, points[i][2], 1e-15);
        assert_close(hit.v, points[i][3], 1e-15);
    }
}

static void test_quad_uv_and_normal_of_tilted_parallelogram(void **state) {
    fixture *f = *state;
    const double o[3] = {0.5, -1, 2}, eu[3] = {1, 1, 0}, ev[3] = {0, 1, 2};
    add_quad(f->scene, o, eu, ev);
    commit(f->scene);
    /* eu x ev = (2, -2, 1), length 3 */
    const double n[3] = {2 / 3.0, -2 / 3.0, 1 / 3.0};
    double p[3];
    for (int k = 0; k < 3; ++k) p[k] = o[k] + 0.3 * eu[k] + 0.6 * ev[k];
    const ppm_hit hit =
        trace(f->scene, make_ray(p[0] + 4 * n[0], p[1] + 4 * n[1], p[2] + 4 * n[2], -n[0], -n[1], -n[2]));
    assert_int_equal(hit.geom_id, 0);
    assert_close(hit.t, 4.0, 1e-12);
    assert_close(hit.u, 0.3, 1e-12);
    assert_close(hit.v, 0.6, 1e-12);
    assert_vector_close(hit.p, p[0], p[1], p[2], 1e-12);
    assert_vector_close(hit.ng, n[0], n[1], n[2], 1e-15);
}

static void test_quad_normal_follows_edge_order(void **state) {
    fixture *f = *state;
    add_quad(f->scene, quad_o, quad_v, quad_u); /* edges swapped: normal -z */
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(1.5, 2.5, 5, 0, 0, -1));
    assert_vector_close(hit.ng, 0, 0, -1, 0);
    assert_close(hit.u, 0.5, 1e-15); /* u now runs along y */
    assert_close(hit.v, 0.25, 1e-15);
}

static void test_quad_parallel_ray_misses(void **state) {
    fixture *f = *state;
    add_quad(f->scene, quad_o, quad_u, quad_v);
    add_sphere(f->scene, 10, 10, 10, 0.5); /* so the scene box has depth */
    commit(f->scene);
    assert_miss(trace(f->scene, make_ray(0, 2, 1, 1, 0, 0)));   /* in the plane */
    assert_miss(trace(f->scene, make_ray(0, 2, 1.5, 1, 0, 0))); /* above it */
}

static void test_quad_is_two_sided(void **state) {
    fixture *f = *state;
    add_quad(f->scene, quad_o, quad_u, quad_v);
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(2, 3, -2, 0, 0, 1));
    assert_int_equal(hit.geom_id, 0);
    assert_close(hit.t, 3.0, 1e-15);
    assert_close(hit.u, 0.5, 1e-15);
    assert_close(hit.v, 2.0 / 3, 1e-15);
    assert_vector_close(hit.ng, 0, 0, 1, 0); /* as stored, not flipped */
}

static void test_quad_tnear_tfar(void **state) {
    fixture *f = *state;
    add_quad(f->scene, quad_o, quad_u, quad_v);
    commit(f->scene);
    ppm_ray ray = make_ray(2, 2, 5, 0, 0, -1); /* t = 4 */
    ray.tfar = 4 - 1e-9;
    assert_miss(trace(f->scene, ray));
    ray.tfar = 4;
    assert_true(trace(f->scene, ray).t == 4);
    ray.tfar = INFINITY;
    ray.tnear = 4 + 1e-9;
    assert_miss(trace(f->scene, ray));
}

/* Triangle meshes ---------------------------------------------------------------------------- */

/* Triangle p0 = (1, 0, 0), p1 = (0, 2, 0), p2 = (0, 0, 3): (p1 - p0) x (p2 - p0) = (6, 3, 2),
 * length 7. */
static const double tri_positions[9] = {1, 0, 0, 0, 2, 0, 0, 0, 3};
static const uint32_t tri_indices[3] = {0, 1, 2};

/* Hit of the ray that meets the triangle at barycentrics (u, v) from 1 unit along the normal. */
static ppm_hit hit_triangle_at(ppm_scene scene, double u, double v) {
    const double w = 1 - u - v;
    double p[3];
    for (int k = 0; k < 3; ++k) p[k] = w * tri_positions[k] + u * tri_positions[3 + k] + v * tri_positions[6 + k];
    return trace(scene, make_ray(p[0] + 6, p[1] + 3, p[2] + 2, -6, -3, -2));
}

static void test_mesh_barycentric_uv(void **state) {
    fixture *f = *state;
    assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, tri_indices, 1, NULL, NULL, NULL));
    commit(f->scene);
    const ppm_hit hit = hit_triangle_at(f->scene, 0.2, 0.3);
    assert_int_equal(hit.geom_id, 0);
    assert_int_equal(hit.prim_id, 0);
    assert_close(hit.t, 1.0, 1e-12);
    assert_close(hit.u, 0.2, 1e-12);
    assert_close(hit.v, 0.3, 1e-12);
    assert_vector_close(hit.p, 0.5, 0.4, 0.9, 1e-12);
}

static void test_mesh_geometric_normal_without_normals(void **state) {
    fixture *f = *state;
    assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, tri_indices, 1, NULL, NULL, NULL));
    commit(f->scene);
    const ppm_hit hit = hit_triangle_at(f->scene, 0.6, 0.1);
    assert_vector_close(hit.ng, 6 / 7.0, 3 / 7.0, 2 / 7.0, 1e-15);
    assert_vector_close(hit.ns, 6 / 7.0, 3 / 7.0, 2 / 7.0, 1e-15);
}

static void test_mesh_shading_normal_interpolated(void **state) {
    fixture *f = *state;
    const double normals[9] = {1, 0, 0, 0, 0.6, 0.8, 0, -0.8, 0.6};
    assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, tri_indices, 1, normals, NULL, NULL));
    commit(f->scene);
    const double u = 0.25, v = 0.5, w = 0.25;
    const ppm_hit hit = hit_triangle_at(f->scene, u, v);
    double ns[3], length = 0;
    for (int k = 0; k < 3; ++k) {
        ns[k] = w * normals[k] + u * normals[3 + k] + v * normals[6 + k];
        length += ns[k] * ns[k];
    }
    length = sqrt(length);
    assert_vector_close(hit.ns, ns[0] / length, ns[1] / length, ns[2] / length, 1e-12);
    assert_vector_close(hit.ng, 6 / 7.0, 3 / 7.0, 2 / 7.0, 1e-15);
}

static void test_mesh_prim_id_names_triangle(void **state) {
    fixture *f = *state;
    /* a strip of four unit triangles along x in z = 0 */
    const double positions[] = {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0, 2, 1, 0};
    const uint32_t indices[] = {0, 2, 1, 1, 2, 3, 2, 4, 3, 3, 4, 5};
    assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, positions, 6, indices, 4, NULL, NULL, NULL));
    commit(f->scene);
    const double probes[4][2] = {{0.2, 0.2}, {0.8, 0.8}, {1.2, 0.2}, {1.8, 0.8}};
    for (uint32_t k = 0; k < 4; ++k) {
        const ppm_hit hit = trace(f->scene, make_ray(probes[k][0], probes[k][1], 1, 0, 0, -1));
        assert_int_equal(hit.geom_id, 0);
        assert_int_equal(hit.prim_id, k);
        assert_close(hit.t, 1.0, 1e-12);
    }
}

static void test_mesh_zero_area_triangle_is_never_hit(void **state) {
    fixture *f = *state;
    const double positions[] = {0, 0, 0, 1, 1, 0, 2, 2, 0, 0, 0, -1, 2, 0, -1, 0, 2, -1};
    const uint32_t indices[] = {0, 1, 2, 3, 4, 5};
    assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, positions, 6, indices, 2, NULL, NULL, NULL));
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(0.5, 0.5, 1, 0, 0, -1)); /* through the sliver's line */
    assert_int_equal(hit.prim_id, 1);
    assert_close(hit.t, 2.0, 1e-12);
}

static void test_mesh_tnear_tfar(void **state) {
    fixture *f = *state;
    assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, tri_indices, 1, NULL, NULL, NULL));
    commit(f->scene);
    ppm_ray ray = make_ray(0.5 + 6, 0.4 + 3, 0.9 + 2, -6, -3, -2); /* t = 1 */
    ray.tfar = 1 - 1e-9;
    assert_miss(trace(f->scene, ray));
    ray.tfar = INFINITY;
    ray.tnear = 1 + 1e-9;
    assert_miss(trace(f->scene, ray));
    ray.tnear = 1 - 1e-9;
    assert_close(trace(f->scene, ray).t, 1.0, 1e-12);
}

/* Patches ------------------------------------------------------------------------------------ */

static void test_patch_saddle_hit(void **state) {
    fixture *f = *state;
    double points[48];
    saddle_patch(points);
    assert_ppm_ok(ppm_scene_add_bezier_patches(f->scene, points, 1, NULL));
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(0.3, 0.8, 2, 0, 0, -1));
    assert_int_equal(hit.geom_id, 0);
    assert_close(hit.t, 2 - 0.24, 1e-8);
    assert_close(hit.u, 0.3, 1e-8);
    assert_close(hit.v, 0.8, 1e-8);
    /* dS/du x dS/dv = (1, 0, v) x (0, 1, u) = (-v, -u, 1) */
    const double length = sqrt(0.64 + 0.09 + 1);
    assert_vector_close(hit.ng, -0.8 / length, -0.3 / length, 1 / length, 1e-7);
    assert_true(hit.p_error > 0);
}

/* The pre-split ("patch_presplit") changes the work, not the answer: the same hit, (u, v) and
 * patch at every value, also after re-committing with a smaller one. */
static void test_patch_presplit_same_hits(void **state) {
    fixture *f = *state;
    double points[96];
    saddle_patch(points);
    flat_patch(points + 48, 1, 0, 0);
    assert_ppm_ok(ppm_scene_add_bezier_patches(f->scene, points, 2, NULL));
    const double presplits[] = {32, 1, 2, 5, 12};
    for (size_t k = 0; k < sizeof presplits / sizeof presplits[0]; ++k) {
        assert_ppm_ok(ppm_scene_set_double(f->scene, "patch_presplit", presplits[k]));
        commit(f->scene);
        const ppm_hit saddle = trace(f->scene, make_ray(0.3, 0.8, 2, 0, 0, -1));
        assert_int_equal(saddle.prim_id, 0);
        assert_close(saddle.t, 2 - 0.24, 1e-8);
        assert_close(saddle.u, 0.3, 1e-8);
        assert_close(saddle.v, 0.8, 1e-8);
        /* On the edge u = 1 of the flat patch: the last sub-patch must reach it. */
        const ppm_hit edge = trace(f->scene, make_ray(2, 0.5, 1, 0, 0, -1));
        assert_int_equal(edge.prim_id, 1);
        assert_close(edge.u, 1, 1e-8);
        assert_close(edge.v, 0.5, 1e-8);
    }
}

static void test_patch_prim_id_names_patch(void **state) {
    fixture *f = *state;
    double points[96];
    flat_patch(points, 0, 0, 0);
    flat_patch(points + 48, 1, 0, 0);
    assert_ppm_ok(ppm_scene_add_bezier_patches(f->scene, points, 2, NULL));
    commit(f->scene);
    const ppm_hit first = trace(f->scene, make_ray(0.5, 0.5, 1, 0, 0, -1));
    const ppm_hit second = trace(f->scene, make_ray(1.75, 0.25, 1, 0, 0, -1));
    assert_int_equal(first.prim_id, 0);
    assert_int_equal(second.prim_id, 1);
    assert_close(second.u, 0.75, 1e-8);
    assert_close(second.v, 0.25, 1e-8);
}

/* Several geometries ----------------------------------------------------------------------- */

static void test_nearest_of_several_spheres(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 9, 0, 0, 1);
    add_sphere(f->scene, 3, 0, 0, 1);
    add_sphere(f->scene, 6, 0, 0, 1);
    commit(f->scene);
    ppm_hit hit = trace(f->scene, make_ray(0, 0, 0, 1, 0, 0));
    assert_int_equal(hit.geom_id, 1);
    assert_true(hit.t == 2);
    hit = trace(f->scene, make_ray(12, 0, 0, -1, 0, 0));
    assert_int_equal(hit.geom_id, 0);
    assert_true(hit.t == 2);
    ppm_ray between = make_ray(0, 0, 0, 1, 0, 0);
    between.tnear = 4.5;
    hit = trace(f->scene, between);
    assert_int_equal(hit.geom_id, 2);
    assert_true(hit.t == 5);
}

static void test_nearest_of_mixed_kinds(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    add_xy_quad(f->scene, -2, -2, 0.5, 4, 4); /* cuts the sphere */
    const double positions[] = {-2, -2, -0.5, 2, -2, -0.5, -2, 2, -0.5};
    assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, positions, 3, tri_indices, 1, NULL, NULL, NULL));
    double points[48];
    flat_patch(points, 1.2, 1.2, 0.75);
    assert_ppm_ok(ppm_scene_add_bezier_patches(f->scene, points, 1, NULL));
    commit(f->scene);

    ppm_hit hit = trace(f->scene, make_ray(0, 0, 5, 0, 0, -1));
    assert_int_equal(hit.geom_id, 0); /* sphere top before the quad */
    assert_true(hit.t == 4);
    hit = trace(f->scene, make_ray(-1.5, 0, 5, 0, 0, -1));
    assert_int_equal(hit.geom_id, 1);
    assert_close(hit.t, 4.5, 1e-15);
    hit = trace(f->scene, make_ray(-1.5, 0, -5, 0, 0, 1));
    assert_int_equal(hit.geom_id, 2);
    assert_close(hit.t, 4.5, 1e-12);
    hit = trace(f->scene, make_ray(1.5, 1.5, 5, 0, 0, -1));
    assert_int_equal(hit.geom_id, 3); /* patch above the quad */
    assert_close(hit.t, 4.25, 1e-8);
    hit = trace(f->scene, make_ray(0, 0, -5, 0, 0, 1));
    assert_int_equal(hit.geom_id, 0); /* sphere bottom before the mesh inside it */
    assert_true(hit.t == 4);
}

/* Random rays against a scene of every kind: occluded agrees with intersect. */
static void build_mixed_scene(ppm_scene scene) {
    add_sphere(scene, 0.5, 0.5, 0.5, 0.4);
    add_sphere(scene, -1, 1, 0, 0.7);
    add_xy_quad(scene, -2, -2, -1, 4, 4);
    const double o[3] = {1, -1, -1}, eu[3] = {0.5, 1, 0}, ev[3] = {0, 0.5, 1.5};
    add_quad(scene, o, eu, ev);
    assert_ppm_ok(ppm_scene_add_triangle_mesh(scene, tri_positions, 3, tri_indices, 1, NULL, NULL, NULL));
    double points[48];
    saddle_patch(points);
    assert_ppm_ok(ppm_scene_add_bezier_patches(scene, points, 1, NULL));
    commit(scene);
}

static ppm_ray random_ray(test_rng *rng) {
    ppm_ray ray;
    for (int k = 0; k < 3; ++k) {
        ray.org[k] = -3 + 6 * test_rng_uniform(rng);
        ray.dir[k] = -1 + 2 * test_rng_uniform(rng);
    }
    ray.tnear = test_rng_uniform(rng) < 0.5 ? 0 : test_rng_uniform(rng);
    ray.tfar = test_rng_uniform(rng) < 0.5 ? INFINITY : ray.tnear + 5 * test_rng_uniform(rng);
    return ray;
}

static void test_occluded_agrees_with_intersect(void **state) {
    fixture *f = *state;
    build_mixed_scene(f->scene);
    enum { n = 4000 };
    static ppm_ray rays[n];
    static ppm_hit hits[n];
    static uint8_t occluded[n];
    test_rng rng = {42};
    for (size_t i = 0; i < n; ++i) rays[i] = random_ray(&rng);
    assert_ppm_ok(ppm_scene_intersect(f->scene, rays, n, hits));
    assert_ppm_ok(ppm_scene_occluded(f->scene, rays, n, occluded));
    size_t hit_count = 0;
    for (size_t i = 0; i < n; ++i) {
        const int found = hits[i].geom_id != PPM_INVALID_ID;
        hit_count += (size_t)found;
        if (occluded[i] != found)
            fail_msg("ray %zu: occluded = %d but intersect found %s (t = %.17g)", i, occluded[i],
                     found ? "a hit" : "none", hits[i].t);
        if (found) assert_true(hits[i].t >= rays[i].tnear && hits[i].t <= rays[i].tfar);
    }
    assert_true(hit_count > n / 10 && hit_count < n); /* the sample exercises both answers */
}

static void test_batch_matches_single_calls(void **state) {
    fixture *f = *state;
    assert_ppm_ok(ppm_context_set_int(f->context, "threads", 2));
    build_mixed_scene(f->scene);
    enum { n = 1000 }; /* above the parallel threshold of 256 */
    static ppm_ray rays[n];
    static ppm_hit hits[n];
    static uint8_t occluded[n];
    test_rng rng = {7};
    for (size_t i = 0; i < n; ++i) rays[i] = random_ray(&rng);
    assert_ppm_ok(ppm_scene_intersect(f->scene, rays, n, hits));
    assert_ppm_ok(ppm_scene_occluded(f->scene, rays, n, occluded));
    for (size_t i = 0; i < n; ++i) {
        ppm_hit single;
        uint8_t single_occluded;
        assert_ppm_ok(ppm_scene_intersect(f->scene, &rays[i], 1, &single));
        assert_ppm_ok(ppm_scene_occluded(f->scene, &rays[i], 1, &single_occluded));
        if (memcmp(&single, &hits[i], sizeof single) != 0)
            fail_msg("ray %zu: batch hit (geom %u, t %.17g) differs from single (geom %u, t %.17g)", i, hits[i].geom_id,
                     hits[i].t, single.geom_id, single.t);
        assert_int_equal(single_occluded, occluded[i]);
    }
}

/* Transforms ------------------------------------------------------------------------------- */

static void test_transformed_sphere_moves_and_scales(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    /* translate (10, 0, 0) after rotating 90 degrees about z and scaling by 2 */
    const double m[16] = {0, -2, 0, 10, 2, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1};
    assert_ppm_ok(ppm_scene_set_geometry_transform(f->scene, 0, m));
    commit(f->scene);
    double lower[3], upper[3];
    assert_ppm_ok(ppm_scene_get_bounds(f->scene, lower, upper));
    assert_vector_close(lower, 8, -2, -2, 1e-12);
    assert_vector_close(upper, 12, 2, 2, 1e-12);

    ppm_hit hit = trace(f->scene, make_ray(10, 0, 10, 0, 0, -1));
    assert_close(hit.t, 8.0, 1e-12);
    assert_vector_close(hit.p, 10, 0, 2, 1e-12);
    assert_vector_close(hit.ng, 0, 0, 1, 1e-12);
    assert_close(hit.v, 0.0, 1e-12);
    assert_miss(trace(f->scene, make_ray(0, 0, 10, 0, 0, -1)));
}

static void test_transformed_sphere_uv_follows_rotation(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    const double m[16] = {0, -2, 0, 10, 2, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1};
    assert_ppm_ok(ppm_scene_set_geometry_transform(f->scene, 0, m));
    commit(f->scene);
    /* world +x of the sphere is the object's -y: u = 0.75; world +y is object +x: u = 0 */
    ppm_hit hit = trace(f->scene, make_ray(20, 0, 0, -1, 0, 0));
    assert_close(hit.t, 8.0, 1e-12);
    assert_close(hit.u, 0.75, 1e-12);
    assert_close(hit.v, 0.5, 1e-12);
    hit = trace(f->scene, make_ray(10, 10, 0, 0, -1, 0));
    assert_close(hit.u, 0.0, 1e-12);
}

static void test_transformed_patches_move(void **state) {
    fixture *f = *state;
    double points[96];
    flat_patch(points, 0, 0, 0);
    flat_patch(points + 48, 0, 1, 0);
    uint32_t id = PPM_INVALID_ID;
    assert_ppm_ok(ppm_scene_add_bezier_patches(f->scene, points, 2, &id));
    /* (x, y, z) -> (1 + 2x, 2 - 2z, 3 + 2y): rotate 90 degrees about x, scale 2, translate */
    const double m[16] = {2, 0, 0, 1, 0, 0, -2, 2, 0, 2, 0, 3, 0, 0, 0, 1};
    assert_ppm_ok(ppm_scene_set_geometry_transform(f->scene, id, m));
    commit(f->scene);
    /* patch 0 point (0.25, 0.5, 0) is now (1.5, 2, 4) */
    ppm_hit hit = trace(f->scene, make_ray(1.5, 10, 4, 0, -1, 0));
    assert_int_equal(hit.prim_id, 0);
    assert_close(hit.t, 8.0, 1e-8);
    assert_close(hit.u, 0.25, 1e-8);
    assert_close(hit.v, 0.5, 1e-8);
    assert_vector_close(hit.p, 1.5, 2, 4, 1e-8);
    assert_vector_close(hit.ng, 0, -1, 0, 1e-8);
    /* patch 1 point (0.5, 1.75, 0) is now (2, 2, 6.5) */
    hit = trace(f->scene, make_ray(2, -3, 6.5, 0, 1, 0));
    assert_int_equal(hit.prim_id, 1);
    assert_close(hit.t, 5.0, 1e-8);
    assert_close(hit.u, 0.5, 1e-8);
    assert_close(hit.v, 0.75, 1e-8);
    /* the old place is empty */
    assert_miss(trace(f->scene, make_ray(0.5, 0.5, 1, 0, 0, -1)));
}

static void test_transformed_mesh_normals_under_non_uniform_scale(void **state) {
    fixture *f = *state;
    const double positions[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double s = 1 / sqrt(3.0);
    const double normals[9] = {s, s, s, s, s, s, s, s, s};
    assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, positions, 3, tri_indices, 1, normals, NULL, NULL));
    const double m[16] = {2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; /* x scaled by 2 */
    assert_ppm_ok(ppm_scene_set_geometry_transform(f->scene, 0, m));
    commit(f->scene);
    /* the plane x / 2 + y + z = 1 has normal (1, 2, 2) / 3; normals follow the inverse transpose */
    const ppm_hit hit = trace(f->scene, make_ray(0, 0, 0, 2.0 / 3, 1.0 / 3, 1.0 / 3));
    assert_close(hit.t, 1.0, 1e-12);
    assert_close(hit.u, 1.0 / 3, 1e-12);
    assert_close(hit.v, 1.0 / 3, 1e-12);
    assert_vector_close(hit.ng, 1.0 / 3, 2.0 / 3, 2.0 / 3, 1e-12);
    assert_vector_close(hit.ns, 1.0 / 3, 2.0 / 3, 2.0 / 3, 1e-12);
}

static void test_transformed_mesh_normals_under_shear(void **state) {
    fixture *f = *state;
    /* vertex normals equal to the face normal stay equal to it under any transform with a
     * positive determinant (here 0.677) */
    const double normals[9] = {6 / 7.0, 3 / 7.0, 2 / 7.0, 6 / 7.0, 3 / 7.0, 2 / 7.0, 6 / 7.0, 3 / 7.0, 2 / 7.0};
    assert_ppm_ok(ppm_scene_add_triangle_mesh(f->scene, tri_positions, 3, tri_indices, 1, normals, NULL, NULL));
    const double m[16] = {1, 0.7, -0.3, 1, 0.2, 1.5, 0.4, -2, -0.5, 0.1, 0.8, 3, 0, 0, 0, 1};
    assert_ppm_ok(ppm_scene_set_geometry_transform(f->scene, 0, m));
    commit(f->scene);
    double p[3][3], centroid[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
        for (int r = 0; r < 3; ++r) {
            p[k][r] = m[4 * r + 3];
            for (int c = 0; c < 3; ++c) p[k][r] += m[4 * r + c] * tri_positions[3 * k + c];
            centroid[r] += p[k][r] / 3;
        }
    const double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double length = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) n[k] /= length;
    const ppm_hit hit =
        trace(f->scene, make_ray(centroid[0] + n[0], centroid[1] + n[1], centroid[2] + n[2], -n[0], -n[1], -n[2]));
    assert_int_equal(hit.geom_id, 0);
    assert_close(hit.t, 1.0, 1e-12);
    assert_close(hit.u, 1.0 / 3, 1e-12);
    assert_close(hit.v, 1.0 / 3, 1e-12);
    assert_vector_close(hit.ng, n[0], n[1], n[2], 1e-12);
    assert_vector_close(hit.ns, n[0], n[1], n[2], 1e-12);
}

/* Materials ------------------------------------------------------------------------------- */

static void test_material_ids_are_reported(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    add_sphere(f->scene, 5, 0, 0, 1);
    add_xy_quad(f->scene, -1, -1, -3, 2, 2);
    assert_ppm_ok(ppm_scene_set_geometry_material(f->scene, 1, 7));
    assert_ppm_ok(ppm_scene_set_geometry_material(f->scene, 2, 0xFFFFFFFEu));
    commit(f->scene);
    assert_int_equal(trace(f->scene, make_ray(0, 0, 5, 0, 0, -1)).material, 0);
    assert_int_equal(trace(f->scene, make_ray(5, 0, 5, 0, 0, -1)).material, 7);
    assert_int_equal(trace(f->scene, make_ray(0, 0, -5, 0, 0, 1)).material, 0xFFFFFFFEu);
    assert_int_equal(trace(f->scene, make_ray(0, 0, -5, 0, 0, 1)).reserved, 0);

    assert_ppm_ok(ppm_scene_set_geometry_material(f->scene, 1, 8));
    commit(f->scene);
    assert_int_equal(trace(f->scene, make_ray(5, 0, 5, 0, 0, -1)).material, 8);
}

/* ppm_hit_spawn_ray ------------------------------------------------------------------------ */

static ppm_ray spawn(const ppm_hit *hit, double x, double y, double z) {
    const double dir[3] = {x, y, z};
    ppm_ray ray;
    assert_ppm_ok(ppm_hit_spawn_ray(hit, dir, &ray));
    return ray;
}

static void test_spawn_from_quad_hits_parallel_quad(void **state) {
    fixture *f = *state;
    add_xy_quad(f->scene, 0, 0, 0, 1, 1);
    add_xy_quad(f->scene, 0, 0, 1e-6, 1, 1);
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(0.5, 0.5, -1, 0, 0, 1));
    assert_int_equal(hit.geom_id, 0);
    assert_true(2 * hit.p_error < 1e-7);

    ppm_hit next = trace(f->scene, spawn(&hit, 0, 0, 1));
    assert_int_equal(next.geom_id, 1);
    assert_close(next.t, 1e-6, 2 * hit.p_error + 1e-15);
    next = trace(f->scene, spawn(&hit, 0.3, -0.2, 1));
    assert_int_equal(next.geom_id, 1);
    assert_miss(trace(f->scene, spawn(&hit, 0, 0, -1)));
    assert_miss(trace(f->scene, spawn(&hit, 0.1, 0.1, -1)));
}

static void test_spawn_from_upper_quad_going_down(void **state) {
    fixture *f = *state;
    add_xy_quad(f->scene, 0, 0, 0, 1, 1);
    add_xy_quad(f->scene, 0, 0, 1e-6, 1, 1);
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(0.25, 0.75, 1, 0, 0, -1));
    assert_int_equal(hit.geom_id, 1);
    const ppm_hit next = trace(f->scene, spawn(&hit, 0, 0, -1)); /* against ng: moved below */
    assert_int_equal(next.geom_id, 0);
    assert_close(next.t, 1e-6, 2 * hit.p_error + 1e-15);
    assert_miss(trace(f->scene, spawn(&hit, 0, 0, 1)));
}

static void test_spawn_from_sphere_hits_quad_outside(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    const double o[3] = {1 + 1e-6, -0.5, -0.5}, eu[3] = {0, 1, 0}, ev[3] = {0, 0, 1};
    add_quad(f->scene, o, eu, ev);
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(0, 0, 0, 1, 0, 0));
    assert_int_equal(hit.geom_id, 0);
    assert_true(2 * hit.p_error < 1e-7);
    const ppm_hit next = trace(f->scene, spawn(&hit, 1, 0, 0));
    assert_int_equal(next.geom_id, 1);
    assert_close(next.t, 1e-6, 2 * hit.p_error + 1e-15);
}

static void test_spawn_into_sphere_hits_far_side(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(5, 0, 0, -1, 0, 0));
    const ppm_hit next = trace(f->scene, spawn(&hit, -1, 0, 0));
    assert_int_equal(next.geom_id, 0);
    assert_close(next.t, 2.0, 4 * hit.p_error);
    assert_vector_close(next.p, -1, 0, 0, 1e-12);
    /* leaving outwards, even tangentially, sees nothing */
    assert_miss(trace(f->scene, spawn(&hit, 1, 0, 0)));
    assert_miss(trace(f->scene, spawn(&hit, 0, 1, 0)));
    assert_miss(trace(f->scene, spawn(&hit, 0.001, 1, 1)));
}

static void test_spawn_from_inside_sphere_hit(void **state) {
    fixture *f = *state;
    add_sphere(f->scene, 0, 0, 0, 1);
    commit(f->scene);
    const ppm_hit hit = trace(f->scene, make_ray(0, 0, 0, 0, 1, 0)); /* far side from inside */
    const ppm_hit next = trace(f->scene, spawn(&hit, 0, -1, 0));
    assert_int_equal(next.geom_id, 0);
    assert_close(next.t, 2.0, 4 * hit.p_error);
    assert_miss(trace(f->scene, spawn(&hit, 0, 1, 0)));
}

/* Nearest root t > 0 of a unit-direction ray and a sphere, in the cancellation-free form. */
static double sphere_root(const double o[3], const double d[3], const double c[3], double r) {
    double f[3], l[3];
    for (int k = 0; k < 3; ++k) f[k] = o[k] - c[k];
    const double b = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
    for (int k = 0; k < 3; ++k) l[k] = f[k] - d[k] * b;
    const double disc = r * r - (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    if (disc < 0) return INFINITY;
    const double q = -(b + copysign(sqrt(disc), b));
    const double cc = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] - r * r;
    double t0 = q, t1 = q != 0 ? cc / q : q;
    if (t0 > t1) {
        const double s = t0;
        t0 = t1;
        t1 = s;
    }
    return t0 > 0 ? t0 : (t1 > 0 ? t1 : INFINITY);
}

/* Hachisuka's smallppm box: walls are spheres of radius 1e5, whose boxes hold the whole scene
 * (the library tests such spheres outside its BVH), plus three small spheres inside. Random
 * rays from inside the room must find the nearest sphere, as brute force does. */
static void test_huge_wall_spheres_and_small_ones(void **state) {
    fixture *f = *state;
    const double spheres[9][4] = {
        {1e5 + 1, 40.8, 81.6, 1e5},  {-1e5 + 99, 40.8, 81.6, 1e5}, {50, 40.8, 1e5, 1e5},
        {50, 40.8, -1e5 + 170, 1e5}, {50, 1e5, 81.6, 1e5},         {50, -1e5 + 81.6, 81.6, 1e5},
        {27, 16.5, 47, 16.5},        {73, 16.5, 88, 16.5},         {50, 8.5, 60, 8.5}};
    for (int s = 0; s < 9; ++s) add_sphere(f->scene, spheres[s][0], spheres[s][1], spheres[s][2], spheres[s][3]);
    commit(f->scene);
    test_rng rng = {21};
    for (int i = 0; i < 3000; ++i) {
        const double o[3] = {5 + 90 * test_rng_uniform(&rng), 35 + 40 * test_rng_uniform(&rng),
                             110 + 55 * test_rng_uniform(&rng)};
        double d[3] = {test_rng_uniform(&rng) - 0.5, test_rng_uniform(&rng) - 0.5, test_rng_uniform(&rng) - 0.5};
        const double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int k = 0; k < 3; ++k) d[k] /= len;
        double best = INFINITY;
        int nearest = -1;
        for (int s = 0; s < 9; ++s) {
            const double t = sphere_root(o, d, spheres[s], spheres[s][3]);
            if (t < best) {
                best = t;
                nearest = s;
            }
        }
        const ppm_hit hit = trace(f->scene, make_ray(o[0], o[1], o[2], d[0], d[1], d[2]));
        assert_int_equal(nearest >= 0, 1); /* the room is closed */
        assert_int_equal(hit.geom_id, (uint32_t)nearest);
        assert_close(hit.t, best, 1e-6);
        /* A shadow ray stopping short of the nearest surface sees nothing. */
        ppm_ray shorter = make_ray(o[0], o[1], o[2], d[0], d[1], d[2]);
        shorter.tfar = 0.99 * best;
        assert_miss(trace(f->scene, shorter));
    }
}

/* Both roots of a unit-direction ray and a sphere, ascending (INFINITY twice on a miss). */
static void sphere_roots(const double o[3], const double d[3], const double c[3], double r, double t[2]) {
    double f[3], l[3];
    for (int k = 0; k < 3; ++k) f[k] = o[k] - c[k];
    const double b = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
    for (int k = 0; k < 3; ++k) l[k] = f[k] - d[k] * b;
    const double disc = r * r - (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    t[0] = t[1] = INFINITY;
    if (disc < 0) return;
    const double q = -(b + copysign(sqrt(disc), b));
    const double cc = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] - r * r;
    t[0] = q;
    t[1] = q != 0 ? cc / q : q;
    if (t[0] > t[1]) {
        const double s = t[0];
        t[0] = t[1];
        t[1] = s;
    }
}

/* Overlapping spheres of many sizes, rays from anywhere (inside spheres too) with directions of
 * any length and random [tnear, tfar]: the nearest root within the interval, as brute force
 * finds it. Exercises the sphere test's shortcuts (receding rays, roots beyond the nearest hit
 * so far) in every order. With 40 spheres the big ones are tested outside the BVH and the small
 * ones in it; a scene of 12 spheres keeps them all outside (three groups of SIMD lanes). */
static void check_random_spheres_and_ray_intervals(fixture *f, int count, uint64_t seed) {
    test_rng rng = {seed};
    double spheres[40][4];
    assert_true(count <= 40);
    for (int s = 0; s < count; ++s) {
        for (int k = 0; k < 3; ++k) spheres[s][k] = 200 * test_rng_uniform(&rng) - 100;
        spheres[s][3] = s < 4 ? 60 + 60 * test_rng_uniform(&rng) : 1 + 20 * test_rng_uniform(&rng);
        add_sphere(f->scene, spheres[s][0], spheres[s][1], spheres[s][2], spheres[s][3]);
    }
    commit(f->scene);
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
        double o[3], d[3];
        for (int k = 0; k < 3; ++k) o[k] = 300 * test_rng_uniform(&rng) - 150;
        for (int k = 0; k < 3; ++k) d[k] = test_rng_uniform(&rng) - 0.5;
        const double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int k = 0; k < 3; ++k) d[k] /= len;
        const double scale = pow(10.0, 4 * test_rng_uniform(&rng) - 2); /* |dir| in [0.01, 100] */
        const double tnear = test_rng_uniform(&rng) < 0.5 ? 0 : 100 * test_rng_uniform(&rng);
        const double tfar = test_rng_uniform(&rng) < 0.5 ? INFINITY : tnear + 200 * test_rng_uniform(&rng);
        double best = INFINITY;
        int nearest = -1;
        for (int s = 0; s < count; ++s) {
            double t[2];
            sphere_roots(o, d, spheres[s], spheres[s][3], t);
            for (int k = 0; k < 2; ++k)
                if (t[k] >= tnear && t[k] <= tfar && t[k] < best) {
                    best = t[k];
                    nearest = s;
                }
        }
        ppm_ray ray = make_ray(o[0], o[1], o[2], d[0] * scale, d[1] * scale, d[2] * scale);
        ray.tnear = tnear / scale;
        ray.tfar = tfar / scale;
        const ppm_hit hit = trace(f->scene, ray);
        if (nearest < 0) {
            assert_miss(hit);
            continue;
        }
        ++hits;
        assert_int_equal(hit.geom_id, (uint32_t)nearest);
        assert_close(hit.t * scale, best, 1e-9 * (1 + best));
    }
    assert_true(hits > 1000);
}

static void test_random_spheres_and_ray_intervals(void **state) {
    check_random_spheres_and_ray_intervals(*state, 40, 23);
}

static void test_few_random_spheres_all_outside_the_bvh(void **state) {
    check_random_spheres_and_ray_intervals(*state, 12, 29);
}

/* Twenty nested spheres, all with boxes holding most of the scene's: more than the library
 * tests outside its BVH (16), so the smaller ones stay in it. The nearest is found either way. */
static void test_many_nested_big_spheres(void **state) {
    fixture *f = *state;
    for (int s = 0; s < 20; ++s) add_sphere(f->scene, 0, 0, 0, 1000 * (20 - s)); /* id 19: radius 1000 */
    commit(f->scene);
    const ppm_hit inside = trace(f->scene, make_ray(0, 0, 0, 0.6, 0, 0.8));
    assert_int_equal(inside.geom_id, 19);
    assert_close(inside.t, 1000, 1e-9);
    const ppm_hit between = trace(f->scene, make_ray(0, 0, 7500, 0, 0, 1)); /* inside radius 8000 */
    assert_int_equal(between.geom_id, 12);
    assert_close(between.t, 500, 1e-9);
    const ppm_hit outside = trace(f->scene, make_ray(0, 0, -30000, 0, 0, 1));
    assert_int_equal(outside.geom_id, 0);
    assert_close(outside.t, 10000, 1e-9);
}

#define TEST(name) cmocka_unit_test_setup_teardown(name, scene_fixture_setup, scene_fixture_teardown)

int main(void) {
    const struct CMUnitTest tests[] = {
        TEST(test_sphere_ray_through_center),
        TEST(test_sphere_t_is_in_units_of_dir_length),
        TEST(test_sphere_exact_distance_on_axis),
        TEST(test_sphere_near_tangent_ray_hits),
        TEST(test_sphere_near_tangent_ray_misses),
        TEST(test_sphere_ray_from_inside_hits_far_side),
        TEST(test_sphere_uv_on_equator),
        TEST(test_sphere_uv_poles_and_general_point),
        TEST(test_sphere_uv_of_offset_sphere),
        TEST(test_sphere_tnear_tfar),
        TEST(test_huge_wall_spheres_and_small_ones),
        TEST(test_many_nested_big_spheres),
        TEST(test_random_spheres_and_ray_intervals),
        TEST(test_few_random_spheres_all_outside_the_bvh),
        TEST(test_quad_hit_inside),
        TEST(test_quad_miss_outside),
        TEST(test_quad_edges_and_corners_hit),
        TEST(test_quad_uv_and_normal_of_tilted_parallelogram),
        TEST(test_quad_normal_follows_edge_order),
        TEST(test_quad_parallel_ray_misses),
        TEST(test_quad_is_two_sided),
        TEST(test_quad_tnear_tfar),
        TEST(test_mesh_barycentric_uv),
        TEST(test_mesh_geometric_normal_without_normals),
        TEST(test_mesh_shading_normal_interpolated),
        TEST(test_mesh_prim_id_names_triangle),
        TEST(test_mesh_zero_area_triangle_is_never_hit),
        TEST(test_mesh_tnear_tfar),
        TEST(test_patch_saddle_hit),
        TEST(test_patch_prim_id_names_patch),
        TEST(test_patch_presplit_same_hits),
        TEST(test_nearest_of_several_spheres),
        TEST(test_nearest_of_mixed_kinds),
        TEST(test_occluded_agrees_with_intersect),
        TEST(test_batch_matches_single_calls),
        TEST(test_transformed_sphere_moves_and_scales),
        TEST(test_transformed_sphere_uv_follows_rotation),
        TEST(test_transformed_patches_move),
        TEST(test_transformed_mesh_normals_under_non_uniform_scale),
        TEST(test_transformed_mesh_normals_under_shear),
        TEST(test_material_ids_are_reported),
        TEST(test_spawn_from_quad_hits_parallel_quad),
        TEST(test_spawn_from_upper_quad_going_down),
        TEST(test_spawn_from_sphere_hits_quad_outside),
        TEST(test_spawn_into_sphere_hits_far_side),
        TEST(test_spawn_from_inside_sphere_hit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
