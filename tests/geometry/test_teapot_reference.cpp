// SPDX-License-Identifier: Apache-2.0
// Accuracy of libppm's ray / teapot intersection against an independent reference.
//
// The reference (tools/reference/reference_intersector.*) finds ALL roots of a ray with the 32
// bicubic patches by subdividing each patch with De Casteljau in world space, in long double,
// culling sub-patches whose control-point hull misses the ray, down to leaves of ~1e-6 of the
// model diagonal, where a long-double Newton iteration on (u, v, t) solves
// S(u, v) = o + t d. It shares no code and no algorithm with libppm (ray-space projection,
// Krawczyk interval test, double-precision Newton on two unknowns, Embree traversal), reads
// the .bpt file with its own parser, and works in a wider type (rounding ~1e-19), so
// agreement is evidence that both are right. Where Newton fails in a leaf (tangent rays,
// collapsed patch edges) it measures the ray's closest approach to the leaf instead:
// "singular" roots (distance at rounding level: a real hit) and "tangent" near misses
// (distance reported). The reference is itself checked: it must see the surface point every
// constructed ray passes through, and agree with a coarser-leaved run of itself.
//
// Against it, through the public API only (ppm_scene_intersect / ppm_scene_occluded /
// ppm_hit_spawn_ray, default tolerance 1e-9 of the bounding-box diagonal):
//   miss       the reference has a robust root (below) in [tnear, tfar] and libppm reports
//              nothing, or libppm's hit lies more than the tolerance beyond it;
//   false hit  libppm's hit point (prim, u, v) is farther than 1.5 tolerances from the ray,
//              or lies before every root the reference knows and is not near one;
//   wrong t    |t_lib - t_ref| |d| > 1e-9 * diagonal for the matching robust root.
// Robust roots are those through which the ray dips deeper than 1e-15 of the diagonal (and
// roots at collapsed edges). A ray tangent in real arithmetic, once rounded to double,
// crosses or misses the surface by ~1e-17, which no double-precision method can resolve: for
// its roots, and for near misses within 1.5 tolerances, a hit and a miss are both right (a
// hit must still be a valid point); such rays are counted as "tangent-ambiguous". Rays for
// which the reference hit its work bound are "undecided": skipped, counted, and only a tiny
// fraction of them is allowed.
//
// PPM_TEST_QUICK=1 or --quick cuts the ray counts about tenfold (sanitizer builds).
// --presplit N sets the scene's "patch_presplit" (default: libppm's): the answers must not
// depend on it, and ctest runs the suite at 1 and 4 as well as at the default.
#include <ppm/ppm.h>

#include "reference_intersector.h"
#include "test_support.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

using ref::cross;
using ref::normalize;
using ref::real;
using ref::RootKind;

// ---------------------------------------------------------------------------------------
// Shared state: the scene (libppm) and the reference, built once.

struct Fixture {
    ppm_context context = nullptr;
    ppm_scene scene = nullptr;
    ref::Intersector *reference = nullptr;
    double diagonal = 0;  // of the scene's bounding box
    double tolerance = 0; // absolute: scene tolerance * diagonal
    bool quick = false;
    int presplit = 0; // scene setting "patch_presplit"; 0: libppm's default
};
Fixture g;

int scaled(int n) { return g.quick ? std::max(1, n / 10) : n; }

double uniform(test_rng &rng) { return test_rng_uniform(&rng); }

// Uniform direction on the unit sphere.
void random_direction(test_rng &rng, double d[3]) {
    const double z = 2 * uniform(rng) - 1, phi = 2 * M_PI * uniform(rng);
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    d[0] = r * std::cos(phi);
    d[1] = r * std::sin(phi);
    d[2] = z;
}

ppm_ray make_ray(const double o[3], const double d[3], double tnear = 0, double tfar = INFINITY) {
    ppm_ray r;
    for (int c = 0; c < 3; ++c) {
        r.org[c] = o[c];
        r.dir[c] = d[c];
    }
    r.tnear = tnear;
    r.tfar = tfar;
    return r;
}

// A ray through `point` (long double) at distance `length` along the unit direction `dir`:
// origin = point - length * dir, rounded to double.
ppm_ray ray_through(const real point[3], const real dir[3], real length) {
    double o[3], d[3];
    for (int c = 0; c < 3; ++c) {
        d[c] = static_cast<double>(dir[c]);
        o[c] = static_cast<double>(point[c] - length * dir[c]);
    }
    return make_ray(o, d);
}

double dir_length(const ppm_ray &r) {
    return std::sqrt(r.dir[0] * r.dir[0] + r.dir[1] * r.dir[1] + r.dir[2] * r.dir[2]);
}

ref::Result reference_roots(const ppm_ray &r) {
    const real o[3] = {r.org[0], r.org[1], r.org[2]}, d[3] = {r.dir[0], r.dir[1], r.dir[2]};
    return g.reference->intersect(o, d, r.tnear, r.tfar);
}

ppm_hit library_hit(const ppm_ray &r) {
    ppm_hit h;
    const ppm_status s = ppm_scene_intersect(g.scene, &r, 1, &h);
    if (s != PPM_OK) fail_msg("ppm_scene_intersect: %s", ppm_last_error_message());
    return h;
}

bool library_occluded(const ppm_ray &r) {
    uint8_t occluded = 2;
    const ppm_status s = ppm_scene_occluded(g.scene, &r, 1, &occluded);
    if (s != PPM_OK) fail_msg("ppm_scene_occluded: %s", ppm_last_error_message());
    assert_true(occluded == 0 || occluded == 1);
    return occluded == 1;
}

// Roots a hit may match: real roots and tangent touches within 1.5 tolerances.
bool is_candidate(const ref::Root &r) { return r.kind != RootKind::tangent || r.distance <= 1.5L * g.tolerance; }
// Real roots libppm must find: those whose dip through the surface is deeper than 1e-15 of
// the diagonal (~20 ulps of the teapot's coordinates, well above the rounding of a
// double-precision evaluation of the surface), and roots at collapsed edges. Shallower ones
// come from rays tangent in real arithmetic, which after rounding to double cross or miss
// the surface by ~1e-17: no double-precision method can tell which, so either answer is
// right (the hit must still be a valid point).
bool is_robust(const ref::Root &r) {
    return r.kind != RootKind::tangent && (r.degenerate_normal || r.dip > 1e-15L * g.diagonal);
}
const ref::Root *first_real(const ref::Result &res) {
    for (const ref::Root &r : res.roots)
        if (r.kind != RootKind::tangent) return &r;
    return nullptr;
}
const ref::Root *first_robust(const ref::Result &res) {
    for (const ref::Root &r : res.roots)
        if (is_robust(r)) return &r;
    return nullptr;
}
const ref::Root *first_candidate(const ref::Result &res) {
    for (const ref::Root &r : res.roots)
        if (is_candidate(r)) return &r;
    return nullptr;
}

// Number of distinct points among the real roots (seams give one root per patch).
int distinct_real_roots(const ref::Result &res, double dlen) {
    int count = 0;
    real last = -INFINITY;
    for (const ref::Root &r : res.roots) {
        if (r.kind == RootKind::tangent) continue;
        if ((r.t - last) * dlen > 10 * g.tolerance) ++count;
        last = r.t;
    }
    return count;
}

// ---------------------------------------------------------------------------------------
// Comparison of one ray and its tallies.

struct Tally {
    const char *name;
    size_t rays = 0, hits = 0, misses = 0, false_hits = 0, wrong_t = 0, undecided = 0, ambiguous = 0,
           other = 0;  // other: case-specific failed checks
    double max_dt = 0; // over matched real roots, relative to the diagonal
    ppm_ray worst{};   // the ray of max_dt
    int printed = 0;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
};

Tally totals{"all"};

const char *kind_name(RootKind k) {
    return k == RootKind::proper ? "proper" : k == RootKind::singular ? "singular" : "tangent";
}

void print_ray(const char *what, const Tally &tally, const ppm_ray &r, const ppm_hit &h, const ref::Result &res,
               const char *detail) {
    std::printf("  %s [%s]: %s\n    org = {%.17g, %.17g, %.17g} dir = {%.17g, %.17g, %.17g} "
                "tnear = %.17g tfar = %.17g\n    libppm: t = %.17g prim %u u = %.17g v = %.17g\n",
                what, tally.name, detail, r.org[0], r.org[1], r.org[2], r.dir[0], r.dir[1], r.dir[2], r.tnear, r.tfar,
                h.t, h.prim_id, h.u, h.v);
    int shown = 0;
    for (const ref::Root &x : res.roots) {
        if (++shown > 6) break;
        std::printf("    reference: t = %.17Lg patch %d u = %.17Lg v = %.17Lg %s distance %.3Lg "
                    "sin %.3Lg dip %.3Lg%s\n",
                    x.t, x.patch, x.u, x.v, kind_name(x.kind), x.distance, x.sin_angle, x.dip,
                    is_robust(x) ? "" : " (not robust)");
    }
    if (res.roots.empty()) std::printf("    reference: no root\n");
}

void report(Tally &tally, size_t Tally::*counter, const char *what, const ppm_ray &r, const ppm_hit &h,
            const ref::Result &res, const char *detail) {
    ++(tally.*counter);
    if (tally.printed++ < 8) print_ray(what, tally, r, h, res, detail);
}

// Whether libppm's hit is a point of the surface on the ray: (prim, u, v) evaluated in long
// double lies within 1.5 tolerances of o + t d; p and the normal are consistent and finite.
bool hit_is_valid(const ppm_ray &r, const ppm_hit &h, std::string &why) {
    char text[200];
    if (h.geom_id != 0 || h.prim_id >= g.reference->patches().size()) {
        why = "bad geom_id / prim_id";
        return false;
    }
    if (!(h.u >= 0 && h.u <= 1 && h.v >= 0 && h.v <= 1)) {
        why = "(u, v) outside [0, 1]";
        return false;
    }
    const double nl = std::sqrt(h.ng[0] * h.ng[0] + h.ng[1] * h.ng[1] + h.ng[2] * h.ng[2]);
    if (!(std::fabs(nl - 1) < 1e-9)) {
        std::snprintf(text, sizeof text, "normal not unit or not finite: |ng| = %.17g", nl);
        why = text;
        return false;
    }
    real s[3];
    ref::evaluate(g.reference->patches()[h.prim_id], h.u, h.v, s);
    real off = 0, p_off = 0;
    for (int c = 0; c < 3; ++c) {
        const real e = s[c] - (static_cast<real>(r.org[c]) + static_cast<real>(h.t) * r.dir[c]);
        off += e * e;
        p_off += (s[c] - h.p[c]) * (s[c] - h.p[c]);
    }
    off = std::sqrt(off);
    p_off = std::sqrt(p_off);
    if (!(off <= 1.5L * g.tolerance) || !(p_off <= 1e-3L * g.tolerance) || !(h.p_error >= g.tolerance)) {
        std::snprintf(text, sizeof text,
                      "point S(u, v) is %.3Lg from o + t d (tolerance %.3g), p is %.3Lg from "
                      "S(u, v), p_error %.3g",
                      off, g.tolerance, p_off, h.p_error);
        why = text;
        return false;
    }
    return true;
}

enum class Verdict { ok, ambiguous, miss, false_hit, wrong_t, undecided };

// Compares libppm's hit for `r` with the reference's roots `res` (computed for the same ray
// and interval) and updates the tally.
Verdict compare(Tally &tally, const ppm_ray &r, const ppm_hit &h, const ref::Result &res) {
    ++tally.rays;
    if (!res.decided) {
        ++tally.undecided;
        return Verdict::undecided;
    }
    const double dlen = dir_length(r);
    const ref::Root *real_root = first_robust(res), *candidate = first_candidate(res);
    const bool hit = h.geom_id != PPM_INVALID_ID;
    if (!hit) {
        if (!(std::isinf(h.t) && h.t > 0)) {
            report(tally, &Tally::other, "BAD MISS RECORD", r, h, res, "miss with finite t");
            return Verdict::false_hit;
        }
        if (real_root) {
            report(tally, &Tally::misses, "MISS", r, h, res, "reference root, libppm miss");
            return Verdict::miss;
        }
        if (candidate) {
            ++tally.ambiguous;
            return Verdict::ambiguous;
        }
        return Verdict::ok;
    }
    ++tally.hits;
    std::string why;
    if (!hit_is_valid(r, h, why)) {
        report(tally, &Tally::false_hits, "FALSE HIT", r, h, res, why.c_str());
        return Verdict::false_hit;
    }
    if (!candidate) {
        report(tally, &Tally::false_hits, "FALSE HIT", r, h, res, "reference has no root");
        return Verdict::false_hit;
    }
    if (real_root && (h.t - real_root->t) * dlen > g.tolerance) {
        report(tally, &Tally::misses, "MISS", r, h, res, "libppm skipped the nearest root");
        return Verdict::miss;
    }
    if ((candidate->t - h.t) * dlen > g.tolerance) {
        // The point is on the surface (checked above), before every root the reference knows.
        // Near the reference's first root (a grazing ray, where the surface stays within the
        // tolerance of the ray over a long stretch) it is an inaccurate t; elsewhere the
        // reference has missed a surface or libppm invented one.
        real far = 0;
        for (int c = 0; c < 3; ++c) {
            const real e = (candidate->t - static_cast<real>(h.t)) * r.dir[c];
            far += e * e;
        }
        if (std::sqrt(far) <= 1e-4L * g.diagonal && !is_robust(*candidate)) {
            // A touch: the surface stays within the tolerance of the ray along a stretch
            // around the touch point, and any point of it is a right answer.
            ++tally.ambiguous;
            return Verdict::ambiguous;
        }
        if (std::sqrt(far) <= 1e-4L * g.diagonal) {
            if (static_cast<double>(std::sqrt(far)) / g.diagonal > tally.max_dt) {
                tally.max_dt = static_cast<double>(std::sqrt(far)) / g.diagonal;
                tally.worst = r;
            }
            char text[160];
            std::snprintf(text, sizeof text, "on the surface but %.3Lg before the nearest root (tolerance %.3g)",
                          std::sqrt(far), g.tolerance);
            report(tally, &Tally::wrong_t, "WRONG T", r, h, res, text);
            return Verdict::wrong_t;
        }
        report(tally, &Tally::false_hits, "FALSE HIT", r, h, res,
               "before every reference root (the point is on the surface: reference suspect)");
        return Verdict::false_hit;
    }
    // The matching root: the nearest robust one if it is within the tolerance (at a seam or
    // a collapsed edge a near miss of a neighbouring patch may be nearer still), else the
    // nearest candidate of any kind.
    const ref::Root *match = nullptr, *robust = nullptr;
    for (const ref::Root &x : res.roots) {
        if (is_candidate(x) && (!match || std::fabs(x.t - h.t) < std::fabs(match->t - h.t))) match = &x;
        if (is_robust(x) && (!robust || std::fabs(x.t - h.t) < std::fabs(robust->t - h.t))) robust = &x;
    }
    if (robust && static_cast<double>(std::fabs(robust->t - h.t)) * dlen <= g.tolerance) match = robust;
    const double dt = static_cast<double>(std::fabs(match->t - h.t)) * dlen;
    if (!is_robust(*match)) {
        // A touch within the tolerance: where along it the hit lies is not defined more
        // precisely than the point's validity, checked above.
        ++tally.ambiguous;
        return Verdict::ambiguous;
    }
    if (dt / g.diagonal > tally.max_dt) {
        tally.max_dt = dt / g.diagonal;
        tally.worst = r;
    }
    if (dt > g.tolerance) {
        char text[120];
        std::snprintf(text, sizeof text, "|dt| |d| = %.3g > tolerance %.3g", dt, g.tolerance);
        report(tally, &Tally::wrong_t, "WRONG T", r, h, res, text);
        return Verdict::wrong_t;
    }
    return Verdict::ok;
}

// Prints the one-line summary, adds to the totals and asserts.
void finish(Tally &t, const char *extra = "") {
    std::printf("%s: %zu rays, %zu hits, %zu misses, %zu false hits, %zu wrong t, "
                "%zu undecided, %zu tangent-ambiguous, %zu other failures, max |dt|/diag %.3g%s\n",
                t.name, t.rays, t.hits, t.misses, t.false_hits, t.wrong_t, t.undecided, t.ambiguous, t.other, t.max_dt,
                extra);
    if (t.max_dt > 1e-12)
        std::printf("  (max |dt| on org = {%.17g, %.17g, %.17g} dir = {%.17g, %.17g, %.17g} "
                    "tnear = %.17g)\n",
                    t.worst.org[0], t.worst.org[1], t.worst.org[2], t.worst.dir[0], t.worst.dir[1], t.worst.dir[2],
                    t.worst.tnear);
    std::printf("  (%s: %.1f s)\n", t.name,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t.start).count());
    std::fflush(stdout);
    totals.rays += t.rays;
    totals.hits += t.hits;
    totals.misses += t.misses;
    totals.false_hits += t.false_hits;
    totals.wrong_t += t.wrong_t;
    totals.undecided += t.undecided;
    totals.ambiguous += t.ambiguous;
    totals.other += t.other;
    totals.max_dt = std::max(totals.max_dt, t.max_dt);
    assert_int_equal(t.misses, 0);
    assert_int_equal(t.false_hits, 0);
    assert_int_equal(t.wrong_t, 0);
    assert_int_equal(t.other, 0);
    // The reference's work bound may leave a tiny fraction of rays undecided.
    assert_true(t.undecided * 500 <= t.rays);
}

// A case-specific check that failed: counted, printed (with the reference roots).
void check(Tally &t, bool ok, const char *what, const ppm_ray &r, const ppm_hit &h, const ref::Result &res) {
    if (!ok) report(t, &Tally::other, "CHECK FAILED", r, h, res, what);
}

// ---------------------------------------------------------------------------------------
// Geometry helpers on the reference's patches (long double).

// Unit normal of patch `p` at (u, v); false where it is degenerate.
bool unit_normal(int p, real u, real v, real s[3], real n[3]) {
    real su[3], sv[3];
    ref::evaluate(g.reference->patches()[p], u, v, s, su, sv);
    cross(su, sv, n);
    const real l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const real lu = std::sqrt(su[0] * su[0] + su[1] * su[1] + su[2] * su[2]);
    const real lv = std::sqrt(sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2]);
    if (!(l > 1e-3L * lu * lv) || !(lu > 1e-6L) || !(lv > 1e-6L)) return false;
    for (int c = 0; c < 3; ++c) n[c] /= l;
    return true;
}

// Runs the ray through libppm and the reference, compares, and returns both answers.
Verdict run(Tally &t, const ppm_ray &r, ppm_hit &h, ref::Result &res) {
    h = library_hit(r);
    res = reference_roots(r);
    return compare(t, r, h, res);
}

// A ray constructed through a known surface point at t = length: the reference must see the
// point (a check of the reference: a root there, or at least a touch where rounding the ray
// to double has left it tangent), and libppm must hit at or before it when the root there
// is robust. Returns whether the reference has a root before the point.
bool check_known_point(Tally &t, const ppm_ray &r, const ppm_hit &h, const ref::Result &res, real length) {
    bool seen = false, robust = false;
    for (const ref::Root &x : res.roots)
        if (std::fabs(x.t - length) * dir_length(r) <= 10 * g.tolerance && is_candidate(x)) {
            seen = true;
            robust = robust || is_robust(x);
        }
    check(t, seen, "reference does not see the known point (reference bug)", r, h, res);
    if (robust)
        check(t, h.t <= static_cast<double>(length) + g.tolerance / dir_length(r),
              "libppm's hit is beyond the known surface point", r, h, res);
    const ref::Root *first = first_real(res);
    return first && (length - first->t) * dir_length(r) > 10 * g.tolerance;
}

// A random surface point away from the patch edges with a regular normal: its patch, point,
// unit normal and an orthonormal tangent basis.
struct SurfacePoint {
    int patch;
    real s[3], n[3], e1[3], e2[3];
};
SurfacePoint random_surface_point(test_rng &rng) {
    SurfacePoint x;
    real u, v;
    do {
        x.patch = static_cast<int>(uniform(rng) * 32) % 32;
        u = 0.01 + 0.98 * uniform(rng);
        v = 0.01 + 0.98 * uniform(rng);
    } while (!unit_normal(x.patch, u, v, x.s, x.n));
    real su[3], sv[3];
    ref::evaluate(g.reference->patches()[x.patch], u, v, x.s, su, sv);
    std::copy(su, su + 3, x.e1);
    normalize(x.e1);
    cross(x.n, x.e1, x.e2);
    return x;
}

// ---------------------------------------------------------------------------------------
// Setup.

int setup(void **) {
    const char *quick = std::getenv("PPM_TEST_QUICK");
    g.quick = g.quick || (quick && *quick && std::strcmp(quick, "0") != 0);
    if (ppm_context_create(&g.context) != PPM_OK) return -1;
    // One worker: the timing budget is for one core, and the machine is shared.
    if (ppm_context_set_int(g.context, "threads", 1) != PPM_OK) return -1;
    if (ppm_scene_create(g.context, &g.scene) != PPM_OK) return -1;
    if (ppm_scene_load_bpt(g.scene, PPM_TEAPOT, nullptr) != PPM_OK) {
        std::printf("load: %s\n", ppm_last_error_message());
        return -1;
    }
    if (g.presplit > 0 && ppm_scene_set_double(g.scene, "patch_presplit", g.presplit) != PPM_OK) {
        std::printf("patch_presplit: %s\n", ppm_last_error_message());
        return -1;
    }
    if (ppm_scene_commit(g.scene) != PPM_OK) return -1;
    double lo[3], hi[3], tol = 0, presplit = 0;
    if (ppm_scene_get_bounds(g.scene, lo, hi) != PPM_OK) return -1;
    if (ppm_scene_get_double(g.scene, "tolerance", &tol) != PPM_OK) return -1;
    if (ppm_scene_get_double(g.scene, "patch_presplit", &presplit) != PPM_OK) return -1;
    double sum = 0;
    for (int c = 0; c < 3; ++c) sum += (hi[c] - lo[c]) * (hi[c] - lo[c]);
    g.diagonal = std::sqrt(sum);
    g.tolerance = tol * g.diagonal;

    std::vector<ref::Patch> patches;
    std::string error;
    if (!ref::load_bpt(PPM_TEAPOT, patches, error)) {
        std::printf("reference load: %s\n", error.c_str());
        return -1;
    }
    g.reference = new ref::Intersector(std::move(patches));
    std::printf("teapot: diagonal %.6f, tolerance %.3g (absolute %.3g), patch_presplit %g%s\n", g.diagonal, tol,
                g.tolerance, presplit, g.quick ? ", quick mode" : "");
    return 0;
}

int teardown(void **) {
    delete g.reference;
    ppm_scene_release(g.scene);
    ppm_context_release(g.context);
    return 0;
}

// The two programs agree on the model itself.
void model_facts(void **) {
    assert_int_equal(g.reference->patches().size(), 32);
    size_t count = 0;
    assert_int_equal(ppm_scene_get_primitive_count(g.scene, 0, &count), PPM_OK);
    assert_int_equal(count, 32);
    double lo[3], hi[3], tol = 0;
    assert_int_equal(ppm_scene_get_bounds(g.scene, lo, hi), PPM_OK);
    real rlo[3], rhi[3];
    g.reference->bounds(rlo, rhi);
    for (int c = 0; c < 3; ++c) {
        assert_close(lo[c], static_cast<double>(rlo[c]), 0);
        assert_close(hi[c], static_cast<double>(rhi[c]), 0);
    }
    assert_close(g.diagonal, 8.27636, 1e-5);
    assert_close(static_cast<double>(g.reference->diagonal()), g.diagonal, 1e-12);
    assert_int_equal(ppm_scene_get_double(g.scene, "tolerance", &tol), PPM_OK);
    assert_close(tol, 1e-9, 0);
}

// ---------------------------------------------------------------------------------------
// Random rays from outside the bounding box towards random points inside it.

std::vector<ppm_ray> random_rays(int n, uint64_t seed) {
    test_rng rng{seed};
    double lo[3], hi[3];
    ppm_scene_get_bounds(g.scene, lo, hi);
    std::vector<ppm_ray> rays;
    for (int i = 0; i < n; ++i) {
        double d[3], o[3], target[3];
        random_direction(rng, d);
        for (int c = 0; c < 3; ++c) {
            o[c] = 0.5 * (lo[c] + hi[c]) + g.diagonal * d[c]; // outside: |o - centre| = diagonal
            target[c] = lo[c] + (hi[c] - lo[c]) * uniform(rng);
        }
        double dir[3];
        for (int c = 0; c < 3; ++c) dir[c] = target[c] - o[c];
        // Every third ray keeps the unnormalised direction (t in units of |dir|).
        if (i % 3 != 0) {
            const double l = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
            for (double &x : dir) x /= l;
        }
        rays.push_back(make_ray(o, dir));
    }
    return rays;
}

void random_rays_match_reference(void **) {
    Tally t{"random"};
    const std::vector<ppm_ray> rays = random_rays(scaled(4000), 0x7ea907);
    std::vector<ppm_hit> hits(rays.size());
    assert_int_equal(ppm_scene_intersect(g.scene, rays.data(), rays.size(), hits.data()), PPM_OK);
    // A check of the reference: with leaves 100 times larger it finds the same roots.
    ref::Options coarse_options;
    coarse_options.leaf_size = 1e-4L * g.reference->diagonal();
    const ref::Intersector coarse(g.reference->patches(), coarse_options);
    size_t multiple = 0, self_checks = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const ref::Result res = reference_roots(rays[i]);
        compare(t, rays[i], hits[i], res);
        if (i % 8 == 0 && res.decided) {
            const ppm_ray &r = rays[i];
            const real o[3] = {r.org[0], r.org[1], r.org[2]};
            const real d[3] = {r.dir[0], r.dir[1], r.dir[2]};
            const ref::Result other = coarse.intersect(o, d, r.tnear, r.tfar);
            bool same = other.decided && other.roots.size() == res.roots.size();
            for (const ref::Root &x : res.roots) {
                bool found = false;
                for (const ref::Root &y : other.roots)
                    found = found ||
                            (x.patch == y.patch && (x.kind == RootKind::tangent) == (y.kind == RootKind::tangent) &&
                             std::fabs(x.t - y.t) * dir_length(r) <= 1e-12L * g.diagonal);
                same = same && found;
            }
            check(t, same, "reference with coarser leaves finds other roots (reference bug)", r, hits[i], res);
            ++self_checks;
        }
        if (res.decided && distinct_real_roots(res, dir_length(rays[i])) >= 2) ++multiple;
        // The batch and the single-ray call agree exactly.
        if (i % 17 == 0) {
            const ppm_hit single = library_hit(rays[i]);
            check(t, single.t == hits[i].t || (std::isinf(single.t) && std::isinf(hits[i].t)),
                  "batch and single-ray hit differ", rays[i], hits[i], res);
        }
    }
    char extra[100];
    std::snprintf(extra, sizeof extra, ", %zu with >= 2 roots, %zu reference self-checks", multiple, self_checks);
    finish(t, extra);
}

// ---------------------------------------------------------------------------------------
// Grazing rays: at angle theta to the tangent plane at a known surface point.

void grazing(double theta, uint64_t seed, const char *name) {
    Tally t{name};
    test_rng rng{seed};
    const int n = scaled(300);
    size_t before = 0;
    for (int i = 0; i < n; ++i) {
        const SurfacePoint x = random_surface_point(rng);
        const real phi = 2 * M_PIl * uniform(rng), side = uniform(rng) < 0.5 ? -1 : 1;
        real dir[3];
        for (int c = 0; c < 3; ++c)
            dir[c] = std::cos(static_cast<real>(theta)) * (std::cos(phi) * x.e1[c] + std::sin(phi) * x.e2[c]) +
                     side * std::sin(static_cast<real>(theta)) * x.n[c];
        normalize(dir);
        const real length = 0.5L + 2.5L * uniform(rng);
        const ppm_ray r = ray_through(x.s, dir, length);
        ppm_hit h;
        ref::Result res;
        if (run(t, r, h, res) == Verdict::undecided) continue;
        if (check_known_point(t, r, h, res, length)) ++before;
    }
    char extra[80];
    std::snprintf(extra, sizeof extra, ", theta %g, %zu with a root before the point", theta, before);
    finish(t, extra);
}

void grazing_rays_1e3(void **) { grazing(1e-3, 0x9a21, "grazing 1e-3"); }
void grazing_rays_1e4(void **) { grazing(1e-4, 0x9a22, "grazing 1e-4"); }
void grazing_rays_1e6(void **) { grazing(1e-6, 0x9a23, "grazing 1e-6"); }

// Grazing rays (theta = 1e-6 and 3e-7) found by larger runs of the cases above, where libppm
// accepted a sub-region of ray-space extent below the tolerance that holds no root (the root
// lies just outside it) and reported its centre, up to 1.23 tolerances before the root.
void grazing_hard_cases(void **) {
    Tally t{"grazing hard cases"};
    const double rays[][6] = {
        // theta = 1e-6
        {-2.184917342384781, 0.72249366986559049, 3.9345390936141267, 0.5131258130780435, -0.14970742079040095,
         -0.84515654651270533},
        {0.42348122590803783, -0.073550532496038615, 0.73358541231427465, -0.23910048372153725, -0.57985970393616393,
         0.77884124340920158},
        {-0.74241361628154423, 0.72405174780764825, 0.6377979478041842, 0.68687732182256989, 0.086376706276024839,
         0.72162220682207323},
        // theta = 3e-7
        {2.0104216877156493, 0.87221425316872858, 2.6361179983382357, -0.87527054271689286, -0.47568733271854297,
         0.08731001399148873},
        {-3.8069465898838297, 1.4665763728621539, 2.2403077774867741, 0.46199307195485562, -0.87019472707995804,
         -0.17124117036493544},
        {1.3621204277900474, -0.1443415568866851, -0.78697122160037758, 0.53092399091874354, 0.042271390928255645,
         0.84636448730786462},
    };
    for (const auto &x : rays) {
        const ppm_ray r = make_ray(x, x + 3);
        ppm_hit h;
        ref::Result res;
        run(t, r, h, res);
    }
    finish(t);
}

// Rays in the tangent plane (theta = 0) at a known point, and the same rays moved off the
// surface along the normal by +-0.5 and +-3 tolerances: a touch (either answer is right
// within the tolerance unless the reference sees a real root), a near miss that must not be
// hit (3 tolerances on the convex side) or a secant with two close roots (on the other).
void tangent_rays(void **) {
    Tally t{"tangent"};
    test_rng rng{0x7a6e};
    const int n = scaled(200);
    const double offsets[] = {0, 0.5, -0.5, 3, -3};
    for (int i = 0; i < n; ++i) {
        const SurfacePoint x = random_surface_point(rng);
        const real phi = 2 * M_PIl * uniform(rng);
        real dir[3];
        for (int c = 0; c < 3; ++c) dir[c] = std::cos(phi) * x.e1[c] + std::sin(phi) * x.e2[c];
        normalize(dir);
        const real length = 0.5L + 2.5L * uniform(rng);
        for (double offset : offsets) {
            real moved[3];
            for (int c = 0; c < 3; ++c) moved[c] = x.s[c] + offset * g.tolerance * x.n[c];
            const ppm_ray r = ray_through(moved, dir, length);
            ppm_hit h;
            ref::Result res;
            run(t, r, h, res);
        }
    }
    finish(t);
}

// ---------------------------------------------------------------------------------------
// Seams and corners.

// Control points of edge `e` of a patch: 0: v = 0 (row 0), 1: v = 1 (row 3), 2: u = 0
// (column 0), 3: u = 1 (column 3), in order of the running parameter.
void edge_points(const ref::Patch &patch, int e, const real *out[4]) {
    for (int k = 0; k < 4; ++k) {
        const int index = e == 0 ? k : e == 1 ? 12 + k : e == 2 ? 4 * k : 4 * k + 3;
        out[k] = patch.p[index];
    }
}
bool same_point(const real *a, const real *b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

// (u, v) on edge e at running parameter s.
void edge_parameter(int e, real s, real &u, real &v) {
    u = e == 2 ? 0 : e == 3 ? 1 : s;
    v = e == 0 ? 0 : e == 1 ? 1 : s;
}

struct Seam {
    int a, ea, b, eb;
    bool reversed;
};

std::vector<Seam> find_seams() {
    const auto &patches = g.reference->patches();
    std::vector<Seam> seams;
    for (int a = 0; a < 32; ++a)
        for (int ea = 0; ea < 4; ++ea) {
            const real *pa[4];
            edge_points(patches[a], ea, pa);
            if (same_point(pa[0], pa[1]) && same_point(pa[1], pa[2]) && same_point(pa[2], pa[3])) continue; // collapsed
            for (int b = a + 1; b < 32; ++b)
                for (int eb = 0; eb < 4; ++eb) {
                    const real *pb[4];
                    edge_points(patches[b], eb, pb);
                    bool forward = true, backward = true;
                    for (int k = 0; k < 4; ++k) {
                        forward = forward && same_point(pa[k], pb[k]);
                        backward = backward && same_point(pa[k], pb[3 - k]);
                    }
                    if (forward || backward) seams.push_back({a, ea, b, eb, !forward});
                }
        }
    return seams;
}

// Rays through `point` (normal `n` there, may be null) from `count` directions: +-n and
// random ones, all with the point at t = 2.
void rays_through_point(Tally &t, test_rng &rng, const real point[3], const real *n, int count) {
    for (int k = 0; k < count; ++k) {
        real dir[3];
        if (k < 2 && n) {
            for (int c = 0; c < 3; ++c) dir[c] = (k == 0 ? 1 : -1) * n[c];
        } else {
            double d[3];
            random_direction(rng, d);
            for (int c = 0; c < 3; ++c) dir[c] = d[c];
        }
        normalize(dir);
        const ppm_ray r = ray_through(point, dir, 2);
        ppm_hit h;
        ref::Result res;
        if (run(t, r, h, res) == Verdict::undecided) continue;
        check_known_point(t, r, h, res, 2);
    }
}

void seam_and_corner_rays(void **) {
    Tally t{"seams+corners"};
    test_rng rng{0x5ea3};
    const auto &patches = g.reference->patches();

    const std::vector<Seam> seams = find_seams();
    // 104 shared edges of the teapot = 52 pairs (see /work/shared/data/README.md).
    assert_int_equal(seams.size(), 52);
    const real along[4] = {0.1L, 0.37L, 0.5L, 0.81L};
    const int samples = g.quick ? 1 : 4;
    for (const Seam &seam : seams)
        for (int k = 0; k < samples; ++k) {
            real u, v, s[3], n[3];
            edge_parameter(seam.ea, along[g.quick ? 1 : k], u, v);
            const bool has_normal = unit_normal(seam.a, u, v, s, n);
            if (!has_normal) ref::evaluate(patches[seam.a], u, v, s);
            // Both patches agree on the seam point (a check of the seam table).
            real ub, vb, sb[3];
            const real sa = along[g.quick ? 1 : k];
            edge_parameter(seam.eb, seam.reversed ? 1 - sa : sa, ub, vb);
            ref::evaluate(patches[seam.b], ub, vb, sb);
            for (int c = 0; c < 3; ++c) assert_true(std::fabs(s[c] - sb[c]) < 1e-15L);
            rays_through_point(t, rng, s, has_normal ? n : nullptr, g.quick ? 3 : 6);
        }

    // Corners shared by three or more patches.
    struct Corner {
        const real *p;
        int patches;
    };
    std::vector<Corner> corners;
    for (int a = 0; a < 32; ++a)
        for (int k : {0, 3, 12, 15}) {
            const real *p = patches[a].p[k];
            bool known = false;
            for (const Corner &c : corners) known = known || same_point(c.p, p);
            if (known) continue;
            int count = 0;
            for (int b = 0; b < 32; ++b) {
                bool touches = false;
                for (int m : {0, 3, 12, 15}) touches = touches || same_point(patches[b].p[m], p);
                count += touches;
            }
            corners.push_back({p, count});
        }
    size_t used = 0;
    for (const Corner &c : corners) {
        if (c.patches < 3) continue;
        ++used;
        // The mean of the unit normals of the patches there, where defined.
        real mean[3] = {0, 0, 0};
        for (int b = 0; b < 32; ++b)
            for (int m : {0, 3, 12, 15}) {
                if (!same_point(patches[b].p[m], c.p)) continue;
                const real u = (m == 3 || m == 15) ? 1 : 0, v = m >= 12 ? 1 : 0;
                real s[3], n[3];
                if (!unit_normal(b, u, v, s, n)) continue;
                const real sign = mean[0] * n[0] + mean[1] * n[1] + mean[2] * n[2] < 0 ? -1 : 1;
                for (int k = 0; k < 3; ++k) mean[k] += sign * n[k];
            }
        const bool has_normal = mean[0] != 0 || mean[1] != 0 || mean[2] != 0;
        if (has_normal) normalize(mean);
        rays_through_point(t, rng, c.p, has_normal ? mean : nullptr, g.quick ? 4 : 12);
    }
    assert_true(used >= 8);
    char extra[80];
    std::snprintf(extra, sizeof extra, ", %zu seams, %zu corners of >= 3 patches", seams.size(), used);
    finish(t, extra);
}

// ---------------------------------------------------------------------------------------
// The collapsed edges: lid apex (0, 0, 3.15) and bottom centre (0, 0, 0).

void degenerate_points(void **) {
    Tally t{"apex+bottom"};
    // The apex as the file stores it (3.15 rounded to double) and the bottom centre.
    const real apex_d[3] = {0, 0, static_cast<real>(3.15)}, bottom[3] = {0, 0, 0};
    auto vertical_normal = [&](const ppm_ray &r, const ppm_hit &h, const ref::Result &res) {
        check(t,
              std::isfinite(h.ng[0]) && std::isfinite(h.ng[1]) && std::isfinite(h.ng[2]) &&
                  std::fabs(std::fabs(h.ng[2]) - 1) <= 1e-9,
              "normal at the collapsed point is not (0, 0, +-1)", r, h, res);
    };
    ppm_hit h;
    ref::Result res;

    // Vertical ray from above: the apex at t = 2, then the bottom centre at t = 5.15.
    {
        const double o[3] = {0, 0, 5.15}, d[3] = {0, 0, -1};
        const ppm_ray r = make_ray(o, d);
        run(t, r, h, res);
        assert_true(res.decided);
        check(t, std::fabs(h.t - 2) <= g.tolerance, "vertical ray: apex not at t = 2", r, h, res);
        check(t, h.prim_id >= 20 && h.prim_id <= 23, "vertical ray: apex not on patches 20-23", r, h, res);
        vertical_normal(r, h, res);
        check(t, distinct_real_roots(res, 1) == 2, "vertical ray: reference should see 2 points", r, h, res);
        // Past the apex: the bottom centre.
        const ppm_ray r2 = make_ray(o, d, 2.5);
        run(t, r2, h, res);
        check(t, std::fabs(h.t - 5.15) <= g.tolerance, "vertical ray: bottom centre not at t = 5.15", r2, h, res);
        check(t, h.prim_id >= 28 && h.prim_id <= 31, "vertical ray: bottom not on patches 28-31", r2, h, res);
        vertical_normal(r2, h, res);
        // Occlusion just short of / just past the apex.
        check(t, !library_occluded(make_ray(o, d, 0, 2 - 4 * g.tolerance)), "vertical ray occluded before the apex", r,
              h, res);
        check(t, library_occluded(make_ray(o, d, 0, 2 + 4 * g.tolerance)), "vertical ray not occluded past the apex", r,
              h, res);
    }
    // Vertical rays from inside, upwards to the apex and downwards to the bottom centre, and
    // from below to the bottom centre.
    {
        const double o[3] = {0, 0, 1}, up[3] = {0, 0, 1}, down[3] = {0, 0, -1};
        ppm_ray r = make_ray(o, up);
        run(t, r, h, res);
        check(t, std::fabs(h.t - (static_cast<double>(apex_d[2]) - 1)) <= g.tolerance, "from inside: apex not hit", r,
              h, res);
        vertical_normal(r, h, res);
        r = make_ray(o, down);
        run(t, r, h, res);
        check(t, std::fabs(h.t - 1) <= g.tolerance, "from inside: bottom centre not hit", r, h, res);
        vertical_normal(r, h, res);
        const double below[3] = {0, 0, -3};
        r = make_ray(below, up);
        run(t, r, h, res);
        check(t, std::fabs(h.t - 3) <= g.tolerance, "from below: bottom centre not hit", r, h, res);
        vertical_normal(r, h, res);
    }
    // Oblique rays through the apex from above and through the bottom centre from below:
    // the apex is the highest point of the model and the bottom centre the lowest, so each
    // is the first hit, at t = 2.
    const double polar[] = {1e-7, 0.02, 0.3, 0.8, 1.2, 1.5};
    const int azimuths = g.quick ? 2 : 12;
    for (double a : polar)
        for (int k = 0; k < azimuths; ++k) {
            const double phi = 2 * M_PI * (k + 0.37) / azimuths;
            const real s = std::sin(static_cast<real>(a)), c = std::cos(static_cast<real>(a));
            const real from_above[3] = {s * std::cos(static_cast<real>(phi)), s * std::sin(static_cast<real>(phi)), -c};
            const real from_below[3] = {from_above[0], from_above[1], c};
            ppm_ray r = ray_through(apex_d, from_above, 2);
            if (run(t, r, h, res) != Verdict::undecided) {
                check(t, std::fabs(h.t - 2) <= g.tolerance, "oblique ray: apex is not the first hit", r, h, res);
                // The normal near the apex tilts by about (distance from the apex) x curvature.
                check(t, std::fabs(std::fabs(h.ng[2]) - 1) <= 1e-6, "oblique ray: apex normal not vertical", r, h, res);
            }
            r = ray_through(bottom, from_below, 2);
            if (run(t, r, h, res) != Verdict::undecided) {
                check(t, std::fabs(h.t - 2) <= g.tolerance, "oblique ray: bottom centre is not the first hit", r, h,
                      res);
                check(t, std::fabs(std::fabs(h.ng[2]) - 1) <= 1e-6, "oblique ray: bottom normal not vertical", r, h,
                      res);
            }
        }
    finish(t);
}

// ---------------------------------------------------------------------------------------
// Rays with several hits: the nearest wins; tnear / tfar just around the nearest root.

void several_hits(void **) {
    Tally t{"several hits"};
    std::vector<ppm_ray> rays;
    // Horizontal rays along x through handle, body and spout; along y through the body.
    const double ys[] = {-0.6, -0.05, 0, 0.31};
    const double zs[] = {0.4, 0.9, 1.3, 1.65, 1.8, 2.0, 2.2, 2.45};
    for (double y : ys)
        for (double z : zs) {
            const double o[3] = {-5, y, z}, d[3] = {1, 0, 0};
            const double o2[3] = {6, y, z}, d2[3] = {-1, 0, 0};
            const double o3[3] = {y, -4, z}, d3[3] = {0, 1, 0};
            rays.push_back(make_ray(o, d));
            rays.push_back(make_ray(o2, d2));
            rays.push_back(make_ray(o3, d3));
        }
    // Random rays of which the reference sees at least two points.
    const size_t constructed = rays.size();
    {
        const std::vector<ppm_ray> random = random_rays(scaled(1500), 0x5e7e4a1);
        for (const ppm_ray &r : random) rays.push_back(r);
    }
    size_t multi = 0, occlusion_checks = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const ppm_ray &r = rays[i];
        const double dlen = dir_length(r);
        const ref::Result all = reference_roots(r);
        if (!all.decided) {
            ++t.rays;
            ++t.undecided;
            continue;
        }
        const int distinct = distinct_real_roots(all, dlen);
        if (i < constructed && std::fabs(r.org[1]) < 4 && std::fabs(r.org[2] - 1.3) < 0.5) {
            // Through the body: at least two points (entering and leaving).
            check(t, distinct >= 2, "horizontal ray through the body: fewer than 2 roots", r, library_hit(r), all);
        }
        if (distinct < 2) continue;
        ++multi;
        ppm_hit h = library_hit(r);
        compare(t, r, h, all);
        // Occlusion around the nearest root, unless a touch comes first (ambiguous).
        const ref::Root *first = first_robust(all);
        if (!first || first_candidate(all) != first) continue;
        const double step = 4 * g.tolerance / dlen;
        ++occlusion_checks;
        const double t1 = static_cast<double>(first->t);
        check(t, !library_occluded(make_ray(r.org, r.dir, 0, t1 - step)),
              "occluded with tfar just below the nearest root", r, h, all);
        check(t, library_occluded(make_ray(r.org, r.dir, 0, t1 + step)),
              "not occluded with tfar just above the nearest root", r, h, all);
        check(t, library_occluded(r), "not occluded with tfar = inf", r, h, all);
        // An interval [t1 - step, t1 + step] around the nearest root finds exactly it.
        ppm_ray around = make_ray(r.org, r.dir, std::max(0.0, t1 - step), t1 + step);
        ppm_hit ha;
        ref::Result ra;
        run(t, around, ha, ra);
        // Past the nearest root: the next one.
        ppm_ray next = make_ray(r.org, r.dir, t1 + step);
        ppm_hit hn;
        ref::Result rn;
        if (run(t, next, hn, rn) != Verdict::undecided) {
            check(t, hn.geom_id != PPM_INVALID_ID, "no hit past the nearest root", next, hn, rn);
            check(t, library_occluded(next), "not occluded past the nearest root", next, hn, rn);
        }
    }
    char extra[100];
    std::snprintf(extra, sizeof extra, ", %zu rays with >= 2 roots, %zu occlusion checks", multi, occlusion_checks);
    finish(t, extra);
    assert_true(multi >= (g.quick ? 20u : 200u));
}

// ---------------------------------------------------------------------------------------
// Rays leaving a hit point (ppm_hit_spawn_ray), into both sides of the surface.

void spawned_rays(void **) {
    Tally t{"spawned"};
    test_rng rng{0x59a3};
    const std::vector<ppm_ray> primary = random_rays(scaled(2000), 0x59a4);
    std::vector<ppm_hit> hits(primary.size());
    assert_int_equal(ppm_scene_intersect(g.scene, primary.data(), primary.size(), hits.data()), PPM_OK);
    // Roots this close to the spawned origin are a different surface within a hair of the
    // hit (where the handle and spout pass through the body): skipped, counted.
    const double near_origin = 1e-6 * g.diagonal;
    size_t used = 0, skipped = 0, self_hits = 0;
    for (size_t i = 0; i < primary.size(); ++i) {
        const ppm_hit &hit = hits[i];
        if (hit.geom_id == PPM_INVALID_ID) continue;
        ++used;
        double d[3];
        do random_direction(rng, d);
        while (std::fabs(d[0] * hit.ng[0] + d[1] * hit.ng[1] + d[2] * hit.ng[2]) < 0.1);
        for (int side = 0; side < 2; ++side) {
            const double dir[3] = {side ? -d[0] : d[0], side ? -d[1] : d[1], side ? -d[2] : d[2]};
            ppm_ray r;
            assert_int_equal(ppm_hit_spawn_ray(&hit, dir, &r), PPM_OK);
            assert_true(r.tnear == 0 && std::isinf(r.tfar));
            // The origin is 2 p_error off the hit point, on the side dir points to.
            double off = 0, along = 0;
            for (int c = 0; c < 3; ++c) {
                off += (r.org[c] - hit.p[c]) * (r.org[c] - hit.p[c]);
                along += (r.org[c] - hit.p[c]) * hit.ng[c];
            }
            off = std::sqrt(off);
            const ppm_hit h = library_hit(r);
            const ref::Result res = reference_roots(r);
            if (res.decided) {
                const ref::Root *first = first_real(res);
                if (first && first->t * dir_length(r) < near_origin) {
                    ++skipped;
                    continue;
                }
            }
            check(t,
                  std::fabs(off - 2 * hit.p_error) <= 1e-3 * hit.p_error &&
                      along * (dir[0] * hit.ng[0] + dir[1] * hit.ng[1] + dir[2] * hit.ng[2]) > 0,
                  "spawned origin is not 2 p_error off the surface on the side of dir", r, h, res);
            if (h.geom_id != PPM_INVALID_ID && h.t * dir_length(r) < near_origin) {
                ++self_hits;
                report(t, &Tally::false_hits, "SELF HIT", r, h, res, "hit at t ~ 0");
                ++t.rays;
                continue;
            }
            compare(t, r, h, res);
        }
    }
    char extra[100];
    std::snprintf(extra, sizeof extra, ", from %zu hits, %zu self hits, %zu skipped (surface near origin)", used,
                  self_hits, skipped);
    finish(t, extra);
}

// ---------------------------------------------------------------------------------------

void all_cases_total(void **) {
    std::printf("total: %zu rays, %zu hits, %zu misses, %zu false hits, %zu wrong t, "
                "%zu undecided, %zu tangent-ambiguous, %zu other failures, max |dt|/diag %.3g\n",
                totals.rays, totals.hits, totals.misses, totals.false_hits, totals.wrong_t, totals.undecided,
                totals.ambiguous, totals.other, totals.max_dt);
    assert_int_equal(totals.misses, 0);
    assert_int_equal(totals.false_hits, 0);
    assert_int_equal(totals.wrong_t, 0);
    assert_int_equal(totals.other, 0);
    assert_true(totals.undecided * 500 <= totals.rays);
}

} // namespace

int main(int argc, char **argv) {
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) {
            g.quick = true;
        } else if (std::strcmp(argv[i], "--presplit") == 0 && i + 1 < argc) {
            g.presplit = std::atoi(argv[++i]);
        } else {
            std::fprintf(stderr, "usage: test_teapot_reference [--quick] [--presplit N]\n");
            return 2;
        }
    }
    const auto start = std::chrono::steady_clock::now();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(model_facts),       cmocka_unit_test(random_rays_match_reference),
        cmocka_unit_test(grazing_rays_1e3),  cmocka_unit_test(grazing_rays_1e4),
        cmocka_unit_test(grazing_rays_1e6),  cmocka_unit_test(grazing_hard_cases),
        cmocka_unit_test(tangent_rays),      cmocka_unit_test(seam_and_corner_rays),
        cmocka_unit_test(degenerate_points), cmocka_unit_test(several_hits),
        cmocka_unit_test(spawned_rays),      cmocka_unit_test(all_cases_total),
    };
    const int failed = cmocka_run_group_tests(tests, setup, teardown);
    std::printf("test_teapot_reference: %.1f s\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return failed;
}
