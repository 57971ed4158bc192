// SPDX-License-Identifier: Apache-2.0
// Reader for .bpt files: a patch count, then per patch a degree line "3 3" and 16 lines of
// "x y z". '#' starts a comment that runs to the end of the line.
#pragma once

#include "geometry/bezier.h"

#include <string>
#include <vector>

namespace ppm {

// Largest patch count a file may announce; more is taken as a corrupt file.
constexpr size_t max_bpt_patches = 10000000;

// Throws ppm::Error: IO if the file cannot be read, PARSE with "path:line: what" otherwise.
std::vector<BezierPatch> read_bpt_file(const std::string &path);
// The same on text already in memory; `name` is used in messages.
std::vector<BezierPatch> parse_bpt(const std::string &text, const std::string &name);

} // namespace ppm
