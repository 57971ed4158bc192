// SPDX-License-Identifier: Apache-2.0
// Command line of `ppm-bench intersect`.
#pragma once

#include "common/command_line.h"

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

struct IntersectOptions {
    std::string bpt_path;          // empty: teapot.bpt in the data folder (data_files.h)
    size_t rays = 20000;           // random rays; the other sets scale with it
    int width = 256, height = 256; // camera rays
    std::vector<std::string> sets = {"random", "camera", "grazing", "seams", "poles", "leaving"};
    std::vector<double> angles = {1e-2, 1e-3, 1e-4, 1e-6};
    std::vector<std::string> methods = {"exact", "newton", "embree", "adaptive", "cgal"};
    std::vector<double> tolerances = {1e-3, 1e-6, 1e-9, 1e-12};
    std::vector<int> presplits = {1, 2, 4, 12}; // exact method at tolerance 1e-9, patch_presplit N
    std::vector<int> grids = {8, 16, 32, 64, 128};
    std::vector<int> cgal_grids = {8, 32, 128};
    std::vector<double> adaptive = {1e-3, 1e-4, 1e-5}; // mesh tolerances / diagonal
    std::vector<double> cgal_adaptive = {1e-4};
    int threads = 0; // all-thread runs; 0 = all hardware threads
    double min_seconds = 0.1;
    uint64_t seed = 1;
    size_t max_listed = 5;      // disagreements listed per ray set
    std::string explain;        // method whose disagreements are listed; empty: exact-1e-9
    std::string out_dir;        // empty: the current directory
    std::string csv_path;       // empty: <out>/bench-results.csv
    std::string stability_path; // empty: <out>/stability.md if --out was given
    std::string summary_path;   // empty: <out>/summary.md if --out was given
    std::string chart_dir;      // empty: no chart

    bool has_method(const std::string &name) const;
    bool has_set(const std::string &name) const;
};

// Adds the subcommand `intersect` to `app`; parsing it fills `options`.
CLI::App *add_intersect_command(CLI::App &app, IntersectOptions &options);

// What CLI11 cannot check alone, after parsing; throws ppm_tools::UsageError.
void check_intersect_options(const IntersectOptions &options);

} // namespace bench
