/* SPDX-License-Identifier: Apache-2.0 */
/* Tessellation through the public API (ppm_tessellate_patches and the ppm_mesh getters),
 * checked with this file's own Bezier evaluation and nearest-point search, not with the
 * library's measurement: distance to the surface on every patch of the teapot, watertightness
 * across seams, no degenerate triangles at the collapsed edges, the triangle budget against
 * the coarsest uniform grid that meets the same tolerance, uniform counts, bad arguments.
 *
 * Run as `test_tessellate --tool PATH_TO_PPM_TESS` it instead checks the ppm-tess tool: it
 * tessellates the teapot into a temporary folder and loads the OBJ back into a scene. */
#define _XOPEN_SOURCE 700

#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

#include <dirent.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* ---- The teapot, read by this file ---------------------------------------------------- */

enum { teapot_patches = 32 };

typedef struct patches {
    size_t count;
    double *points; /* count * 48 */
    double diagonal;
} patches;

static patches read_teapot(void) {
    patches t = {0, NULL, 0};
    FILE *file = fopen(PPM_TEAPOT, "r");
    assert_non_null(file);
    int count = 0;
    assert_int_equal(fscanf(file, "%d", &count), 1);
    assert_int_equal(count, teapot_patches);
    t.count = (size_t)count;
    t.points = malloc(sizeof(double) * 48 * t.count);
    assert_non_null(t.points);
    for (size_t p = 0; p < t.count; ++p) {
        int du = 0, dv = 0;
        assert_int_equal(fscanf(file, "%d %d", &du, &dv), 2);
        for (int k = 0; k < 48; ++k) assert_int_equal(fscanf(file, "%lf", &t.points[48 * p + k]), 1);
    }
    fclose(file);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t k = 0; k < 48 * t.count; ++k) {
        lo[k % 3] = fmin(lo[k % 3], t.points[k]);
        hi[k % 3] = fmax(hi[k % 3], t.points[k]);
    }
    t.diagonal =
        sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    return t;
}

static int setup(void **state) {
    patches *t = malloc(sizeof *t);
    if (!t) return -1;
    *t = read_teapot();
    *state = t;
    return 0;
}

static int teardown(void **state) {
    patches *t = *state;
    free(t->points);
    free(t);
    return 0;
}

/* ---- Bezier surface and nearest points, independent of the library --------------------- */

static void bernstein(double t, double b[4], double d[4]) {
    const double s = 1 - t;
    b[0] = s * s * s;
    b[1] = 3 * t * s * s;
    b[2] = 3 * t * t * s;
    b[3] = t * t * t;
    d[0] = -3 * s * s;
    d[1] = 3 * s * s - 6 * t * s;
    d[2] = 6 * t * s - 3 * t * t;
    d[3] = 3 * t * t;
}

/* S(u, v) = sum_i sum_j B_i(v) B_j(u) P[i][j] and its partial derivatives. */
static void surface(const double *patch, double u, double v, double p[3], double pu[3], double pv[3]) {
    double bu[4], du[4], bv[4], dv[4];
    bernstein(u, bu, du);
    bernstein(v, bv, dv);
    for (int c = 0; c < 3; ++c) p[c] = pu[c] = pv[c] = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int c = 0; c < 3; ++c) {
                const double x = patch[3 * (4 * i + j) + c];
                p[c] += bv[i] * bu[j] * x;
                pu[c] += bv[i] * du[j] * x;
                pv[c] += dv[i] * bu[j] * x;
            }
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static double clamp01(double t) { return t < 0 ? 0 : t > 1 ? 1 : t; }

/* Distance from x to the patch: damped Gauss-Newton for the nearest point from (u, v), kept
 * inside the domain, accepting only steps that bring the surface point closer; where a step
 * does not, half of it and steps along one parameter are tried (the nearest point may lie on
 * the border). */
static double patch_distance(const double *patch, const double x[3], double u, double v) {
    double p[3], pu[3], pv[3], r[3];
    surface(patch, u, v, p, pu, pv);
    for (int c = 0; c < 3; ++c) r[c] = p[c] - x[c];
    double best = dot3(r, r);
    for (int iteration = 0; iteration < 20 && best > 0; ++iteration) {
        const double a = dot3(pu, pu), b = dot3(pu, pv), c = dot3(pv, pv);
        const double damp = 1e-12 * (a + c);
        const double det = (a + damp) * (c + damp) - b * b;
        if (!(det > 0)) break;
        const double g1 = dot3(pu, r), g2 = dot3(pv, r);
        const double su = -((c + damp) * g1 - b * g2) / det, sv = -((a + damp) * g2 - b * g1) / det;
        const double tries[4][2] = {
            {u + su, v + sv}, {u + su / 2, v + sv / 2}, {u - g1 / (a + damp), v}, {u, v - g2 / (c + damp)}};
        int moved = 0;
        for (int k = 0; k < 4 && !moved; ++k) {
            const double nu = clamp01(tries[k][0]), nv = clamp01(tries[k][1]);
            double q[3], qu[3], qv[3], s[3];
            surface(patch, nu, nv, q, qu, qv);
            for (int e = 0; e < 3; ++e) s[e] = q[e] - x[e];
            const double dist2 = dot3(s, s);
            if (!(dist2 < best)) continue;
            best = dist2;
            u = nu;
            v = nv;
            memcpy(pu, qu, sizeof pu);
            memcpy(pv, qv, sizeof pv);
            memcpy(r, s, sizeof r);
            moved = 1;
        }
        if (!moved) break;
    }
    return sqrt(best);
}

/* ---- Mesh access -------------------------------------------------------------------------- */

typedef struct mesh_view {
    const double *positions, *normals, *uvs;
    size_t vertex_count;
    const uint32_t *indices;
    size_t triangle_count;
    const uint32_t *patch_of;
    const uint32_t *welded;
    size_t welded_count;
} mesh_view;

static mesh_view view_of(ppm_mesh mesh) {
    mesh_view m;
    memset(&m, 0, sizeof m);
    assert_ppm_ok(ppm_mesh_get_vertices(mesh, &m.positions, &m.normals, &m.uvs, &m.vertex_count));
    assert_ppm_ok(ppm_mesh_get_triangles(mesh, &m.indices, &m.triangle_count));
    assert_ppm_ok(ppm_mesh_get_triangle_patches(mesh, &m.patch_of));
    assert_ppm_ok(ppm_mesh_get_welded_vertices(mesh, &m.welded, &m.welded_count));
    for (size_t k = 0; k < 3 * m.triangle_count; ++k) assert_true(m.indices[k] < m.vertex_count);
    return m;
}

static ppm_mesh tessellate(const patches *t, double tolerance, uint32_t grid) {
    ppm_mesh mesh = NULL;
    assert_ppm_ok(ppm_tessellate_patches(t->points, t->count, tolerance, grid, &mesh));
    assert_non_null(mesh);
    return mesh;
}

/* Largest distance to its patch over every triangle, sampled at the barycentric lattice of
 * step 1 / k, each sample starting its search at the interpolated (u, v); per patch in
 * per_patch (may be NULL). */
static double measure(const patches *t, const mesh_view *m, int k, double *per_patch) {
    double worst = 0;
    if (per_patch)
        for (size_t p = 0; p < t->count; ++p) per_patch[p] = 0;
    for (size_t tri = 0; tri < m->triangle_count; ++tri) {
        const uint32_t *c = m->indices + 3 * tri;
        const uint32_t patch = m->patch_of[tri];
        assert_true(patch < t->count);
        for (int i = 0; i <= k; ++i)
            for (int j = 0; i + j <= k; ++j) {
                const double l[3] = {(double)(k - i - j) / k, (double)i / k, (double)j / k};
                double x[3] = {0, 0, 0}, u = 0, v = 0;
                for (int corner = 0; corner < 3; ++corner) {
                    for (int a = 0; a < 3; ++a) x[a] += l[corner] * m->positions[3 * c[corner] + a];
                    u += l[corner] * m->uvs[2 * c[corner]];
                    v += l[corner] * m->uvs[2 * c[corner] + 1];
                }
                const double d = patch_distance(t->points + 48 * patch, x, u, v);
                if (d > worst) worst = d;
                if (per_patch && d > per_patch[patch]) per_patch[patch] = d;
            }
    }
    return worst;
}

/* ---- Patch borders: seams, collapsed edges, free boundaries ------------------------------ */

/* Side s of a patch, in the direction of increasing parameter: 0 v = 0, 1 u = 1, 2 v = 1,
 * 3 u = 0. */
static void side_points(const double *patch, int s, double q[4][3]) {
    for (int k = 0; k < 4; ++k) {
        const int i = s == 0 ? 0 : s == 2 ? 3 : k, j = s == 3 ? 0 : s == 1 ? 3 : k;
        memcpy(q[k], patch + 3 * (4 * i + j), sizeof q[k]);
    }
}

enum side_kind { side_seam, side_collapsed, side_free };

static enum side_kind classify_side(const patches *t, size_t p, int s) {
    double q[4][3], r[4][3];
    side_points(t->points + 48 * p, s, q);
    if (!memcmp(q[0], q[1], sizeof q[0]) && !memcmp(q[0], q[2], sizeof q[0]) && !memcmp(q[0], q[3], sizeof q[0]))
        return side_collapsed;
    for (size_t o = 0; o < t->count; ++o)
        for (int os = 0; os < 4; ++os) {
            if (o == p && os == s) continue;
            side_points(t->points + 48 * o, os, r);
            int forward = 1, backward = 1;
            for (int k = 0; k < 4; ++k) {
                forward &= !memcmp(q[k], r[k], sizeof q[k]);
                backward &= !memcmp(q[k], r[3 - k], sizeof q[k]);
            }
            if (forward || backward) return side_seam;
        }
    return side_free;
}

/* Whether (u, v) lies on side s. */
static int lies_on(const double *uv, int s) {
    return s == 0 ? uv[1] == 0 : s == 1 ? uv[0] == 1 : s == 2 ? uv[1] == 1 : uv[0] == 0;
}

/* The side both uvs lie on, or -1. */
static int side_of(const double *a, const double *b) {
    for (int s = 0; s < 4; ++s)
        if (lies_on(a, s) && lies_on(b, s)) return s;
    return -1;
}

static int compare_u64(const void *a, const void *b) {
    const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

static const double *sort_positions;
static int compare_by_position(const void *a, const void *b) {
    const double *p = sort_positions + 3 * *(const uint32_t *)a, *q = sort_positions + 3 * *(const uint32_t *)b;
    for (int c = 0; c < 3; ++c)
        if (p[c] != q[c]) return p[c] < q[c] ? -1 : 1;
    return 0;
}

/* Welded ids are exactly "same position": equal positions have equal ids and vice versa. */
static void check_welding(const mesh_view *m) {
    uint32_t *order = malloc(sizeof(uint32_t) * m->vertex_count);
    assert_non_null(order);
    for (size_t v = 0; v < m->vertex_count; ++v) order[v] = (uint32_t)v;
    sort_positions = m->positions;
    qsort(order, m->vertex_count, sizeof *order, compare_by_position);
    size_t distinct = 0;
    for (size_t k = 0; k < m->vertex_count; ++k) {
        assert_true(m->welded[order[k]] < m->welded_count);
        const int same = k > 0 && compare_by_position(&order[k - 1], &order[k]) == 0;
        if (same)
            assert_int_equal(m->welded[order[k - 1]], m->welded[order[k]]);
        else
            ++distinct;
        if (k > 0 && !same) assert_int_not_equal(m->welded[order[k - 1]], m->welded[order[k]]);
    }
    assert_int_equal(distinct, m->welded_count);
    free(order);
}

/* Every edge (by welded positions) belongs to exactly two triangles, except edges on the free
 * sides of the patches, which belong to one; every free side has such edges. Returns the
 * number of boundary edges. */
static size_t check_watertight(const patches *t, const mesh_view *m) {
    enum side_kind kind[teapot_patches][4];
    size_t counts[3] = {0, 0, 0};
    for (size_t p = 0; p < t->count; ++p)
        for (int s = 0; s < 4; ++s) ++counts[kind[p][s] = classify_side(t, p, s)];
    /* The data README's facts: 104 sides pair up into seams, 8 are collapsed, 16 are free. */
    assert_int_equal(counts[side_seam], 104);
    assert_int_equal(counts[side_collapsed], 8);
    assert_int_equal(counts[side_free], 16);

    const size_t edge_count = 3 * m->triangle_count;
    uint64_t *edges = malloc(sizeof(uint64_t) * edge_count);
    assert_non_null(edges);
    for (size_t tri = 0; tri < m->triangle_count; ++tri)
        for (int e = 0; e < 3; ++e) {
            uint64_t a = m->welded[m->indices[3 * tri + e]], b = m->welded[m->indices[3 * tri + (e + 1) % 3]];
            if (a > b) {
                const uint64_t swap = a;
                a = b;
                b = swap;
            }
            edges[3 * tri + e] = a << 32 | b;
        }
    uint64_t *sorted = malloc(sizeof(uint64_t) * edge_count);
    assert_non_null(sorted);
    memcpy(sorted, edges, sizeof(uint64_t) * edge_count);
    qsort(sorted, edge_count, sizeof *sorted, compare_u64);
    size_t boundary = 0;
    size_t side_edges[teapot_patches][4];
    memset(side_edges, 0, sizeof side_edges);
    for (size_t k = 0; k < edge_count;) {
        size_t run = 1;
        while (k + run < edge_count && sorted[k + run] == sorted[k]) ++run;
        if (run > 2) fail_msg("an edge is shared by %zu triangles", run);
        if (run == 1) {
            ++boundary;
            /* Find the triangle and check the edge lies on a free side of its patch. */
            size_t where = 0;
            while (edges[where] != sorted[k]) ++where;
            const size_t tri = where / 3;
            const uint32_t a = m->indices[where], b = m->indices[3 * tri + (where % 3 + 1) % 3];
            const int side = side_of(m->uvs + 2 * a, m->uvs + 2 * b);
            const uint32_t patch = m->patch_of[tri];
            if (side < 0) fail_msg("boundary edge of triangle %zu (patch %u) is not on a patch side", tri, patch);
            if (kind[patch][side] != side_free)
                fail_msg("boundary edge of triangle %zu lies on side %d of patch %u, which is %s", tri, side, patch,
                         kind[patch][side] == side_seam ? "a seam" : "collapsed");
            ++side_edges[patch][side];
        }
        k += run;
    }
    /* Each free side is covered from end to end: its boundary edges join all of the patch's
     * vertices on it, in a chain. */
    char *on_side = malloc(m->vertex_count);
    assert_non_null(on_side);
    for (size_t p = 0; p < t->count; ++p)
        for (int s = 0; s < 4; ++s) {
            if (kind[p][s] != side_free) continue;
            memset(on_side, 0, m->vertex_count);
            size_t vertices = 0;
            for (size_t tri = 0; tri < m->triangle_count; ++tri)
                for (int k = 0; k < 3 && m->patch_of[tri] == p; ++k) {
                    const uint32_t v = m->indices[3 * tri + k];
                    if (!on_side[v] && lies_on(m->uvs + 2 * v, s)) {
                        on_side[v] = 1;
                        ++vertices;
                    }
                }
            if (vertices < 2 || side_edges[p][s] != vertices - 1)
                fail_msg("free side %d of patch %zu: %zu boundary edges for %zu vertices", s, p, side_edges[p][s],
                         vertices);
        }
    free(on_side);
    free(sorted);
    free(edges);
    return boundary;
}

/* No triangle repeats a position or has (nearly) zero area, and every vertex normal is a unit
 * vector on the side of the triangle's winding normal. */
static void check_triangles(const patches *t, const mesh_view *m) {
    double smallest = INFINITY;
    for (size_t tri = 0; tri < m->triangle_count; ++tri) {
        const uint32_t *c = m->indices + 3 * tri;
        assert_true(m->welded[c[0]] != m->welded[c[1]] && m->welded[c[1]] != m->welded[c[2]] &&
                    m->welded[c[0]] != m->welded[c[2]]);
        const double *p0 = m->positions + 3 * c[0], *p1 = m->positions + 3 * c[1], *p2 = m->positions + 3 * c[2];
        const double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        const double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        const double w[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                             e1[0] * e2[1] - e1[1] * e2[0]};
        const double area = 0.5 * sqrt(dot3(w, w));
        if (area < smallest) smallest = area;
        if (!(area > 1e-12 * t->diagonal * t->diagonal))
            fail_msg("triangle %zu of patch %u has area %g", tri, m->patch_of[tri], area);
        for (int k = 0; k < 3; ++k) {
            const double *n = m->normals + 3 * c[k];
            assert_close(dot3(n, n), 1.0, 1e-12);
            if (!(dot3(n, w) > 0))
                fail_msg("vertex %u's normal points against triangle %zu (patch %u)", c[k], tri, m->patch_of[tri]);
        }
    }
    print_message("smallest triangle area %.3g (diagonal^2 = %.3g)\n", smallest, t->diagonal * t->diagonal);
}

/* ---- Tests ------------------------------------------------------------------------------- */

static const double relative_tolerance = 1e-3;

/* Every patch of the adaptive teapot within the tolerance, measured here. The finest
 * tolerance (33k triangles, 2M nearest-point searches of this file's own) is left to the
 * Release run when quick. */
static void test_adaptive_deviation_on_every_patch(void **state) {
    const patches *t = *state;
    const double tolerances[] = {relative_tolerance * t->diagonal, 1e-2, 1e-3};
    const int count = test_quick() ? 2 : 3;
    for (int k = 0; k < count; ++k) {
        const double tolerance = tolerances[k];
        ppm_mesh mesh = tessellate(t, tolerance, 0);
        const mesh_view m = view_of(mesh);
        double per_patch[teapot_patches];
        const double worst = measure(t, &m, 10, per_patch);
        for (size_t p = 0; p < t->count; ++p)
            if (!(per_patch[p] <= tolerance))
                fail_msg("tolerance %g: patch %zu deviates by %.6g", tolerance, p, per_patch[p]);
        double reported = -1, requested = -1;
        assert_ppm_ok(ppm_mesh_get_double(mesh, "max_deviation", &reported));
        assert_ppm_ok(ppm_mesh_get_double(mesh, "tolerance", &requested));
        assert_true(requested == tolerance);
        assert_true(reported <= tolerance);
        /* The library's own figure agrees with this independent one (it samples more finely
         * near the maxima, so it may be slightly larger). */
        assert_true(fabs(reported - worst) <= 0.02 * tolerance);
        print_message("tolerance %g: %zu triangles, deviation %.6g (library %.6g)\n", tolerance, m.triangle_count,
                      worst, reported);
        ppm_mesh_release(mesh);
    }
}

static void test_adaptive_is_watertight(void **state) {
    const patches *t = *state;
    ppm_mesh mesh = tessellate(t, relative_tolerance * t->diagonal, 0);
    const mesh_view m = view_of(mesh);
    check_welding(&m);
    const size_t boundary = check_watertight(t, &m);
    print_message("%zu triangles, %zu vertices, %zu positions, %zu boundary edges\n", m.triangle_count, m.vertex_count,
                  m.welded_count, boundary);
    ppm_mesh_release(mesh);
}

static void test_adaptive_has_no_degenerate_triangles(void **state) {
    const patches *t = *state;
    ppm_mesh mesh = tessellate(t, relative_tolerance * t->diagonal, 0);
    const mesh_view m = view_of(mesh);
    check_triangles(t, &m);
    /* The lid apex and the bottom centre are vertices, each surrounded by a fan. */
    const double apexes[2][3] = {{0, 0, 3.15}, {0, 0, 0}};
    for (int a = 0; a < 2; ++a) {
        size_t fan = 0;
        for (size_t tri = 0; tri < m.triangle_count; ++tri)
            for (int k = 0; k < 3; ++k)
                if (!memcmp(m.positions + 3 * m.indices[3 * tri + k], apexes[a], sizeof apexes[a])) ++fan;
        if (fan < 8) fail_msg("apex %d is in %zu triangles", a, fan);
    }
    ppm_mesh_release(mesh);
}

/* Coarsest uniform grid whose deviation, measured here, is within tolerance; the library's
 * figure gives the starting guess. */
static uint32_t coarsest_uniform(const patches *t, double tolerance) {
    uint32_t lo = 0, hi = 1; /* lo fails (or is 0), hi passes */
    for (;;) {
        ppm_mesh mesh = tessellate(t, 0, hi);
        double d = 0;
        assert_ppm_ok(ppm_mesh_get_double(mesh, "max_deviation", &d));
        ppm_mesh_release(mesh);
        if (d <= tolerance) break;
        lo = hi;
        hi *= 2;
    }
    while (hi - lo > 1) {
        const uint32_t mid = (lo + hi) / 2;
        ppm_mesh mesh = tessellate(t, 0, mid);
        double d = 0;
        assert_ppm_ok(ppm_mesh_get_double(mesh, "max_deviation", &d));
        ppm_mesh_release(mesh);
        if (d <= tolerance)
            hi = mid;
        else
            lo = mid;
    }
    /* Confirm with this file's measurement (the Release run; quick runs take the library's
     * figure, which test_uniform_counts checks against this file's). */
    if (test_quick()) return hi;
    for (;;) {
        ppm_mesh mesh = tessellate(t, 0, hi);
        const mesh_view m = view_of(mesh);
        const double d = measure(t, &m, 10, NULL);
        ppm_mesh_release(mesh);
        if (d <= tolerance) break;
        ++hi;
    }
    while (hi > 1) {
        ppm_mesh mesh = tessellate(t, 0, hi - 1);
        const mesh_view m = view_of(mesh);
        const double d = measure(t, &m, 10, NULL);
        ppm_mesh_release(mesh);
        if (d > tolerance) break;
        --hi;
    }
    return hi;
}

static void test_adaptive_needs_at_most_half_of_uniform(void **state) {
    const patches *t = *state;
    const double tolerance = relative_tolerance * t->diagonal;
    ppm_mesh mesh = tessellate(t, tolerance, 0);
    size_t adaptive = 0;
    assert_ppm_ok(ppm_mesh_get_triangles(mesh, NULL, &adaptive));
    ppm_mesh_release(mesh);
    const uint32_t n = coarsest_uniform(t, tolerance);
    const size_t uniform = t->count * n * n * 2;
    print_message("tolerance %g: adaptive %zu triangles, coarsest passing uniform grid %u: %zu (ratio %.3f)\n",
                  tolerance, adaptive, n, uniform, (double)adaptive / uniform);
    assert_true(2 * adaptive <= uniform);
}

static void test_uniform_counts(void **state) {
    const patches *t = *state;
    const uint32_t grids[] = {1, 2, 5, 16};
    for (int k = 0; k < 4; ++k) {
        const uint32_t n = grids[k];
        ppm_mesh mesh = tessellate(t, NAN, n); /* the tolerance is ignored */
        const mesh_view m = view_of(mesh);
        assert_int_equal(m.triangle_count, (size_t)teapot_patches * n * n * 2);
        assert_int_equal(m.vertex_count, (size_t)teapot_patches * (n + 1) * (n + 1));
        check_welding(&m);
        double tolerance = -1, reported = -1;
        assert_ppm_ok(ppm_mesh_get_double(mesh, "tolerance", &tolerance));
        assert_true(tolerance == 0);
        assert_ppm_ok(ppm_mesh_get_double(mesh, "max_deviation", &reported));
        const int measured = n == 5 || (n > 5 && !test_quick());
        if (measured) {
            const double worst = measure(t, &m, 10, NULL);
            assert_true(fabs(reported - worst) <= 0.02 * worst);
        }
        ppm_mesh_release(mesh);
    }
}

/* A patch bent in u only (a quarter cylinder) is refined in u only: sixteen times tighter
 * costs about four times the triangles, not sixteen. */
static void test_adaptive_is_anisotropic(void **state) {
    (void)state;
    const double profile[4][2] = {{1, 0}, {1, 0.5523}, {0.5523, 1}, {0, 1}};
    double cylinder[48];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            cylinder[3 * (4 * i + j)] = profile[j][0];
            cylinder[3 * (4 * i + j) + 1] = i / 3.0;
            cylinder[3 * (4 * i + j) + 2] = profile[j][1];
        }
    patches one = {1, cylinder, 1};
    size_t counts[2];
    for (int k = 0; k < 2; ++k) {
        const double tolerance = k == 0 ? 1e-3 : 1e-3 / 16;
        ppm_mesh mesh = tessellate(&one, tolerance, 0);
        const mesh_view m = view_of(mesh);
        assert_true(measure(&one, &m, 10, NULL) <= tolerance);
        counts[k] = m.triangle_count;
        ppm_mesh_release(mesh);
    }
    print_message("quarter cylinder: %zu and %zu triangles\n", counts[0], counts[1]);
    assert_true(counts[1] < 6 * counts[0]);

    /* A flat patch needs the fewest triangles the scheme makes and deviates by nothing. */
    double flat[48];
    for (int k = 0; k < 16; ++k) {
        flat[3 * k] = (k % 4) / 3.0;
        flat[3 * k + 1] = (k / 4) / 3.0;
        flat[3 * k + 2] = 0;
    }
    ppm_mesh mesh = NULL;
    assert_ppm_ok(ppm_tessellate_patches(flat, 1, 1e-9, 0, &mesh));
    size_t triangles = 0;
    double deviation = -1;
    assert_ppm_ok(ppm_mesh_get_triangles(mesh, NULL, &triangles));
    assert_ppm_ok(ppm_mesh_get_double(mesh, "max_deviation", &deviation));
    assert_true(triangles <= 4);
    assert_true(deviation <= 1e-15);
    ppm_mesh_release(mesh);
}

static void test_mesh_reference_counting(void **state) {
    const patches *t = *state;
    ppm_mesh mesh = tessellate(t, 0, 2);
    const uint32_t *indices = NULL;
    size_t count = 0;
    assert_ppm_ok(ppm_mesh_retain(mesh));
    ppm_mesh_release(mesh);
    assert_ppm_ok(ppm_mesh_get_triangles(mesh, &indices, &count)); /* still alive */
    assert_int_equal(count, teapot_patches * 8);
    ppm_mesh_release(mesh);
    ppm_mesh_release(NULL);
}

static void test_bad_arguments(void **state) {
    const patches *t = *state;
    ppm_mesh mesh = NULL;
    const double tolerance = 1e-2;
    assert_ppm_error(ppm_tessellate_patches(NULL, 1, tolerance, 0, &mesh), PPM_ERROR_INVALID_ARGUMENT,
                     "control_points");
    assert_ppm_error(ppm_tessellate_patches(t->points, 0, tolerance, 0, &mesh), PPM_ERROR_INVALID_ARGUMENT,
                     "patch_count");
    assert_ppm_error(ppm_tessellate_patches(t->points, 20000000, tolerance, 0, &mesh), PPM_ERROR_INVALID_ARGUMENT,
                     "patch_count");
    assert_ppm_error(ppm_tessellate_patches(t->points, t->count, tolerance, 0, NULL), PPM_ERROR_INVALID_ARGUMENT,
                     "out_mesh");
    const double bad[] = {0, -1, NAN, INFINITY};
    for (int k = 0; k < 4; ++k)
        assert_ppm_error(ppm_tessellate_patches(t->points, t->count, bad[k], 0, &mesh), PPM_ERROR_INVALID_ARGUMENT,
                         "tolerance");
    assert_ppm_error(ppm_tessellate_patches(t->points, t->count, tolerance, 4097, &mesh), PPM_ERROR_INVALID_ARGUMENT,
                     "grid");
    /* Absurd budgets are refused up front, naming the limit. */
    assert_ppm_error(ppm_tessellate_patches(t->points, t->count, 0, 4096, &mesh), PPM_ERROR_INVALID_ARGUMENT,
                     "200000000");
    assert_ppm_error(ppm_tessellate_patches(t->points, t->count, 1e-12, 0, &mesh), PPM_ERROR_INVALID_ARGUMENT,
                     "200000000");
    double *copy = malloc(sizeof(double) * 48 * t->count);
    assert_non_null(copy);
    memcpy(copy, t->points, sizeof(double) * 48 * t->count);
    copy[48 * 7 + 3 * 5 + 1] = NAN;
    assert_ppm_error(ppm_tessellate_patches(copy, t->count, tolerance, 0, &mesh), PPM_ERROR_INVALID_ARGUMENT,
                     "patch 7 control point 5");
    free(copy);
    assert_null(mesh); /* no failed call wrote it */

    const double *d = NULL;
    const uint32_t *u = NULL;
    size_t n = 0;
    double value = 0;
    assert_ppm_error(ppm_mesh_retain(NULL), PPM_ERROR_INVALID_ARGUMENT, "mesh");
    assert_ppm_error(ppm_mesh_get_vertices(NULL, &d, &d, &d, &n), PPM_ERROR_INVALID_ARGUMENT, "mesh");
    assert_ppm_error(ppm_mesh_get_triangles(NULL, &u, &n), PPM_ERROR_INVALID_ARGUMENT, "mesh");
    assert_ppm_error(ppm_mesh_get_triangle_patches(NULL, &u), PPM_ERROR_INVALID_ARGUMENT, "mesh");
    assert_ppm_error(ppm_mesh_get_welded_vertices(NULL, &u, &n), PPM_ERROR_INVALID_ARGUMENT, "mesh");
    assert_ppm_error(ppm_mesh_get_double(NULL, "max_deviation", &value), PPM_ERROR_INVALID_ARGUMENT, "mesh");
    mesh = tessellate(t, 0, 1);
    assert_ppm_error(ppm_mesh_get_triangle_patches(mesh, NULL), PPM_ERROR_INVALID_ARGUMENT, "out_patch_ids");
    assert_ppm_error(ppm_mesh_get_double(mesh, NULL, &value), PPM_ERROR_INVALID_ARGUMENT, "key");
    assert_ppm_error(ppm_mesh_get_double(mesh, "max_deviation", NULL), PPM_ERROR_INVALID_ARGUMENT, "out_value");
    assert_ppm_error(ppm_mesh_get_double(mesh, "deviation", &value), PPM_ERROR_INVALID_ARGUMENT, "deviation");
    /* All outputs of the array getters are optional. */
    assert_ppm_ok(ppm_mesh_get_vertices(mesh, NULL, NULL, NULL, NULL));
    assert_ppm_ok(ppm_mesh_get_triangles(mesh, NULL, NULL));
    assert_ppm_ok(ppm_mesh_get_welded_vertices(mesh, NULL, NULL));
    ppm_mesh_release(mesh);
}

/* ---- The ppm-tess tool ------------------------------------------------------------------- */

static const char *tool_path;

typedef struct tool_fixture {
    char dir[256];
} tool_fixture;

static int tool_setup(void **state) {
    tool_fixture *f = calloc(1, sizeof *f);
    if (!f) return -1;
    if (test_make_folder(f->dir, sizeof f->dir, "ppm_test_tess_") != 0) {
        free(f);
        return -1;
    }
    *state = f;
    return 0;
}

static int tool_teardown(void **state) {
    tool_fixture *f = *state;
    test_remove_folder(f->dir);
    free(f);
    return 0;
}

/* Runs the tool with `args` (NULL-terminated), stderr to DIR/stderr.txt; returns the exit
 * status. */
static int run_tool(tool_fixture *f, const char *const *args) {
    char err_path[600];
    snprintf(err_path, sizeof err_path, "%s/stderr.txt", f->dir);
    const char *argv[16];
    int argc = 0;
    argv[argc++] = tool_path;
    while (args[argc - 1] && argc < 15) {
        argv[argc] = args[argc - 1];
        ++argc;
    }
    argv[argc] = NULL;
    const pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        const int fd = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd < 0) _exit(99);
        dup2(fd, 2);
        const int null = open("/dev/null", O_WRONLY);
        if (null >= 0) dup2(null, 1);
        execv(tool_path, (char *const *)argv);
        _exit(98);
    }
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    return WEXITSTATUS(status);
}

static int stderr_contains(tool_fixture *f, const char *needle) {
    char path[600], text[4096];
    snprintf(path, sizeof path, "%s/stderr.txt", f->dir);
    FILE *file = fopen(path, "r");
    assert_non_null(file);
    const size_t n = fread(text, 1, sizeof text - 1, file);
    fclose(file);
    text[n] = '\0';
    return strstr(text, needle) != NULL;
}

/* Number of lines starting with `prefix`. */
static size_t count_lines(const char *path, const char *prefix) {
    FILE *file = fopen(path, "r");
    assert_non_null(file);
    char line[512];
    size_t count = 0;
    while (fgets(line, sizeof line, file))
        if (!strncmp(line, prefix, strlen(prefix))) ++count;
    fclose(file);
    return count;
}

static void test_tool_writes_obj_that_loads_back(void **state) {
    tool_fixture *f = *state;
    char obj[600], ply[600];
    snprintf(obj, sizeof obj, "%s/teapot.obj", f->dir);
    snprintf(ply, sizeof ply, "%s/teapot.ply", f->dir);
    const char *args[] = {PPM_TEAPOT, "-o", obj, "--tolerance", "1e-3", "--relative", NULL};
    assert_int_equal(run_tool(f, args), 0);
    assert_true(stderr_contains(f, "triangles"));
    assert_true(stderr_contains(f, "max deviation"));

    /* The same tessellation through the API: the OBJ has its triangles and welded positions. */
    patches t = read_teapot();
    ppm_mesh mesh = tessellate(&t, 1e-3 * t.diagonal, 0);
    const mesh_view m = view_of(mesh);
    assert_int_equal(count_lines(obj, "f "), m.triangle_count);
    assert_int_equal(count_lines(obj, "v "), m.welded_count);
    assert_int_equal(count_lines(obj, "vt "), m.vertex_count);
    assert_int_equal(count_lines(obj, "vn "), m.vertex_count);

    /* Loaded into a scene, a ray down onto the lid hits the mesh within the tolerance of the
     * exact patch. */
    ppm_context context = NULL;
    ppm_scene exact = NULL, tessellated = NULL;
    uint32_t id = 99;
    size_t primitives = 0;
    assert_ppm_ok(ppm_context_create(&context));
    assert_ppm_ok(ppm_scene_create(context, &exact));
    assert_ppm_ok(ppm_scene_create(context, &tessellated));
    assert_ppm_ok(ppm_scene_load_bpt(exact, PPM_TEAPOT, NULL));
    assert_ppm_ok(ppm_scene_load_obj(tessellated, obj, &id));
    assert_ppm_ok(ppm_scene_get_primitive_count(tessellated, id, &primitives));
    assert_int_equal(primitives, m.triangle_count);
    assert_ppm_ok(ppm_scene_commit(exact));
    assert_ppm_ok(ppm_scene_commit(tessellated));
    const ppm_ray rays[2] = {{{0.3, 0.2, 10}, 0, {0, 0, -1}, INFINITY}, {{10, 0.1, 1.5}, 0, {-1, 0, 0}, INFINITY}};
    ppm_hit a[2], b[2];
    assert_ppm_ok(ppm_scene_intersect(exact, rays, 2, a));
    assert_ppm_ok(ppm_scene_intersect(tessellated, rays, 2, b));
    for (int k = 0; k < 2; ++k) {
        assert_true(isfinite(a[k].t) && isfinite(b[k].t));
        /* Near-perpendicular rays: the hit distances differ by about the mesh's deviation. */
        assert_close(a[k].t, b[k].t, 2 * 1e-3 * t.diagonal);
    }
    ppm_scene_release(exact);
    ppm_scene_release(tessellated);
    ppm_context_release(context);
    ppm_mesh_release(mesh);
    free(t.points);

    /* PLY, by extension; the folder holds no temporary files afterwards. */
    const char *ply_args[] = {PPM_TEAPOT, "-o", ply, "--grid", "3", NULL};
    assert_int_equal(run_tool(f, ply_args), 0);
    assert_int_equal(count_lines(ply, "ply"), 1);
    char header[64];
    snprintf(header, sizeof header, "element face %d\n", teapot_patches * 3 * 3 * 2);
    assert_int_equal(count_lines(ply, header), 1);
    DIR *dir = opendir(f->dir);
    assert_non_null(dir);
    struct dirent *entry;
    int files = 0;
    while ((entry = readdir(dir)))
        if (entry->d_name[0] != '.') ++files;
    closedir(dir);
    assert_int_equal(files, 3); /* teapot.obj, teapot.ply, stderr.txt */
}

static void test_tool_errors(void **state) {
    tool_fixture *f = *state;
    char out[600], missing[600];
    snprintf(out, sizeof out, "%s/out.obj", f->dir);
    snprintf(missing, sizeof missing, "%s/missing.bpt", f->dir);
    const char *no_output[] = {PPM_TEAPOT, NULL};
    assert_int_equal(run_tool(f, no_output), 1);
    const char *bad_option[] = {PPM_TEAPOT, "-o", out, "--frobnicate", NULL};
    assert_int_equal(run_tool(f, bad_option), 1);
    assert_true(stderr_contains(f, "--frobnicate"));
    /* An output whose extension names no format ppm-tess writes is a usage error, not OBJ
     * text under another name. */
    char stl[600];
    snprintf(stl, sizeof stl, "%s/out.stl", f->dir);
    const char *stl_output[] = {PPM_TEAPOT, "-o", stl, NULL};
    assert_int_equal(run_tool(f, stl_output), 1);
    assert_true(stderr_contains(f, "must end in .obj or .ply"));
    assert_int_equal(access(stl, F_OK), -1);
    const char *ply_flag_obj_name[] = {PPM_TEAPOT, "-o", out, "--ply", NULL};
    assert_int_equal(run_tool(f, ply_flag_obj_name), 1);
    const char *bad_number[] = {PPM_TEAPOT, "-o", out, "--tolerance", "abc", NULL};
    assert_int_equal(run_tool(f, bad_number), 1);
    const char *no_input[] = {missing, "-o", out, NULL};
    assert_int_equal(run_tool(f, no_input), 2);
    assert_true(stderr_contains(f, missing));
    const char *too_fine[] = {PPM_TEAPOT, "-o", out, "--tolerance", "1e-12", NULL};
    assert_int_equal(run_tool(f, too_fine), 2);
    assert_true(stderr_contains(f, "200000000"));
    assert_int_equal(access(out, F_OK), -1); /* nothing written */
    const char *help[] = {"-h", NULL};
    assert_int_equal(run_tool(f, help), 0);
    const char *version[] = {"--version", NULL};
    assert_int_equal(run_tool(f, version), 0);
}

int main(int argc, char **argv) {
    if (argc == 3 && !strcmp(argv[1], "--tool")) {
        tool_path = argv[2];
        const struct CMUnitTest tool_tests[] = {
            cmocka_unit_test_setup_teardown(test_tool_writes_obj_that_loads_back, tool_setup, tool_teardown),
            cmocka_unit_test_setup_teardown(test_tool_errors, tool_setup, tool_teardown),
        };
        return cmocka_run_group_tests_name("ppm-tess", tool_tests, NULL, NULL);
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_adaptive_deviation_on_every_patch, setup, teardown),
        cmocka_unit_test_setup_teardown(test_adaptive_is_watertight, setup, teardown),
        cmocka_unit_test_setup_teardown(test_adaptive_has_no_degenerate_triangles, setup, teardown),
        cmocka_unit_test_setup_teardown(test_adaptive_needs_at_most_half_of_uniform, setup, teardown),
        cmocka_unit_test_setup_teardown(test_uniform_counts, setup, teardown),
        cmocka_unit_test_setup_teardown(test_adaptive_is_anisotropic, setup, teardown),
        cmocka_unit_test_setup_teardown(test_mesh_reference_counting, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_arguments, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
