// SPDX-License-Identifier: Apache-2.0
// Limits every tessellation stays within, shared by its steps.
#pragma once

#include <cstdint>

namespace ppm {
namespace tess {

// Upper end of the doubling searches for edge segments and grid lines: (2^22)^2 triangles are
// far beyond max_tessellation_triangles, so a count that needs more is over budget anyway.
constexpr uint32_t max_segments = 1u << 22;

// Throws INVALID_ARGUMENT: about `triangles` would exceed max_tessellation_triangles.
[[noreturn]] void over_budget(double triangles);

} // namespace tess
} // namespace ppm
