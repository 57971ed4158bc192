// ppm-render's command line.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ppm_render {

// A command line that cannot be run: exit status 1 with the message and a hint to -h.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Options {
    std::string scene;
    std::vector<std::string> outputs; // -o, repeatable; default <scene name>.png (none with --partial)
    std::int64_t passes = -1;         // -1: from the scene file, else 16 (unless --time)
    std::int64_t photons = -1;        // photons_per_pass; -1: the scene's
    double time = -1;                 // seconds; -1: the scene's, 0: no budget
    std::int64_t seed = -1;           // -1: the scene's
    std::int64_t threads = 0;         // 0: all hardware threads
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
    bool help = false, version = false;
};

// Throws UsageError naming the bad option.
Options parse_options(int argc, char **argv);

extern const char *const usage_text;

} // namespace ppm_render
