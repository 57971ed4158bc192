// SPDX-License-Identifier: Apache-2.0
// Command line of `ppm-bench targets`.
#pragma once

#include "common/command_line.h"

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

struct TargetsOptions {
    std::string bpt_path;                 // empty: teapot.bpt in the data folder (data_files.h)
    std::vector<int> presplits = {3, 12}; // exact method at these scene patch_presplit values
    int grid = 128;                       // the meshes: grid x grid quads per patch
    size_t rays = 20000;                  // random rays
    int width = 256, height = 256;        // camera rays
    int rounds = 9;
    double min_seconds = 0.2; // per timing of one method on one set
    uint64_t seed = 1;
    std::string csv_path; // empty: no CSV
};

// Adds the subcommand `targets` to `app`; parsing it fills `options`.
CLI::App *add_targets_command(CLI::App &app, TargetsOptions &options);

// What CLI11 cannot check alone, after parsing; throws ppm_tools::UsageError. Drops repeated
// presplit values, which would only time the same method twice under one name.
void check_targets_options(TargetsOptions &options);

} // namespace bench
