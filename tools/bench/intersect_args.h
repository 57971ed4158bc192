// Command line of `ppm-bench intersect`.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace bench {

struct IntersectOptions {
    std::string bpt_path = PPM_SOURCE_DIR "/tests/data/teapot.bpt"; // the repository copy
    size_t random_rays = 1000000;
    int width = 512, height = 512;
    std::vector<int> grids = {32, 128};
    std::string csv_path;                                   // empty: no CSV
    std::vector<std::string> methods = {"exact", "embree", "cgal"};
    uint64_t seed = 1;
    size_t max_listed = 5;                                  // suspect rays listed per class

    bool has_method(const std::string &name) const;
};

enum class ParseResult { run, help, error };

// Parses argv[first..argc). On error prints the reason to stderr.
ParseResult parse_intersect_args(int argc, char **argv, int first, IntersectOptions &options);

void print_intersect_usage(std::FILE *out);

} // namespace bench
