// SPDX-License-Identifier: Apache-2.0
// Small helpers shared by the BSDF files: parameter checks with the messages the API reports,
// and arithmetic in the local shading frame (normal along +z).
#ifndef PPM_MATERIAL_BSDF_HELPERS_H
#define PPM_MATERIAL_BSDF_HELPERS_H

#include "core/error.h"
#include "math/rgb.h"
#include "math/vec3.h"

#include <cmath>
#include <string>

namespace ppm::bsdf_helpers {

// A reflectance or transmittance: finite and within [0, 1] in every channel.
inline void require_reflectance(const Rgb &c, const char *what) {
    if (!(c.is_finite() && c.min() >= 0 && c.max() <= 1))
        invalid_argument(std::string(what) + " must lie in [0, 1] per channel, got (" + format_number(c.r) + ", " +
                         format_number(c.g) + ", " + format_number(c.b) + ")");
}

// A microfacet roughness: finite and > 0.
inline void require_alpha(double alpha, const std::string &what) {
    if (!(alpha > 0 && std::isfinite(alpha)))
        invalid_argument(what + " must be finite and > 0, got " + format_number(alpha));
}

inline double sqr(double x) { return x * x; }

// Mirror reflection about the local normal.
inline Vec3 reflect_local(const Vec3 &w) { return {-w.x, -w.y, w.z}; }

} // namespace ppm::bsdf_helpers

#endif
