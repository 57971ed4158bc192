// SPDX-License-Identifier: Apache-2.0
#include "geometry/bezier.h"

#include <cfloat>

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#endif

namespace ppm {

namespace {

// A derivative shorter than this share of the patch's size is rounding noise of a collapsed
// edge (evaluation rounds at ~1e-15 of it), not a tangent: far above the noise, far below
// the tangents of any patch of sensible proportions.
constexpr double kVanishingShare = 1e-10;
// Where both derivatives and the twist vanish, the normal is taken this share of the way
// towards the patch centre (times the attempt): enough to move off the degenerate point in
// double, little enough to be its limit. Polynomial data need at most three such steps.
constexpr double kCentreStep = 1e-7;
constexpr int kNormalAttempts = 4;

inline Vec3 tensor_sum(const BezierPatch &patch, const double bu[4], const double bv[4]) {
    Vec3 sum;
    for (int i = 0; i < 4; ++i) {
        Vec3 row = patch.at(i, 0) * bu[0] + patch.at(i, 1) * bu[1] + patch.at(i, 2) * bu[2] + patch.at(i, 3) * bu[3];
        sum += row * bv[i];
    }
    return sum;
}

} // namespace

Vec3 evaluate(const BezierPatch &patch, double u, double v) {
    double bu[4], bv[4];
    bernstein3(u, bu);
    bernstein3(v, bv);
    return tensor_sum(patch, bu, bv);
}

SurfaceDerivatives evaluate_derivatives(const BezierPatch &patch, double u, double v) {
    double bu[4], bv[4], du[4], dv[4];
    bernstein3(u, bu);
    bernstein3(v, bv);
    bernstein3_derivative(u, du);
    bernstein3_derivative(v, dv);
    // Each row's value and u-derivative once, shared by all three sums.
    SurfaceDerivatives d;
    for (int i = 0; i < 4; ++i) {
        const Vec3 *row = &patch.p[4 * i];
        const Vec3 r = row[0] * bu[0] + row[1] * bu[1] + row[2] * bu[2] + row[3] * bu[3];
        const Vec3 ru = row[0] * du[0] + row[1] * du[1] + row[2] * du[2] + row[3] * du[3];
        d.p += r * bv[i];
        d.dv += r * dv[i];
        d.du += ru * bv[i];
    }
    return d;
}

SecondDerivatives second_derivatives(const BezierPatch &patch, double u, double v) {
    double bu[4], bv[4], du[4], dv[4], duu[4], dvv[4];
    bernstein3(u, bu);
    bernstein3(v, bv);
    bernstein3_derivative(u, du);
    bernstein3_derivative(v, dv);
    bernstein3_second(u, duu);
    bernstein3_second(v, dvv);
    return {tensor_sum(patch, duu, bv), tensor_sum(patch, du, dv), tensor_sum(patch, bu, dvv)};
}

Vec3 mixed_derivative(const BezierPatch &patch, double u, double v) {
    double du[4], dv[4];
    bernstein3_derivative(u, du);
    bernstein3_derivative(v, dv);
    return tensor_sum(patch, du, dv);
}

Vec3 geometric_normal(const BezierPatch &patch, double u, double v) {
    return geometric_normal(patch, u, v, control_bounds(patch).diagonal());
}

Vec3 geometric_normal(const BezierPatch &patch, double u, double v, double scale) {
    return geometric_normal(patch, u, v, scale, evaluate_derivatives(patch, u, v));
}

Vec3 geometric_normal(const BezierPatch &patch, double u, double v, double scale, const SurfaceDerivatives &at_uv) {
    if (!(scale > 0)) return {};
    const double vanish = kVanishingShare * scale;
    // Walk towards the patch centre if the point itself is degenerate in both directions
    // (both derivatives and the twist vanish).
    for (int attempt = 0; attempt < kNormalAttempts; ++attempt) {
        const SurfaceDerivatives d = attempt == 0 ? at_uv : evaluate_derivatives(patch, u, v);
        Vec3 tu = d.du, tv = d.dv;
        // Near a collapsed edge v = e, dS/du ~ (v - e) * d2S/dudv: the limit direction of
        // the cross product uses the twist vector, with the sign of (v - e).
        if (length2(tu) <= vanish * vanish) tu = mixed_derivative(patch, u, v) * (v < 0.5 ? 1.0 : -1.0);
        if (length2(tv) <= vanish * vanish) tv = mixed_derivative(patch, u, v) * (u < 0.5 ? 1.0 : -1.0);
        const Vec3 n = cross(tu, tv);
        const double len = length(n);
        if (len > vanish * vanish && std::isfinite(len)) return n / len;
        const double step = kCentreStep * (attempt + 1);
        u += (0.5 - u) * step;
        v += (0.5 - v) * step;
    }
    return {};
}

void split_u(const BezierPatch &patch, double t, BezierPatch &left, BezierPatch &right) {
    for (int i = 0; i < 4; ++i) de_casteljau_split(&patch.p[i * 4], 1, t, &left.p[i * 4], &right.p[i * 4]);
}

void split_v(const BezierPatch &patch, double t, BezierPatch &left, BezierPatch &right) {
    for (int j = 0; j < 4; ++j) de_casteljau_split(&patch.p[j], 4, t, &left.p[j], &right.p[j]);
}

BezierPatch sub_patch(const BezierPatch &patch, double u0, double u1, double v0, double v1) {
    // Cut at u1 first, then at u0 inside [0, u1] (relative position u0 / u1). De Casteljau
    // extrapolates just as well, so the interval may reach beyond [0, 1].
    BezierPatch a, b, c, d;
    if (u1 != 1.0)
        split_u(patch, u1, a, b);
    else
        a = patch;
    if (u0 != 0.0)
        split_u(a, u0 / u1, b, c);
    else
        c = a;
    if (v1 != 1.0)
        split_v(c, v1, a, b);
    else
        a = c;
    if (v0 != 0.0)
        split_v(a, v0 / v1, b, d);
    else
        d = a;
    return d;
}

IntervalMatrix IntervalMatrix::of(double a, double b) {
    IntervalMatrix m;
    for (int k = 0; k < 4; ++k) {
        // De Casteljau on the unit coefficient vectors, one level per blossom argument.
        const double args[3] = {k >= 3 ? b : a, k >= 2 ? b : a, k >= 1 ? b : a};
        for (int point = 0; point < 4; ++point) {
            double c[4] = {0, 0, 0, 0};
            c[point] = 1;
            for (int level = 0; level < 3; ++level)
                for (int i = 0; i < 3 - level; ++i) c[i] += (c[i + 1] - c[i]) * args[level];
            m.w[k][point] = c[0];
        }
    }
    return m;
}

void sub_patch_soa(const BezierPatch &patch, const IntervalMatrix &along_u, const IntervalMatrix &along_v, double x[16],
                   double y[16], double z[16]) {
    // Rows first: r[i][j] = sum_l u.w[j][l] P[i][l]; then columns: sum_k v.w[i][k] r[k][j].
#if defined(__AVX2__) && defined(__FMA__)
    // A row of r or of the result is one register over j; this runs for every ray that gets
    // past a sub-patch's culling, and the scalar loops take over twice the instructions.
    const __m256d w0 = _mm256_loadu_pd(along_u.w[0]), w1 = _mm256_loadu_pd(along_u.w[1]);
    const __m256d w2 = _mm256_loadu_pd(along_u.w[2]), w3 = _mm256_loadu_pd(along_u.w[3]);
    const __m256d t0 = _mm256_unpacklo_pd(w0, w1), t1 = _mm256_unpackhi_pd(w0, w1);
    const __m256d t2 = _mm256_unpacklo_pd(w2, w3), t3 = _mm256_unpackhi_pd(w2, w3);
    const __m256d column[4] = {_mm256_permute2f128_pd(t0, t2, 0x20), _mm256_permute2f128_pd(t1, t3, 0x20),
                               _mm256_permute2f128_pd(t0, t2, 0x31), _mm256_permute2f128_pd(t1, t3, 0x31)};
    __m256d rx[4], ry[4], rz[4];
    for (int i = 0; i < 4; ++i) {
        const Vec3 *row = &patch.p[i * 4];
        rx[i] = _mm256_mul_pd(column[0], _mm256_set1_pd(row[0].x));
        ry[i] = _mm256_mul_pd(column[0], _mm256_set1_pd(row[0].y));
        rz[i] = _mm256_mul_pd(column[0], _mm256_set1_pd(row[0].z));
        for (int l = 1; l < 4; ++l) {
            rx[i] = _mm256_fmadd_pd(column[l], _mm256_set1_pd(row[l].x), rx[i]);
            ry[i] = _mm256_fmadd_pd(column[l], _mm256_set1_pd(row[l].y), ry[i]);
            rz[i] = _mm256_fmadd_pd(column[l], _mm256_set1_pd(row[l].z), rz[i]);
        }
    }
    for (int i = 0; i < 4; ++i) {
        __m256d w = _mm256_set1_pd(along_v.w[i][0]);
        __m256d sx = _mm256_mul_pd(w, rx[0]), sy = _mm256_mul_pd(w, ry[0]), sz = _mm256_mul_pd(w, rz[0]);
        for (int k = 1; k < 4; ++k) {
            w = _mm256_set1_pd(along_v.w[i][k]);
            sx = _mm256_fmadd_pd(w, rx[k], sx);
            sy = _mm256_fmadd_pd(w, ry[k], sy);
            sz = _mm256_fmadd_pd(w, rz[k], sz);
        }
        _mm256_storeu_pd(x + 4 * i, sx);
        _mm256_storeu_pd(y + 4 * i, sy);
        _mm256_storeu_pd(z + 4 * i, sz);
    }
#else
    double rx[16], ry[16], rz[16];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double sx = 0, sy = 0, sz = 0;
            for (int l = 0; l < 4; ++l) {
                const Vec3 &p = patch.p[i * 4 + l];
                sx += along_u.w[j][l] * p.x;
                sy += along_u.w[j][l] * p.y;
                sz += along_u.w[j][l] * p.z;
            }
            rx[i * 4 + j] = sx;
            ry[i * 4 + j] = sy;
            rz[i * 4 + j] = sz;
        }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double sx = 0, sy = 0, sz = 0;
            for (int k = 0; k < 4; ++k) {
                sx += along_v.w[i][k] * rx[k * 4 + j];
                sy += along_v.w[i][k] * ry[k * 4 + j];
                sz += along_v.w[i][k] * rz[k * 4 + j];
            }
            x[i * 4 + j] = sx;
            y[i * 4 + j] = sy;
            z[i * 4 + j] = sz;
        }
#endif
}

Box3 control_bounds(const BezierPatch &patch) {
    Box3 box;
    for (const Vec3 &p : patch.p) box.extend(p);
    return box;
}

} // namespace ppm
