#include "intersect_args.h"

#include "option_values.h"

#include <algorithm>
#include <cstring>

namespace bench {

namespace {

const char *const known_sets[] = {"random", "camera", "grazing", "seams", "poles", "leaving"};
const char *const known_methods[] = {"exact", "newton", "embree", "adaptive", "cgal"};

constexpr const char *command = "ppm-bench intersect";

bool bad(const std::string &option, const std::string &value, const char *expected) {
    return report_bad_value(command, option, value, expected);
}

// A comma-separated list of integers in [low, high]; "none" (or an empty value) for none.
bool integer_list(const std::string &option, const std::string &value, long long low, long long high,
                  std::vector<int> &out, const char *expected) {
    return parse_integer_list(value, low, high, out) || bad(option, value, expected);
}

bool double_list(const std::string &option, const std::string &value, double low, double high, std::vector<double> &out,
                 const char *expected) {
    out.clear();
    if (value == "none") return true;
    for (const std::string &item : split_list(value)) {
        double x = 0;
        if (!parse_double(item, low, high, x)) return bad(option, value, expected);
        out.push_back(x);
    }
    return true;
}

template <size_t N> bool name_list(const std::string &option, const std::string &value, const char *const (&known)[N],
                                   std::vector<std::string> &out, const char *expected) {
    out = split_list(value);
    for (const std::string &name : out)
        if (std::find(std::begin(known), std::end(known), name) == std::end(known)) return bad(option, value, expected);
    if (out.empty()) return bad(option, value, expected);
    return true;
}

constexpr const char *grid_list = "a list like 8,32 of grid sizes in [1, 4096], or none";

bool apply(const std::string &option, const std::string &value, IntersectOptions &o) {
    switch (apply_ray_set_option(command, option, value, o)) {
    case OptionMatch::taken: return true;
    case OptionMatch::invalid: return false;
    case OptionMatch::other: break;
    }
    long long n = 0;
    if (option == "--sets") {
        return name_list(option, value, known_sets, o.sets, "a list of random, camera, grazing, seams, poles, leaving");
    } else if (option == "--angles") {
        return double_list(option, value, 1e-12, 1.5, o.angles, "a list like 1e-3,1e-6 of angles in (0, 1.5] rad");
    } else if (option == "--methods") {
        return name_list(option, value, known_methods, o.methods, "a list of exact, newton, embree, adaptive, cgal");
    } else if (option == "--tolerances") {
        return double_list(option, value, 1e-14, 1e-2, o.tolerances,
                           "a list like 1e-6,1e-9 of scene tolerances in [1e-14, 1e-2]");
    } else if (option == "--presplits") {
        return integer_list(option, value, 1, 32, o.presplits,
                            "a list like 1,4 of patch_presplit values in [1, 32], or none");
    } else if (option == "--grids") {
        return integer_list(option, value, 1, 4096, o.grids, grid_list);
    } else if (option == "--cgal-grids") {
        return integer_list(option, value, 1, 4096, o.cgal_grids, grid_list);
    } else if (option == "--adaptive") {
        return double_list(option, value, 1e-9, 1e-1, o.adaptive,
                           "a list like 1e-3,1e-4 of mesh tolerances / diagonal in [1e-9, 0.1], or none");
    } else if (option == "--cgal-adaptive") {
        return double_list(option, value, 1e-9, 1e-1, o.cgal_adaptive,
                           "a list like 1e-4 of mesh tolerances / diagonal in [1e-9, 0.1], or none");
    } else if (option == "--threads") {
        if (!parse_integer(value, 0, 1024, n)) return bad(option, value, "an integer in [0, 1024]");
        o.threads = int(n);
    } else if (option == "--list") {
        if (!parse_integer(value, 0, 1000000, n)) return bad(option, value, "a non-negative integer");
        o.max_listed = size_t(n);
    } else if (option == "--explain") {
        o.explain = value;
    } else if (option == "--out") {
        o.out_dir = value;
    } else if (option == "--csv") {
        o.csv_path = value;
    } else if (option == "--stability-md") {
        o.stability_path = value;
    } else if (option == "--summary-md") {
        o.summary_path = value;
    } else if (option == "--chart") {
        o.chart_dir = value;
    } else {
        std::fprintf(stderr, "%s: unknown option '%s'\n", command, option.c_str());
        return false;
    }
    return true;
}

} // namespace

bool IntersectOptions::has_method(const std::string &name) const {
    return std::find(methods.begin(), methods.end(), name) != methods.end();
}

bool IntersectOptions::has_set(const std::string &name) const {
    return std::find(sets.begin(), sets.end(), name) != sets.end();
}

void print_intersect_usage(std::FILE *out) {
    const IntersectOptions d;
    std::fprintf(out,
                 "usage: ppm-bench intersect [options]\n"
                 "Speed against accuracy of ray / Bezier patch intersection: libppm's exact intersector at\n"
                 "several tolerances, naive Newton methods, and tessellations traced by Embree and CGAL, all\n"
                 "judged ray by ray against an independent long-double reference intersector, on one thread\n"
                 "and on all threads.\n"
                 "  --bpt FILE            patches to load (default %s)\n"
                 "  --rays N              random rays (default %zu); grazing (per angle), seam and leaving\n"
                 "                        sets get N/4 rays each, poles N/10 (at least 1 each; 0 skips them)\n"
                 "  --width W --height H  camera rays (default %d x %d; 0 x 0 skips the set)\n"
                 "  --sets LIST           any of random,camera,grazing,seams,poles,leaving (default all)\n"
                 "  --angles LIST         grazing angles in radians (default 1e-2,1e-3,1e-4,1e-6)\n"
                 "  --methods LIST        any of exact,newton,embree,adaptive,cgal (default all; cgal if built)\n"
                 "  --tolerances LIST     exact method scene tolerances (default 1e-3,1e-6,1e-9,1e-12)\n"
                 "  --presplits LIST      exact method at tolerance 1e-9 with these scene patch_presplit values,\n"
                 "                        methods exact-presplit-N (default 1,2,4,12; 'none' for none)\n"
                 "  --grids LIST          uniform grids traced by Embree (default 8,16,32,64,128)\n"
                 "  --cgal-grids LIST     uniform grids traced by CGAL (default 8,32,128)\n"
                 "  --adaptive LIST       adaptive meshes traced by Embree, tolerance / diagonal\n"
                 "                        (default 1e-3,1e-4,1e-5); 'none' for no mesh\n"
                 "  --cgal-adaptive LIST  adaptive meshes traced by CGAL (default 1e-4)\n"
                 "  --threads N           threads of the all-thread runs (default 0: all hardware threads;\n"
                 "                        1: single-thread runs only)\n"
                 "  --min-time S          trace each set again until S seconds have passed (default %g)\n"
                 "  --seed S              seed of all random ray sets (default %llu)\n"
                 "  --list K              disagreements with the reference listed per set (default %zu)\n"
                 "  --explain METHOD      whose disagreements to list, e.g. newton-r16 (default: exact-1e-9, or\n"
                 "                        the first exact method)\n"
                 "  --out DIR             directory of the outputs (created; default: current directory)\n"
                 "  --csv FILE            results, one row per ray set and method (default DIR/bench-results.csv)\n"
                 "  --stability-md FILE   markdown tables of miss and false-hit rates (default DIR/stability.md\n"
                 "                        with --out)\n"
                 "  --summary-md FILE     markdown summary table (default DIR/summary.md with --out)\n"
                 "  --chart DIR           write DIR/intersect.png and .svg with tools/bench/plot_bench.py\n"
                 "                        (needs python3 with matplotlib)\n"
                 "  -h, --help            this text\n",
                 d.bpt_path.c_str(), d.rays, d.width, d.height, d.min_seconds, (unsigned long long)d.seed,
                 d.max_listed);
}

ParseResult parse_intersect_args(int argc, char **argv, int first, IntersectOptions &options) {
    const ParseResult read =
        read_options(command, argc, argv, first, [&](const std::string &option, const std::string &value) {
            return apply(option, value, options);
        });
    if (read != ParseResult::run) return read;
    if ((options.width == 0) != (options.height == 0)) {
        std::fprintf(stderr, "%s: --width and --height must both be 0 or both positive\n", command);
        return ParseResult::error;
    }
    return ParseResult::run;
}

} // namespace bench
