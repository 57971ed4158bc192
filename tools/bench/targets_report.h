// SPDX-License-Identifier: Apache-2.0
// The output of `ppm-bench targets`: speed tables per ray set, the ratios behind each target
// with its verdict, and the CSV of every timing.
#pragma once

#include "interleaved_rounds.h"

#include <cstdio>
#include <string>
#include <vector>

namespace bench {

// One table per ray set: each method's memory, median rays/s with the range over rounds, and
// how many rays it hits where methods[0] misses or the reverse.
void print_speed_tables(std::FILE *out, const std::vector<RaySet> &sets, const std::vector<BuiltMethod> &methods,
                        const RoundsResult &rounds);

// For every exact method (family exact-presplit): the ratio behind each target against the
// mesh methods (embree-uniform, cgal-uniform) and a PASS / FAIL verdict, then the camera-ray
// ratios, which have no target. Speed ratios are medians over rounds of the ratio within a
// round.
void print_verdicts(std::FILE *out, const std::vector<RaySet> &sets, const std::vector<BuiltMethod> &methods,
                    const RoundsResult &rounds);

// One row per round, method and ray set. Throws on I/O errors.
void write_rounds_csv(const std::string &path, const std::vector<RaySet> &sets, const std::vector<BuiltMethod> &methods,
                      const RoundsResult &rounds);

} // namespace bench
