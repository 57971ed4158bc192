// SPDX-License-Identifier: Apache-2.0
// Interval enclosures of a bicubic's partial derivatives over its whole domain, from the
// differences of its control values (the derivative's own Bernstein coefficients). Shared by
// the ray/patch search (Krawczyk test) and the sub-patch chord bound.
#pragma once

#include "math/min_max.h"

#include <algorithm>
#include <cmath>

namespace ppm {

struct Interval {
    double lo, hi;
    double magnitude() const { return std::max(std::fabs(lo), std::fabs(hi)); }
};

// The 12 coefficients go into 16 slots, the last four repeating the first, for min_max16.
inline Interval hull_of_12(double (&d)[16]) {
    for (int k = 12; k < 16; ++k) d[k] = d[k - 12];
    Interval r;
    min_max16(d, r.lo, r.hi);
    return r;
}

// d/da of the 16 control values c (index i * 4 + j, a along j) over [0, 1]^2.
inline Interval derivative_hull_a(const double *c) {
    double d[16];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 3; ++j) d[i * 3 + j] = 3.0 * (c[i * 4 + j + 1] - c[i * 4 + j]);
    return hull_of_12(d);
}

// d/db (b along i): the rows' differences, which are contiguous.
inline Interval derivative_hull_b(const double *c) {
    double d[16];
    for (int k = 0; k < 12; ++k) d[k] = 3.0 * (c[k + 4] - c[k]);
    return hull_of_12(d);
}

// Interval of y * [i.lo, i.hi] for a point value y.
inline Interval scale(double y, Interval i) {
    const double p = y * i.lo, q = y * i.hi;
    return {std::min(p, q), std::max(p, q)};
}

} // namespace ppm
