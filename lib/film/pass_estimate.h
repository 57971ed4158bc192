// SPDX-License-Identifier: Apache-2.0
// What a mode that estimates a whole pass itself hands the film (Integrator::estimate_pass).
#pragma once

#include "math/rgb.h"

#include <cstdint>
#include <vector>

namespace ppm {

// A whole pass's estimate, for modes that make it themselves (Integrator::estimates_whole_pass).
struct PassEstimate {
    std::vector<Rgb> radiance;         // per pixel
    std::vector<std::uint32_t> merges; // per pixel: light vertices merged (the "photons" layer)
    double radius = 0;                 // the merge radius (the "radius" layer)
    std::uint64_t light_paths = 0;     // light subpaths traced (the film's photons emitted)
};

} // namespace ppm
