// SPDX-License-Identifier: Apache-2.0
// The largest magnitudes a scene may hold. Inputs beyond them are refused where they enter, so
// that no sum, square or product formed while rendering (squared distances, light power, flux
// sums, float images) can overflow into inf or NaN.
#pragma once

#include "math/vec3.h"

namespace ppm {

// Every coordinate, length and radius in scene units: its square (1e24) and products with
// the path lengths a render forms stay far inside double range, and Embree's single-precision
// boxes stay finite.
constexpr double kCoordinateLimit = 1e12;

// Every channel of a light's intensity or an area light's radiance: the total power of a
// light as large as kCoordinateLimit allows stays finite, and so does a pixel of the float
// image (3.4e38).
constexpr double kEmissionLimit = 1e20;

// |x| <= limit, false for NaN.
inline bool within(double x, double limit) { return x >= -limit && x <= limit; }

// A point or vector of the scene: every coordinate within kCoordinateLimit.
inline bool within_coordinate_limit(const Vec3 &v) {
    return within(v.x, kCoordinateLimit) && within(v.y, kCoordinateLimit) && within(v.z, kCoordinateLimit);
}

} // namespace ppm
