// Interval enclosures of a bicubic's partial derivatives over its whole domain, from the
// differences of its control values (the derivative's own Bernstein coefficients). Shared by
// the ray/patch search (Krawczyk test) and the sub-patch chord bound.
#pragma once

#include <algorithm>
#include <cmath>

namespace ppm {

struct Interval {
    double lo, hi;
    double magnitude() const { return std::max(std::fabs(lo), std::fabs(hi)); }
};

// d/da of the 16 control values c (index i * 4 + j, a along j) over [0, 1]^2.
inline Interval derivative_hull_a(const double *c) {
    Interval r{INFINITY, -INFINITY};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 3; ++j) {
            const double d = 3.0 * (c[i * 4 + j + 1] - c[i * 4 + j]);
            r.lo = std::min(r.lo, d);
            r.hi = std::max(r.hi, d);
        }
    return r;
}

// d/db (b along i).
inline Interval derivative_hull_b(const double *c) {
    Interval r{INFINITY, -INFINITY};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
            const double d = 3.0 * (c[(i + 1) * 4 + j] - c[i * 4 + j]);
            r.lo = std::min(r.lo, d);
            r.hi = std::max(r.hi, d);
        }
    return r;
}

// Interval of y * [i.lo, i.hi] for a point value y.
inline Interval scale(double y, Interval i) {
    const double p = y * i.lo, q = y * i.hi;
    return {std::min(p, q), std::max(p, q)};
}

} // namespace ppm
