// Command line of `ppm-bench targets`.
#pragma once

#include "option_values.h" // ParseResult

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace bench {

struct TargetsOptions {
    std::string bpt_path = PPM_SOURCE_DIR "/tests/data/teapot.bpt"; // the repository copy
    std::vector<int> presplits = {3, 12};                           // exact method at these scene patch_presplit values
    int grid = 128;                                                 // the meshes: grid x grid quads per patch
    size_t rays = 20000;                                            // random rays
    int width = 256, height = 256;                                  // camera rays
    int rounds = 9;
    double min_seconds = 0.2; // per timing of one method on one set
    uint64_t seed = 1;
    std::string csv_path; // empty: no CSV
};

// Parses argv[first..argc). On error prints the reason to stderr.
ParseResult parse_targets_args(int argc, char **argv, int first, TargetsOptions &options);

void print_targets_usage(std::FILE *out);

} // namespace bench
