// SPDX-License-Identifier: Apache-2.0
#include "geometry/patch_intersector.h"

#include "geometry/derivative_hull.h"
#include "math/min_max.h"

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>

namespace ppm {

namespace {

// The search's thresholds. Region coordinates a, b run over [0, 1] within the input patch;
// lengths are in ray space (the coordinates' units).

// A rotation maps a vector's largest coordinate to at most sqrt(3) times it (|v|_inf <= |v|_2
// <= sqrt(3) |v|_inf in three dimensions); the closest double to sqrt(3).
constexpr double kSqrt3 = 1.7320508075688772;
// Rounding of the ray-space control points, in ulps of their magnitude: the projection adds a
// few and each De Casteljau halving about one more (averaging does not grow earlier errors);
// boxes and slabs are widened by it. A power of two with headroom over a typical search depth.
constexpr double kNoiseUlps = 64;
// No region is split below this many times the noise: smaller, its box is rounding, not shape.
constexpr double kPointSizeInNoise = 16;
// Where the Jacobian is regular, an undecided region is split this far below the point size
// before it counts as a hit: a grazing ray stays within the tolerance over a stretch much
// longer than the tolerance, so a merely tolerance-sized region can lie before the crossing
// or hold two; a thousandth costs about ten more halvings, and only on such regions.
constexpr double kFineShare = 1e-3;
// Newton's residual |x|, |y| counts as zero at this share of the tolerance (or the noise,
// whichever is larger): far below what the tolerance allows, and within reach of doubles.
constexpr double kResidualShare = 1e-4;
// Newton has converged when its last step moved the point by less than this share of the
// point size: convergence is quadratic, so the remaining error is of the order of its square.
constexpr double kStepShare = 0.1;
// ... or when the Krawczyk data prove the point within this share of the point size of the
// root (a bound, where the step test is an estimate): half the step test's share, and the
// step that follows is still taken, so the root ends well inside the tolerance.
constexpr double kProvenShare = 0.05;
// |det J| below this times |J|_1^2 is singular: a condition number near 1e14 leaves the
// inverse Y = J^-1 computed in double with an error of about 1e14 * DBL_EPSILON ~ 1 %, too
// little to prove anything with.
constexpr double kSingularDeterminant = 1e-14;
// The interval arithmetic of the Krawczyk test is not outward rounded; its few dozen
// operations on values of order 1 (the region's own [0, 1]^2) round by ~1e-15: this margin
// covers them ten thousandfold and is far below any width the search splits to.
constexpr double kIntervalMargin = 1e-12;
// A contraction |I - Y J| below 1 proves injectivity; below this it also stays clear of 1 for
// rounding, and the proven distance to the root (a division by 1 - contraction) is at most
// ten times the Newton step's size.
constexpr double kInjectiveContraction = 0.9;
// Newton from a proven start converges quadratically, from one correct bit to 53 in about
// six steps; 16 allows slow first steps, and a run still unconverged then is wandering (the
// region is split instead).
constexpr int kNewtonIterations = 16;
// A converged root is this region's if it lies within this share of the region's width of it
// (plus kParameterRounding): a root on the border of two regions may be taken by either.
constexpr double kRegionShare = 1e-9;
// A few ulps of a parameter in [0, 1]: the rounding of a region's bounds.
constexpr double kParameterRounding = 4 * DBL_EPSILON;
// Newton may overshoot a region on its way to a root inside; once it is more than half the
// region's width outside, it has left the neighbourhood the region's proof speaks of.
constexpr double kNewtonWander = 0.5;
// Regions narrower than this in both parameters are points: halving a width of 1e-15 within
// [0, 1] (about 4.5 ulps of 1) no longer gives distinct midpoints.
constexpr double kParameterResolution = 1e-15;

} // namespace

RayFrame RayFrame::from_ray(const Vec3 &org, const Vec3 &dir) { return from_ray(org, dir, length(dir)); }

RayFrame RayFrame::from_ray(const Vec3 &org, const Vec3 &dir, double dir_length) {
    RayFrame f;
    f.org = org;
    f.dir_length = dir_length;
    f.axis = dir * (1.0 / dir_length);
    orthonormal_basis(f.axis, f.e1, f.e2);
    return f;
}

ControlGrid ControlGrid::from(const BezierPatch &patch) {
    ControlGrid g;
    for (int k = 0; k < 16; ++k) {
        g.x[k] = patch.p[k].x;
        g.y[k] = patch.p[k].y;
        g.z[k] = patch.p[k].z;
    }
    g.derivative_bound = g.bound_derivatives();
    return g;
}

double ControlGrid::bound_derivatives() const {
    double du = 0, dv = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 3; ++j) {
            const int k = i * 4 + j, across = j * 4 + i; // (i, j) -> (i, j + 1); (j, i) -> (j + 1, i)
            du = std::max(du, std::fabs(x[k + 1] - x[k]) + std::fabs(y[k + 1] - y[k]) + std::fabs(z[k + 1] - z[k]));
            dv = std::max(dv, std::fabs(x[across + 4] - x[across]) + std::fabs(y[across + 4] - y[across]) +
                                  std::fabs(z[across + 4] - z[across]));
        }
    // A cubic's derivative has the control points 3 (c_k+1 - c_k). The 1-norm is not rotation
    // invariant; sqrt(3) covers any rotation of a 2-norm bound.
    return 3.0 * kSqrt3 * std::max(du, dv);
}

namespace {

// Control points in ray space.
using Projected = ControlGrid;

// A region [a0, a1] x [b0, b1] of the input patch with its own control points.
struct Region {
    Projected cp;
    double a0, a1, b0, b1;
    // Estimate of the Krawczyk contraction |I - Y J| here, from the parent's (0: unknown).
    double contraction_hint;
};

// Halving a region at most halves the spread of its Jacobian, so the contraction of a child
// is at least about half its parent's. Above this hint (the parent measured more than 2) the
// interval test cannot prove a unique root (that needs a contraction below 1) and is skipped:
// such regions fill the first levels of a search on whole patches (patch_presplit 1), where
// the box and slab tests already cull what a "no root" verdict would. Skipping only costs a
// split, never a root; regions below the point size are always tested, as the end of the
// subdivision reads the test's `singular`.
constexpr double skip_krawczyk_hint = 1;

// The depth-first work list of the search. Regions stay in the slot they were written to and
// the stack holds slot numbers, so a split writes its children in place: no region (400
// bytes) is copied on its way through the stack, a cost that grows with the search's depth
// (whole patches, patch_presplit 1).
class RegionStack {
public:
    // Each level of the search pushes two regions and pops one; a region shrinks to a width
    // of kParameterResolution (about 2^-50) in a and b within about 100 levels.
    static constexpr int capacity = 160;
    static constexpr int kWholePatch = 255; // a slot number no pool slot has

    bool empty() const { return size_ == 0; }
    Region &operator[](int slot) { return pool_[slot]; }
    // A free slot to write a region into; it belongs to the caller until pushed or released.
    int acquire() { return free_count_ > 0 ? free_[--free_count_] : unused_++; }
    void release(int slot) { free_[free_count_++] = static_cast<uint8_t>(slot); }
    void push(int slot) { stack_[size_++] = static_cast<uint8_t>(slot); }
    int pop() { return stack_[--size_]; }

private:
    Region pool_[capacity];
    uint8_t stack_[capacity], free_[capacity];
    int size_ = 0, free_count_ = 0, unused_ = 0; // slots >= unused_ were never used
};

struct Bounds2 {
    double xmin, xmax, ymin, ymax, zmin, zmax;
};

Bounds2 bounds_of(const Projected &p) {
    Bounds2 b;
    min_max16(p.x, b.xmin, b.xmax);
    min_max16(p.y, b.ymin, b.ymax);
    min_max16(p.z, b.zmin, b.zmax);
    return b;
}

// Whether the projected patch misses the ray by a slab test along the normals of its two
// mean chord directions: axis-aligned boxes of a thin sliver seen at an angle contain the ray
// long before the sliver does, and every near miss would cost a subdivision.
bool misses_chord_slabs(const Projected &p, double noise) {
    const double du_x = (p.x[3] + p.x[15]) - (p.x[0] + p.x[12]), du_y = (p.y[3] + p.y[15]) - (p.y[0] + p.y[12]);
    const double dv_x = (p.x[12] + p.x[15]) - (p.x[0] + p.x[3]), dv_y = (p.y[12] + p.y[15]) - (p.y[0] + p.y[3]);
    const double normals[2][2] = {{-du_y, du_x}, {-dv_y, dv_x}};
    for (const auto &n : normals) {
        double d[16], lo, hi;
        for (int k = 0; k < 16; ++k) d[k] = n[0] * p.x[k] + n[1] * p.y[k];
        min_max16(d, lo, hi);
        const double slack = noise * (std::fabs(n[0]) + std::fabs(n[1]));
        if (lo > slack || hi < -slack) return true;
    }
    return false;
}

// Value and first derivatives of (x, y) at (a, b) in the region's own [0, 1]^2. The depth z
// is needed only once a root is found (evaluate_z).
struct Jet {
    double x, y, xa, xb, ya, yb;
};

// Inlined: returned through memory, its six values reached Newton a store-forwarding delay late.
[[gnu::always_inline]] inline Jet evaluate_jet(const Projected &p, double a, double b) {
    double ba[4], bb[4], da[4], db[4];
    bernstein3(a, ba);
    bernstein3(b, bb);
    bernstein3_derivative(a, da);
    bernstein3_derivative(b, db);
#ifdef __SSE2__
    // Contract the rows into column sums (value and b-derivative), two columns per register,
    // then each column sum with the a-weights.
    __m128d cx0 = _mm_setzero_pd(), cx1 = cx0, cy0 = cx0, cy1 = cx0;
    __m128d bx0 = cx0, bx1 = cx0, by0 = cx0, by1 = cx0;
    for (int i = 0; i < 4; ++i) {
        const __m128d w = _mm_set1_pd(bb[i]), dw = _mm_set1_pd(db[i]);
        const __m128d x0 = _mm_loadu_pd(p.x + 4 * i), x1 = _mm_loadu_pd(p.x + 4 * i + 2);
        const __m128d y0 = _mm_loadu_pd(p.y + 4 * i), y1 = _mm_loadu_pd(p.y + 4 * i + 2);
        cx0 = _mm_add_pd(cx0, _mm_mul_pd(w, x0));
        cx1 = _mm_add_pd(cx1, _mm_mul_pd(w, x1));
        cy0 = _mm_add_pd(cy0, _mm_mul_pd(w, y0));
        cy1 = _mm_add_pd(cy1, _mm_mul_pd(w, y1));
        bx0 = _mm_add_pd(bx0, _mm_mul_pd(dw, x0));
        bx1 = _mm_add_pd(bx1, _mm_mul_pd(dw, x1));
        by0 = _mm_add_pd(by0, _mm_mul_pd(dw, y0));
        by1 = _mm_add_pd(by1, _mm_mul_pd(dw, y1));
    }
    const __m128d ba0 = _mm_loadu_pd(ba), ba1 = _mm_loadu_pd(ba + 2);
    const __m128d da0 = _mm_loadu_pd(da), da1 = _mm_loadu_pd(da + 2);
    auto dot4 = [](__m128d w0, __m128d w1, __m128d v0, __m128d v1) {
        const __m128d s = _mm_add_pd(_mm_mul_pd(w0, v0), _mm_mul_pd(w1, v1));
        return _mm_cvtsd_f64(_mm_add_sd(s, _mm_unpackhi_pd(s, s)));
    };
    return {dot4(ba0, ba1, cx0, cx1), dot4(ba0, ba1, cy0, cy1), dot4(da0, da1, cx0, cx1),
            dot4(ba0, ba1, bx0, bx1), dot4(da0, da1, cy0, cy1), dot4(ba0, ba1, by0, by1)};
#else
    // Each row's value and a-derivative, then the weighted sum over rows.
    Jet r{};
    for (int i = 0; i < 4; ++i) {
        double rx = 0, ry = 0, rxa = 0, rya = 0;
        for (int j = 0; j < 4; ++j) {
            const int k = i * 4 + j;
            rx += ba[j] * p.x[k];
            ry += ba[j] * p.y[k];
            rxa += da[j] * p.x[k];
            rya += da[j] * p.y[k];
        }
        r.x += bb[i] * rx;
        r.y += bb[i] * ry;
        r.xa += bb[i] * rxa;
        r.ya += bb[i] * rya;
        r.xb += db[i] * rx;
        r.yb += db[i] * ry;
    }
    return r;
#endif
}

double evaluate_z(const Projected &p, double a, double b) {
    double ba[4], bb[4];
    bernstein3(a, ba);
    bernstein3(b, bb);
    double z = 0;
    for (int i = 0; i < 4; ++i)
        z += bb[i] * (ba[0] * p.z[i * 4] + ba[1] * p.z[i * 4 + 1] + ba[2] * p.z[i * 4 + 2] + ba[3] * p.z[i * 4 + 3]);
    return z;
}

void split_a(const Projected &p, double t, Projected &left, Projected &right) {
    for (int i = 0; i < 4; ++i) {
        de_casteljau_split(&p.x[i * 4], 1, t, &left.x[i * 4], &right.x[i * 4]);
        de_casteljau_split(&p.y[i * 4], 1, t, &left.y[i * 4], &right.y[i * 4]);
        de_casteljau_split(&p.z[i * 4], 1, t, &left.z[i * 4], &right.z[i * 4]);
    }
}

void split_b(const Projected &p, double t, Projected &left, Projected &right) {
    for (int j = 0; j < 4; ++j) {
        de_casteljau_split(&p.x[j], 4, t, &left.x[j], &right.x[j]);
        de_casteljau_split(&p.y[j], 4, t, &left.y[j], &right.y[j]);
        de_casteljau_split(&p.z[j], 4, t, &left.z[j], &right.z[j]);
    }
}

// Ray-space length of the control net along a (rows) and along b (columns): decides which
// parameter to split so that regions shrink evenly in ray space.
void net_lengths(const Projected &p, double &along_a, double &along_b) {
    along_a = along_b = 0;
    for (int i = 0; i < 4; ++i) {
        const int k0 = i * 4, k3 = i * 4 + 3;
        along_a = std::max(along_a,
                           std::fabs(p.x[k3] - p.x[k0]) + std::fabs(p.y[k3] - p.y[k0]) + std::fabs(p.z[k3] - p.z[k0]));
        const int c0 = i, c3 = 12 + i;
        along_b = std::max(along_b,
                           std::fabs(p.x[c3] - p.x[c0]) + std::fabs(p.y[c3] - p.y[c0]) + std::fabs(p.z[c3] - p.z[c0]));
    }
}

// What the interval test proves about the roots of (x, y) in a region.
enum class Verdict {
    no_root,          // K(X) misses X
    one_root,         // K(X) inside X: exactly one root, Newton converges to it
    at_most_one_root, // |I - Y J(X)| < 1: (x, y) is injective on X, so a root Newton finds
                      // inside X is the only one there
    undecided
};

struct Krawczyk {
    Verdict verdict = Verdict::undecided;
    bool singular = false;                     // J(c) is (numerically) singular: no proof is possible here
    double start_a = 0.5, start_b = 0.5;       // c - Y F(c): a Newton step from the centre
    double y00 = 0, y01 = 0, y10 = 0, y11 = 0; // Y = J(c)^-1 in the region's coordinates
    double contraction = 1;                    // |I - Y J(X)| in the infinity norm

    // For a root x* and a point x both in X: F(x) = J' (x - x*) with J' in J(X), so
    // |x - x*| <= |Y F(x)| / (1 - contraction) (in the region's coordinates).
    double distance_to_root(double fx, double fy) const {
        return std::max(std::fabs(y00 * fx + y01 * fy), std::fabs(y10 * fx + y11 * fy)) / (1 - contraction);
    }
};

// Krawczyk operator on the region's [0, 1]^2 with midpoint c = (1/2, 1/2) and the
// preconditioner Y = J(c)^-1:  K = c - Y F(c) + (I - Y J([0,1]^2)) ([0,1]^2 - c).
// K disjoint from the box proves there is no root; K inside the box's interior proves exactly
// one root. Failing that, a contraction |I - Y J| < 1 (infinity norm) still proves that F is
// injective on the box, which saves a split when the root sits near the box's edge (where K
// sticks out of the box however small the box). `start` receives c - Y F(c), a Newton step
// from the centre.
Krawczyk krawczyk_test(const Projected &p) {
    Krawczyk k;
    const Jet c = evaluate_jet(p, 0.5, 0.5);
    const double det = c.xa * c.yb - c.xb * c.ya;
    const double jnorm = std::fabs(c.xa) + std::fabs(c.xb) + std::fabs(c.ya) + std::fabs(c.yb);
    if (!(std::fabs(det) > kSingularDeterminant * jnorm * jnorm)) {
        k.singular = true;
        return k;
    }
    const double y00 = c.yb / det, y01 = -c.xb / det, y10 = -c.ya / det, y11 = c.xa / det;
    const double step_a = y00 * c.x + y01 * c.y, step_b = y10 * c.x + y11 * c.y;

    const Interval xa = derivative_hull_a(p.x), xb = derivative_hull_b(p.x);
    const Interval ya = derivative_hull_a(p.y), yb = derivative_hull_b(p.y);
    // Row k of M = I - Y J: M_k0 = d_k0 - (Y_k0 xa + Y_k1 ya), M_k1 = d_k1 - (Y_k0 xb + Y_k1 yb).
    auto magnitude = [](double identity, Interval u, Interval v) {
        const double lo = identity - (u.hi + v.hi), hi = identity - (u.lo + v.lo);
        return std::max(std::fabs(lo), std::fabs(hi));
    };
    const double r0 =
        0.5 * (magnitude(1.0, scale(y00, xa), scale(y01, ya)) + magnitude(0.0, scale(y00, xb), scale(y01, yb)));
    const double r1 =
        0.5 * (magnitude(0.0, scale(y10, xa), scale(y11, ya)) + magnitude(1.0, scale(y10, xb), scale(y11, yb)));
    if (!std::isfinite(r0 + r1 + step_a + step_b)) return k;

    // Inflate by a rounding margin: the interval arithmetic above is not outward rounded.
    const double margin = kIntervalMargin;
    const double k0lo = 0.5 - step_a - r0 - margin, k0hi = 0.5 - step_a + r0 + margin;
    const double k1lo = 0.5 - step_b - r1 - margin, k1hi = 0.5 - step_b + r1 + margin;
    k.start_a = 0.5 - step_a;
    k.start_b = 0.5 - step_b;
    k.y00 = y00;
    k.y01 = y01;
    k.y10 = y10;
    k.y11 = y11;
    k.contraction = 2 * (std::max(r0, r1) + margin);
    if (k0hi < 0.0 || k0lo > 1.0 || k1hi < 0.0 || k1lo > 1.0)
        k.verdict = Verdict::no_root;
    else if (k0lo > 0.0 && k0hi < 1.0 && k1lo > 0.0 && k1hi < 1.0)
        k.verdict = Verdict::one_root;
    else if (k.contraction < kInjectiveContraction)
        k.verdict = Verdict::at_most_one_root;
    return k;
}

struct Solver {
    const Projected &top;      // the whole input patch in ray space: Newton evaluates here
    double derivative;         // bound on |dS/da| and |dS/db| over the patch
    double residual_converged; // |x|, |y| at or below this count as zero
    double depth_converged;    // a last step that moved the point less than this: converged
    double error_converged;    // a proven distance to the root below this: converged

    // Guarded Newton on x = y = 0 over the input patch, starting at (a, b), accepting only a
    // root inside [a0, a1] x [b0, b1] (plus a rounding margin). Returns false on a singular
    // Jacobian, NaN, leaving the region's neighbourhood, or no convergence. With the region's
    // Krawczyk data it stops as soon as the proven distance to the root is small enough.
    bool newton(double a, double b, const Region &r, const Krawczyk *proof, double &root_a, double &root_b,
                double &distance) const {
        const double wa = r.a1 - r.a0, wb = r.b1 - r.b0;
        for (int iteration = 0; iteration < kNewtonIterations; ++iteration) {
            const Jet j = evaluate_jet(top, a, b);
            const double det = j.xa * j.yb - j.xb * j.ya;
            if (!(std::fabs(det) > 0) || !std::isfinite(det)) return false;
            const double da = (j.xb * j.y - j.yb * j.x) / det;
            const double db = (j.ya * j.x - j.xa * j.y) / det;
            // A step from a point whose residual is at rounding level, moving the point by
            // less than the tolerance, leaves an error of the order of its square.
            bool converged = std::max(std::fabs(j.x), std::fabs(j.y)) <= residual_converged &&
                             derivative * (std::fabs(da) + std::fabs(db)) <= depth_converged;
            if (!converged && proof && a >= r.a0 && a <= r.a1 && b >= r.b0 && b <= r.b1)
                converged = derivative * (wa + wb) * proof->distance_to_root(j.x, j.y) <= error_converged;
            a += da;
            b += db;
            if (converged) {
                const double margin_a = kRegionShare * wa + kParameterRounding;
                const double margin_b = kRegionShare * wb + kParameterRounding;
                if (!(a >= r.a0 - margin_a && a <= r.a1 + margin_a && b >= r.b0 - margin_b && b <= r.b1 + margin_b))
                    return false; // a root of another region: it is found there
                root_a = std::clamp(a, 0.0, 1.0);
                root_b = std::clamp(b, 0.0, 1.0);
                distance = evaluate_z(top, root_a, root_b);
                return true;
            }
            // Newton may overshoot a little on its way; far outside the region it is lost.
            if (!(a >= r.a0 - kNewtonWander * wa && a <= r.a1 + kNewtonWander * wa && b >= r.b0 - kNewtonWander * wb &&
                  b <= r.b1 + kNewtonWander * wb))
                return false; // also catches NaN
        }
        return false;
    }
};

} // namespace

bool intersect_patch(const ControlGrid &patch, const RayFrame &ray, const PatchRootQuery &query, PatchRoot &root) {
    RegionStack stack;
    // The whole patch stays here, outside the stack's pool, for Newton (which evaluates the
    // whole patch) to read after the search has split it; the stack names it kWholePatch.
    Region first;
    const double ox = ray.org.x, oy = ray.org.y, oz = ray.org.z;
    for (int k = 0; k < 16; ++k) {
        const double qx = patch.x[k] - ox, qy = patch.y[k] - oy, qz = patch.z[k] - oz;
        first.cp.x[k] = qx * ray.e1.x + qy * ray.e1.y + qz * ray.e1.z;
        first.cp.y[k] = qx * ray.e2.x + qy * ray.e2.y + qz * ray.e2.z;
        first.cp.z[k] = qx * ray.axis.x + qy * ray.axis.y + qz * ray.axis.z;
    }
    first.a0 = first.b0 = 0;
    first.a1 = first.b1 = 1;
    first.contraction_hint = 0;
    const Projected &top = first.cp;
    stack.push(RegionStack::kWholePatch);
    // The frame is a rotation: the largest projected coordinate is within sqrt(3) of the
    // largest coordinate of (control point - origin).
    const Bounds2 top_box = bounds_of(top);
    const double magnitude =
        kSqrt3 * std::max({-top_box.xmin, top_box.xmax, -top_box.ymin, top_box.ymax, -top_box.zmin, top_box.zmax});

    // Projection and De Casteljau each add a few ulps of the coordinates' magnitude.
    const double noise = kNoiseUlps * DBL_EPSILON * magnitude;
    const double point_size = std::max(query.tolerance, kPointSizeInNoise * noise);
    // Where the Jacobian is regular, undecided regions are split down to this size.
    const double fine_size = std::max(kFineShare * point_size, kPointSizeInNoise * noise);
    const Solver solver{top, patch.derivative_bound, std::max(noise, kResidualShare * query.tolerance),
                        kStepShare * point_size, kProvenShare * point_size};
    const double znear = query.tnear * ray.dir_length;
    double zbest = query.tfar * ray.dir_length;
    bool found = false;

    auto accept = [&](double a, double b, double z) {
        if (!(z >= znear && z <= zbest)) return false;
        zbest = z;
        root.t = z / ray.dir_length;
        root.a = a;
        root.b = b;
        found = true;
        return true;
    };

    while (!stack.empty()) {
        const int slot = stack.pop();
        // Freed when this iteration ends, whichever `continue` ends it: until then the
        // children, written to other slots, are made from it.
        struct Release {
            RegionStack &stack;
            int slot;
            ~Release() {
                if (slot != RegionStack::kWholePatch) stack.release(slot);
            }
        } release{stack, slot};
        const Region &r = slot == RegionStack::kWholePatch ? first : stack[slot];
        const Bounds2 box = bounds_of(r.cp);
        if (box.xmin > noise || box.xmax < -noise || box.ymin > noise || box.ymax < -noise) continue;
        if (box.zmax < znear - noise || box.zmin > zbest + noise) continue;
        if (misses_chord_slabs(r.cp, noise)) continue;

        const double extent = std::max({box.xmax - box.xmin, box.ymax - box.ymin, box.zmax - box.zmin});
        const double wa = r.a1 - r.a0, wb = r.b1 - r.b0;
        const double ca = r.a0 + 0.5 * wa, cb = r.b0 + 0.5 * wb;
        const bool skip_test = r.contraction_hint > skip_krawczyk_hint && extent > point_size;
        const Krawczyk proof = skip_test ? Krawczyk{} : krawczyk_test(r.cp);
        const double child_hint = 0.5 * (skip_test ? r.contraction_hint : proof.contraction);
        if (proof.verdict == Verdict::no_root) continue;
        if (proof.verdict == Verdict::one_root || proof.verdict == Verdict::at_most_one_root) {
            double a, b, z;
            if (solver.newton(r.a0 + proof.start_a * wa, r.b0 + proof.start_b * wb, r, &proof, a, b, z)) {
                if (accept(a, b, z) && query.any_hit) return true;
                continue;
            }
        }

        // Undecided and below the tolerance: the region is a point of the surface within the
        // tolerance of the ray. Not before it is also singular (a tangent ray, a collapsed
        // edge) or far below the tolerance, though: a grazing ray stays within the tolerance
        // of the surface over a stretch much longer than the tolerance, so a merely small
        // region may lie well before the crossing, or hold two close crossings.
        const bool at_precision_limit = wa <= kParameterResolution && wb <= kParameterResolution;
        if ((extent <= point_size && (proof.singular || extent <= fine_size)) || at_precision_limit) {
            // Newton may still reach a crossing just outside the region; only where it finds
            // none is the centre itself the answer.
            double a = ca, b = cb, z = evaluate_z(top, ca, cb);
            double root_a, root_b, root_z;
            if (solver.newton(ca, cb, r, nullptr, root_a, root_b, root_z) ||
                (solver.newton(ca, cb, first, nullptr, root_a, root_b, root_z) &&
                 std::fabs(root_z - z) <= point_size)) {
                a = root_a;
                b = root_b;
                z = root_z;
            }
            if (accept(a, b, z) && query.any_hit) return true;
            continue;
        }

        double along_a, along_b;
        net_lengths(r.cp, along_a, along_b);
        const bool cut_a = wb <= kParameterResolution || (wa > kParameterResolution && along_a >= along_b);
        // Both halves go on the stack, the one reaching nearer along the ray on top.
        const int low_slot = stack.acquire(), high_slot = stack.acquire();
        Region &low = stack[low_slot], &high = stack[high_slot]; // the halves below / above the cut
        if (cut_a) {
            split_a(r.cp, 0.5, low.cp, high.cp);
            low.a0 = r.a0;
            low.a1 = ca;
            high.a0 = ca;
            high.a1 = r.a1;
            low.b0 = high.b0 = r.b0;
            low.b1 = high.b1 = r.b1;
        } else {
            split_b(r.cp, 0.5, low.cp, high.cp);
            low.b0 = r.b0;
            low.b1 = cb;
            high.b0 = cb;
            high.b1 = r.b1;
            low.a0 = high.a0 = r.a0;
            low.a1 = high.a1 = r.a1;
        }
        low.contraction_hint = high.contraction_hint = child_hint;
        const double low_z = *std::min_element(low.cp.z, low.cp.z + 16);
        const double high_z = *std::min_element(high.cp.z, high.cp.z + 16);
        const bool low_first = low_z <= high_z;
        stack.push(low_first ? high_slot : low_slot);
        stack.push(low_first ? low_slot : high_slot);
    }
    return found;
}

} // namespace ppm
