// SPDX-License-Identifier: Apache-2.0
#include "geometry/chord_slope.h"

#include "geometry/derivative_hull.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace ppm {

namespace {

// Rounding of a sub-patch's control points, in ulps of their magnitude: the De Casteljau cuts
// and the dot products below each add a few.
constexpr double kControlPointUlps = 32;
// A derivative coefficient 3 (c1 - c0) carries the rounding of two control points, times 3.
constexpr double kDerivativeUlpFactor = 6;
// The hull and contraction arithmetic is not outward rounded; its terms are of order 1 and
// round by ~1e-15: this covers them ten thousandfold.
constexpr double kContractionRounding = 1e-12;
// The slope divides by 1 - contraction: above this the bound grows beyond 100 times the
// height's derivatives and settles no ray; it also keeps clear of 1 for rounding.
constexpr double kMaxContraction = 0.99;
// The handful of roundings of the slope's product and quotient, relative, with headroom.
constexpr double kSlopeRounding = 1e-9;
// Rounding of a dot or cross product of v and n, in ulps of |v|_1 |n|_1.
constexpr double kProductUlps = 16;

Interval widened(Interval i, double pad) { return {i.lo - pad, i.hi + pad}; }
double midpoint(Interval i) { return 0.5 * (i.lo + i.hi); }

} // namespace

double chord_slope_bound(const ControlGrid &grid, const Vec3 &n) {
    Vec3 e1, e2;
    orthonormal_basis(n, e1, e2);
    double h[16], q1[16], q2[16], magnitude = 0;
    for (int k = 0; k < 16; ++k) {
        const Vec3 c{grid.x[k], grid.y[k], grid.z[k]};
        h[k] = dot(n, c);
        q1[k] = dot(e1, c);
        q2[k] = dot(e2, c);
        magnitude = std::max(magnitude, max_abs_component(c));
    }
    const double pad = kDerivativeUlpFactor * kControlPointUlps * DBL_EPSILON * magnitude;
    const Interval ha = widened(derivative_hull_a(h), pad), hb = widened(derivative_hull_b(h), pad);
    const Interval q1a = widened(derivative_hull_a(q1), pad), q1b = widened(derivative_hull_b(q1), pad);
    const Interval q2a = widened(derivative_hull_a(q2), pad), q2b = widened(derivative_hull_b(q2), pad);

    // Any invertible Y gives a valid bound; the inverse of the hulls' midpoint Jacobian a good one.
    const double m00 = midpoint(q1a), m01 = midpoint(q1b), m10 = midpoint(q2a), m11 = midpoint(q2b);
    const double det = m00 * m11 - m01 * m10;
    if (!(std::fabs(det) > 0) || !std::isfinite(det)) return INFINITY;
    const double y00 = m11 / det, y01 = -m01 / det, y10 = -m10 / det, y11 = m00 / det;
    // Row r of I - Y Dq: identity - (Y_r0 q1 + Y_r1 q2) for the a and the b column.
    auto entry = [](double identity, Interval u, Interval v) {
        return Interval{identity - (u.hi + v.hi), identity - (u.lo + v.lo)}.magnitude();
    };
    const double row0 = entry(1.0, scale(y00, q1a), scale(y01, q2a)) + entry(0.0, scale(y00, q1b), scale(y01, q2b));
    const double row1 = entry(0.0, scale(y10, q1a), scale(y11, q2a)) + entry(1.0, scale(y10, q1b), scale(y11, q2b));
    const double contraction = std::max(row0, row1) + kContractionRounding;
    if (!(contraction < kMaxContraction)) return INFINITY;
    const double y_norm = std::max(std::fabs(y00) + std::fabs(y01), std::fabs(y10) + std::fabs(y11));
    const double slope = (ha.magnitude() + hb.magnitude()) * y_norm / (1 - contraction) * (1 + kSlopeRounding);
    return std::isfinite(slope) ? slope : INFINITY;
}

bool leaves_for_good(const Vec3 &n, double slope, const Vec3 &offset, double offset_error, const Vec3 &dir) {
    if (!(slope < INFINITY)) return false;
    const double rise_offset = dot(n, offset), rise_dir = dot(n, dir);
    if (!(rise_offset * rise_dir > 0)) return false; // not both to one side of the plane
    const double side = rise_offset > 0 ? 1.0 : -1.0;
    // |v x n| / |n| is the in-plane length in any orthonormal frame around n; an error e in v
    // changes n . v and |v x n| by at most |e| |n| <= |e| |n|_1. The dot and cross products
    // round by a few ulps of |v| |n|.
    const double n_1 = std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
    auto steep = [&](const Vec3 &v, double rise, double error) {
        const double slack =
            error * n_1 + kProductUlps * DBL_EPSILON * n_1 * (std::fabs(v.x) + std::fabs(v.y) + std::fabs(v.z));
        return side * rise - slack > slope * (length(cross(v, n)) + slack);
    };
    return steep(offset, rise_offset, offset_error) && steep(dir, rise_dir, 0.0);
}

} // namespace ppm
