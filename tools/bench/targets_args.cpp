#include "targets_args.h"

#include "option_values.h"

#include <algorithm>
#include <cstring>

namespace bench {

namespace {

constexpr const char *command = "ppm-bench targets";

bool bad(const std::string &option, const std::string &value, const char *expected) {
    return report_bad_value(command, option, value, expected);
}

// Without duplicates, which would only time the same method twice under one name.
bool presplit_list(const std::string &option, const std::string &value, std::vector<int> &out) {
    constexpr const char *expected = "a list like 3,12 of patch_presplit values in [1, 32]";
    if (value == "none" || !parse_integer_list(value, 1, 32, out) || out.empty()) return bad(option, value, expected);
    std::vector<int> distinct;
    for (int n : out)
        if (std::find(distinct.begin(), distinct.end(), n) == distinct.end()) distinct.push_back(n);
    out = distinct;
    return true;
}

bool apply(const std::string &option, const std::string &value, TargetsOptions &o) {
    switch (apply_ray_set_option(command, option, value, o)) {
    case OptionMatch::taken: return true;
    case OptionMatch::invalid: return false;
    case OptionMatch::other: break;
    }
    long long n = 0;
    if (option == "--presplit") {
        return presplit_list(option, value, o.presplits);
    } else if (option == "--grid") {
        if (!parse_integer(value, 1, 4096, n)) return bad(option, value, "an integer in [1, 4096]");
        o.grid = int(n);
    } else if (option == "--rounds") {
        if (!parse_integer(value, 1, 1000, n)) return bad(option, value, "an integer in [1, 1000]");
        o.rounds = int(n);
    } else if (option == "--csv") {
        o.csv_path = value;
    } else {
        std::fprintf(stderr, "%s: unknown option '%s'\n", command, option.c_str());
        return false;
    }
    return true;
}

} // namespace

void print_targets_usage(std::FILE *out) {
    const TargetsOptions d;
    std::fprintf(out,
                 "usage: ppm-bench targets [options]\n"
                 "Checks the speed and memory targets of libppm's exact intersector against the same model\n"
                 "tessellated as a uniform mesh and traced by Embree and by CGAL's AABB tree: at least 0.5\n"
                 "times Embree's speed and 5 times CGAL's on random rays, at least 1000 times less memory\n"
                 "than either. Every method is built once on one thread; then, in each round, each method\n"
                 "(in an order rotated from round to round) traces each ray set on one thread, and a speed\n"
                 "ratio is taken within the round. Verdicts use the median of those per-round ratios, so a\n"
                 "load burst on a shared machine moves one round, not the verdict. The exit status does not\n"
                 "depend on the verdicts.\n"
                 "  --bpt FILE            patches to load (default %s)\n"
                 "  --presplit LIST       exact method at these scene patch_presplit values, methods\n"
                 "                        exact-presplit-N (default 3,12)\n"
                 "  --grid N              the meshes have N x N quads per patch (default %d)\n"
                 "  --rays N              random rays (default %zu; 0 skips the set and the speed targets)\n"
                 "  --width W --height H  camera rays (default %d x %d; 0 x 0 skips the set)\n"
                 "  --rounds K            timing rounds (default %d)\n"
                 "  --min-time S          each timing traces its set again until S seconds have passed\n"
                 "                        (default %g; rays/s come from process CPU time)\n"
                 "  --seed S              seed of the random rays (default %llu)\n"
                 "  --csv FILE            every timing, one row per round, method and ray set\n"
                 "  -h, --help            this text\n",
                 d.bpt_path.c_str(), d.grid, d.rays, d.width, d.height, d.rounds, d.min_seconds,
                 (unsigned long long)d.seed);
}

ParseResult parse_targets_args(int argc, char **argv, int first, TargetsOptions &options) {
    const ParseResult read =
        read_options(command, argc, argv, first, [&](const std::string &option, const std::string &value) {
            return apply(option, value, options);
        });
    if (read != ParseResult::run) return read;
    if ((options.width == 0) != (options.height == 0)) {
        std::fprintf(stderr, "%s: --width and --height must both be 0 or both positive\n", command);
        return ParseResult::error;
    }
    if (options.rays == 0 && options.width == 0) {
        std::fprintf(stderr, "%s: no rays to trace (--rays 0 and --width 0)\n", command);
        return ParseResult::error;
    }
    return ParseResult::run;
}

} // namespace bench
