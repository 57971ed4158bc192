// SPDX-License-Identifier: Apache-2.0
// Conversion of sampled spectra to linear sRGB, as Mitsuba 3's RGB variants read <spectrum>
// values (the rule is described in spectrum.cpp).
#pragma once

#include "math/rgb.h"

#include <vector>

namespace ppm {

// `wavelengths` in nm, increasing, with one value each (at least one pair). `reflectance`:
// weigh with D65 (reflectances and other albedos) or not (emission). The result may lie
// outside [0, 1] or be negative for colours outside the sRGB gamut; callers clamp as they need.
Rgb spectrum_to_rgb(const std::vector<double> &wavelengths, const std::vector<double> &values, bool reflectance);

// CIE XYZ to linear sRGB.
Rgb xyz_to_srgb(double x, double y, double z);

} // namespace ppm
