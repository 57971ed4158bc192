// SPDX-License-Identifier: Apache-2.0
// Affine transforms of scene files (`to_world`): Mitsuba's operations, composed in the order
// listed (the first acts first).
#pragma once

#include "math/vec3.h"
#include "scenefile/json_node.h"

#include <array>

namespace ppm {

bool is_identity(const Affine &a);
// The 4x4 row-major matrix ppm_scene_set_geometry_transform takes.
std::array<double, 16> matrix16(const Affine &a);

// a then b: (b * a) p = b(a(p)).
Affine then(const Affine &a, const Affine &b);

// One operation object or an array of them; fails (PARSE, located) on unknown operations,
// zero scales, zero rotation axes, singular matrices and degenerate look_at frames.
Affine parse_transform(const JsonNode &node);

} // namespace ppm
