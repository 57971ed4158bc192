// SPDX-License-Identifier: Apache-2.0
// The bench's own .bpt reader: the tessellation baselines need control points, and tools see
// only the public C API, which loads patches but does not hand them back.
#pragma once

#include <string>
#include <vector>

namespace bench {

// Control points of every patch in `path`: 16 * 3 doubles per patch, P[i][j] at i * 4 + j
// (the layout of ppm_scene_add_bezier_patches). Throws std::runtime_error naming file and
// line on any problem.
std::vector<double> read_bpt_patches(const std::string &path);

} // namespace bench
