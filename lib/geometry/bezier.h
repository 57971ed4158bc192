// SPDX-License-Identifier: Apache-2.0
// Bicubic Bezier patch math: evaluation, derivatives, De Casteljau subdivision, normals.
//
// Control point P[i][j] is p[i * 4 + j]; u runs along a row (index j), v across rows (index
// i): S(u, v) = sum_i sum_j B_i(v) B_j(u) P[i][j]. This is the .bpt and Embree convention.
#pragma once

#include "math/vec3.h"

namespace ppm {

struct BezierPatch {
    Vec3 p[16];
    const Vec3 &at(int i, int j) const { return p[i * 4 + j]; }
};

// Cubic Bernstein polynomials B_0..B_3 at t and their derivatives.
inline void bernstein3(double t, double b[4]) {
    const double s = 1.0 - t;
    b[0] = s * s * s;
    b[1] = 3.0 * t * s * s;
    b[2] = 3.0 * t * t * s;
    b[3] = t * t * t;
}
inline void bernstein3_derivative(double t, double d[4]) {
    const double s = 1.0 - t;
    d[0] = -3.0 * s * s;
    d[1] = 3.0 * s * (s - 2.0 * t);
    d[2] = 3.0 * t * (2.0 * s - t);
    d[3] = 3.0 * t * t;
}

inline void bernstein3_second(double t, double d[4]) {
    d[0] = 6.0 * (1.0 - t);
    d[1] = 18.0 * t - 12.0;
    d[2] = 6.0 - 18.0 * t;
    d[3] = 6.0 * t;
}

// One De Casteljau step on four values a[0], a[stride], a[2*stride], a[3*stride]: the curve
// on [0, t] goes to `left`, the one on [t, 1] to `right` (same stride). Works in place for
// the output arrays but not when `left` or `right` alias `a`.
template <class T> inline void de_casteljau_split(const T *a, int stride, double t, T *left, T *right) {
    const T p0 = a[0], p1 = a[stride], p2 = a[2 * stride], p3 = a[3 * stride];
    const T q0 = p0 + (p1 - p0) * t, q1 = p1 + (p2 - p1) * t, q2 = p2 + (p3 - p2) * t;
    const T r0 = q0 + (q1 - q0) * t, r1 = q1 + (q2 - q1) * t;
    const T s0 = r0 + (r1 - r0) * t;
    left[0] = p0;
    left[stride] = q0;
    left[2 * stride] = r0;
    left[3 * stride] = s0;
    right[0] = s0;
    right[stride] = r1;
    right[2 * stride] = q2;
    right[3 * stride] = p3;
}

// Position and first derivatives at (u, v).
struct SurfaceDerivatives {
    Vec3 p, du, dv;
};

struct SecondDerivatives {
    Vec3 uu, uv, vv;
};

Vec3 evaluate(const BezierPatch &patch, double u, double v);
SurfaceDerivatives evaluate_derivatives(const BezierPatch &patch, double u, double v);
Vec3 mixed_derivative(const BezierPatch &patch, double u, double v);
SecondDerivatives second_derivatives(const BezierPatch &patch, double u, double v);

// Unit geometric normal dS/du x dS/dv. Where a derivative vanishes (a collapsed edge such as
// the teapot's lid apex) the limit of the normalised cross product is returned, taken along
// the other parameter. Returns the zero vector only for a patch that is a single point or a
// curve everywhere.
Vec3 geometric_normal(const BezierPatch &patch, double u, double v);
// The same with the patch's size (diagonal of its control points) known.
Vec3 geometric_normal(const BezierPatch &patch, double u, double v, double scale);
// The same reusing evaluate_derivatives(patch, u, v).
Vec3 geometric_normal(const BezierPatch &patch, double u, double v, double scale, const SurfaceDerivatives &at_uv);

// Splits at u = t (left: u in [0, t]) or at v = t (left: v in [0, t]).
void split_u(const BezierPatch &patch, double t, BezierPatch &left, BezierPatch &right);
void split_v(const BezierPatch &patch, double t, BezierPatch &left, BezierPatch &right);

// The patch restricted to [u0, u1] x [v0, v1], reparametrised to [0, 1]^2. The interval may
// extend beyond [0, 1] (the polynomial is extrapolated); u1 and v1 must be nonzero.
BezierPatch sub_patch(const BezierPatch &patch, double u0, double u1, double v0, double v1);

// The linear map taking a cubic's control points to those of its restriction to [a, b]
// (reparametrised to [0, 1]): row k holds the weights of the blossom at (a^(3-k), b^k).
struct IntervalMatrix {
    double w[4][4];
    static IntervalMatrix of(double a, double b);
};

// sub_patch through precomputed interval matrices (rows: v, columns: u), written as a
// structure of arrays p[i * 4 + j]: the same patch up to rounding, at a third of the cost.
void sub_patch_soa(const BezierPatch &patch, const IntervalMatrix &along_u, const IntervalMatrix &along_v, double x[16],
                   double y[16], double z[16]);

// Box of the control points, which contains the surface (convex hull property).
Box3 control_bounds(const BezierPatch &patch);

} // namespace ppm
