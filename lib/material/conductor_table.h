// SPDX-License-Identifier: Apache-2.0
// Mitsuba 3's named conductors (the `material` parameter of `conductor` and
// `roughconductor`: "Au", "Cu", "Al", ...) with their RGB complex indices of refraction.
#pragma once

#include "math/rgb.h"

#include <string>
#include <vector>

namespace ppm {

struct ConductorIor {
    const char *name;
    Rgb eta, k;
};

// The preset of that name (case-sensitive, as Mitsuba), or null. "none" is not in the table.
const ConductorIor *find_conductor(const char *name);
// The same, throwing ppm::Error (invalid argument, with a "did you mean") for unknown names.
const ConductorIor &conductor_material(const std::string &name);
std::vector<std::string> conductor_names();

} // namespace ppm
