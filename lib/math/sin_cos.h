// SPDX-License-Identifier: Apache-2.0
// Sine and cosine for the sampling warps, without libm's general range reduction: the
// renderer's angles are either within [-pi/4, pi/4] already (the concentric disk map) or
// 2 pi u for a uniform u in [0, 1), which reduces exactly by octants. Kept because it pays
// over 5 % of smallppm's photon pass (docs/bench/code-history.md). Accurate to a few ulps
// (tests/test_bsdf.cpp checks against std::sin/cos).
#pragma once

namespace ppm {

// sin x and cos x for |x| <= pi/4, by the minimax polynomials of Cephes (Moshier, sin.c).
inline void sin_cos_quarter(double x, double *s, double *c) {
    const double z = x * x;
    const double sp =
        ((((1.58962301576546568060e-10 * z - 2.50507477628578072866e-8) * z + 2.75573136213857245213e-6) * z -
          1.98412698295895385996e-4) *
             z +
         8.33333333332211858878e-3) *
            z -
        1.66666666666666307295e-1;
    const double cp =
        ((((-1.13585365213876817300e-11 * z + 2.08757008419747316778e-9) * z - 2.75573141792967388112e-7) * z +
          2.48015872888517045348e-5) *
             z -
         1.38888888888730564116e-3) *
            z +
        4.16666666666665929218e-2;
    *s = x + x * z * sp;
    *c = 1.0 - 0.5 * z + z * z * cp;
}

// sin and cos of 2 pi u for u in [0, 1): u * 8 splits exactly into an octant and the
// fraction within it; the angle is then k pi/2 + x with |x| <= pi/4.
inline void sin_cos_2pi(double u, double *s, double *c) {
    constexpr double kQuarterPi = 0.78539816339744830962;
    const double t = u * 8;
    const int octant = static_cast<int>(t); // t >= 0
    const double fraction = t - octant;
    int k;
    double x;
    if (octant & 1) { // angle = (octant + 1) pi/4 - (1 - fraction) pi/4
        k = (octant + 1) / 2;
        x = (fraction - 1) * kQuarterPi;
    } else {
        k = octant / 2;
        x = fraction * kQuarterPi;
    }
    double sx, cx;
    sin_cos_quarter(x, &sx, &cx);
    switch (k & 3) {
    case 0:
        *s = sx;
        *c = cx;
        break;
    case 1:
        *s = cx;
        *c = -sx;
        break;
    case 2:
        *s = -sx;
        *c = -cx;
        break;
    default:
        *s = -cx;
        *c = sx;
        break;
    }
}

} // namespace ppm
