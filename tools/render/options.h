// SPDX-License-Identifier: Apache-2.0
// ppm-render's command line, parsed with CLI11 (tools/common/command_line.h).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace ppm_render {

struct Options {
    std::string scene;
    std::vector<std::string> outputs; // -o, repeatable; default <scene name>.png (none with --partial)
    std::vector<std::pair<std::string, std::string>> defines; // -D name=value: XML parameters
    bool lenient = false;                                     // substitute what cannot be rendered
    std::int64_t passes = -1;                                 // -1: from the scene file, else 16 (unless --time)
    std::int64_t photons = -1;                                // photons_per_pass; -1: the scene's
    double time = -1;                                         // seconds; -1: the scene's, 0: no budget
    std::int64_t seed = -1;                                   // -1: the scene's
    std::int64_t threads = 0;                                 // 0: all hardware threads
    std::uint32_t width = 0, height = 0;                      // --size; 0: the scene's film
    std::uint32_t crop[4] = {0, 0, 0, 0};                     // --crop x0,y0,x1,y1; all 0: none
    bool cropped() const { return crop[2] > 0; }
    std::vector<std::pair<std::string, std::string>> settings; // --set key=value, in order
    double exposure = 0;                                       // stops, for PNG/JPEG
    std::vector<std::string> layers;                           // extra EXR layers: radius, photons
    double write_interval = 1;                                 // seconds between image rewrites; 0: every pass
    std::string checkpoint;                                    // "" : <first output without extension>.ppmckpt
    bool checkpoint_given = false;
    double checkpoint_interval = 300; // seconds between periodic checkpoints
    std::string resume;
    std::int64_t pass_first = -1, pass_end = -1; // --pass-range A:B, passes [A, B); -1: not given
    std::string partial;                         // --partial PATH: save the passes' partial render
    bool partial_render() const { return !partial.empty(); }
    bool quiet = false;
};

// Parses the command line into *options. Returns -1 when ppm-render should render, else the
// exit status to return at once: 0 after --help or --version, 1 after a usage error (printed).
int parse_options(int argc, char **argv, Options *options);

} // namespace ppm_render
