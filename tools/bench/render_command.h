// SPDX-License-Identifier: Apache-2.0
// `ppm-bench render`: photon paths per second, eye-pass time and peak memory of the renderer
// on the benchmark scenes (bench_scenes.h), for each hit-point search structure.
#pragma once

#include "common/command_line.h"

#include <string>
#include <vector>

namespace bench {

struct RenderOptions {
    std::vector<std::string> scenes{"smallppm", "teapot-glass"};
    std::vector<std::string> searches{"grid", "kdtree"};
    std::vector<long> photon_counts{100000, 1000000};
    std::string mode = "sppm"; // the renderer's mode: eye and photon passes are timed apart in the photon modes
    int width = 1024, height = 768;
    int passes = 4;
    int threads = 0;
    std::string teapot; // empty: teapot.bpt in the data folder (data_files.h)
    std::string image_dir;
};

// Adds the subcommand `render` to `app`; parsing it fills `options`.
CLI::App *add_render_command(CLI::App &app, RenderOptions &options);

// Returns the process exit code: 0 success, 2 runtime error.
int run_render_command(const RenderOptions &options);

} // namespace bench
