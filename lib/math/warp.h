// SPDX-License-Identifier: Apache-2.0
// Maps from uniform numbers in [0,1)^2 to the few distributions the renderer samples, with
// their densities. Same mappings as Mitsuba 3's `warp::` functions, so a sample sequence
// lands on the same points in both renderers.
#pragma once

#include "math/sin_cos.h"
#include "math/vec3.h"

#include <algorithm>
#include <cmath>

namespace ppm {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInvPi = 1.0 / kPi;

// Shirley and Chiu's concentric map onto the unit disk: low distortion, so stratified
// samples stay stratified. Returns (x, y) in *x, *y.
inline void square_to_uniform_disk_concentric(double u, double v, double *x, double *y) {
    const double a = 2.0 * u - 1.0, b = 2.0 * v - 1.0;
    if (a == 0 && b == 0) {
        *x = *y = 0;
        return;
    }
    // phi = pi/4 * b/a, or pi/2 - pi/4 * a/b, whose cosine and sine are the sine and cosine
    // of pi/4 * a/b: either way an angle within [-pi/4, pi/4] to take sin and cos of.
    double s, c;
    if (std::fabs(a) > std::fabs(b)) {
        sin_cos_quarter((kPi / 4.0) * (b / a), &s, &c);
        *x = a * c;
        *y = a * s;
    } else {
        sin_cos_quarter((kPi / 4.0) * (a / b), &s, &c);
        *x = b * s;
        *y = b * c;
    }
}

// Cosine-weighted upper hemisphere (z >= 0) by Malley's method: project the disk up.
// Uniform on the unit sphere (density 1 / (4 pi)).
inline Vec3 uniform_sphere(double u1, double u2) {
    const double z = 1.0 - 2.0 * u1, r = std::sqrt(std::max(0.0, 1.0 - z * z));
    double sin_phi, cos_phi;
    sin_cos_2pi(u2, &sin_phi, &cos_phi);
    return {r * cos_phi, r * sin_phi, z};
}

inline Vec3 square_to_cosine_hemisphere(double u, double v) {
    double x, y;
    square_to_uniform_disk_concentric(u, v, &x, &y);
    return {x, y, std::sqrt(std::max(0.0, 1.0 - x * x - y * y))};
}
inline double square_to_cosine_hemisphere_pdf(const Vec3 &w) { return w.z > 0 ? w.z * kInvPi : 0.0; }

} // namespace ppm
