// SPDX-License-Identifier: Apache-2.0
// Fresnel reflectance of a conductor (complex index of refraction eta + i k relative to the
// outside medium) for unpolarised light: the mean of the s- and p-polarised reflectances,
// the same quantity as Mitsuba 3's fresnel_conductor (include/mitsuba/render/fresnel.h) and
// pbrt-v4's FrComplex (src/pbrt/util/scattering.h), written here with std::complex.
#pragma once

#include "math/rgb.h"

#include <algorithm>
#include <cmath>
#include <complex>

namespace ppm {

// cos_i = cos(angle of incidence to the normal), taken in [0, 1]; eta, k >= 0.
inline double fresnel_conductor(double cos_i, double eta, double k) {
    using C = std::complex<double>;
    cos_i = std::clamp(cos_i, 0.0, 1.0);
    const C n(eta, k);
    const double sin2_i = 1.0 - cos_i * cos_i;
    const C sin2_t = sin2_i / (n * n);
    const C cos_t = std::sqrt(C(1.0) - sin2_t);
    const C r_parallel = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    const C r_perpendicular = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    const double r = 0.5 * (std::norm(r_parallel) + std::norm(r_perpendicular));
    return std::isfinite(r) ? std::min(r, 1.0) : 1.0;
}

inline Rgb fresnel_conductor(double cos_i, const Rgb &eta, const Rgb &k) {
    return {fresnel_conductor(cos_i, eta.r, k.r), fresnel_conductor(cos_i, eta.g, k.g),
            fresnel_conductor(cos_i, eta.b, k.b)};
}

} // namespace ppm
