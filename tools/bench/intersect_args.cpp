#include "intersect_args.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <sstream>

namespace bench {

namespace {

bool parse_integer(const std::string &text, long long low, long long high, long long &out) {
    if (text.empty()) return false;
    char *end = nullptr;
    errno = 0;
    const long long value = std::strtoll(text.c_str(), &end, 10);
    if (errno != 0 || *end != '\0' || value < low || value > high) return false;
    out = value;
    return true;
}

std::vector<std::string> split(const std::string &text) {
    std::vector<std::string> items;
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) items.push_back(item);
    return items;
}

bool bad(const std::string &option, const std::string &value, const char *expected) {
    std::fprintf(stderr, "ppm-bench intersect: %s '%s': expected %s\n", option.c_str(), value.c_str(),
                 expected);
    return false;
}

bool apply(const std::string &option, const std::string &value, IntersectOptions &o) {
    long long n = 0;
    if (option == "--bpt") {
        o.bpt_path = value;
    } else if (option == "--rays") {
        if (!parse_integer(value, 0, 100000000, n)) return bad(option, value, "an integer in [0, 1e8]");
        o.random_rays = size_t(n);
    } else if (option == "--width" || option == "--height") {
        if (!parse_integer(value, 0, 16384, n)) return bad(option, value, "an integer in [0, 16384]");
        (option == "--width" ? o.width : o.height) = int(n);
    } else if (option == "--grids") {
        o.grids.clear();
        for (const std::string &item : split(value)) {
            if (!parse_integer(item, 1, 4096, n)) return bad(option, value, "a list like 32,128 of integers in [1, 4096]");
            o.grids.push_back(int(n));
        }
        if (o.grids.empty()) return bad(option, value, "at least one grid size");
    } else if (option == "--csv") {
        o.csv_path = value;
    } else if (option == "--methods") {
        o.methods = split(value);
        for (const std::string &m : o.methods)
            if (m != "exact" && m != "embree" && m != "cgal")
                return bad(option, value, "a list of exact, embree, cgal");
        if (o.methods.empty()) return bad(option, value, "at least one method");
    } else if (option == "--seed") {
        if (!parse_integer(value, 0, INT64_MAX, n)) return bad(option, value, "a non-negative integer");
        o.seed = uint64_t(n);
    } else if (option == "--list") {
        if (!parse_integer(value, 0, 1000000, n)) return bad(option, value, "a non-negative integer");
        o.max_listed = size_t(n);
    } else {
        std::fprintf(stderr, "ppm-bench intersect: unknown option '%s'\n", option.c_str());
        return false;
    }
    return true;
}

} // namespace

bool IntersectOptions::has_method(const std::string &name) const {
    return std::find(methods.begin(), methods.end(), name) != methods.end();
}

void print_intersect_usage(std::FILE *out) {
    std::fprintf(out,
        "usage: ppm-bench intersect [options]\n"
        "Times libppm's exact patch intersector against Embree and CGAL on uniform\n"
        "tessellations of the same patches (one thread each) and compares their hits.\n"
        "  --bpt FILE          patches to load (default %s)\n"
        "  --rays N            incoherent random rays (default 1000000; 0 skips the set)\n"
        "  --width W --height H  pinhole camera rays (default 512 x 512; 0 skips the set)\n"
        "  --grids LIST        segments per patch edge of the meshes (default 32,128)\n"
        "  --methods LIST      any of exact,embree,cgal (default all)\n"
        "  --csv FILE          also write the results as CSV\n"
        "  --seed S            seed of the random rays (default 1)\n"
        "  --list K            suspicious rays listed per class (default 5)\n"
        "  -h, --help          this text\n",
        IntersectOptions().bpt_path.c_str());
}

ParseResult parse_intersect_args(int argc, char **argv, int first, IntersectOptions &options) {
    for (int i = first; i < argc; ++i) {
        std::string option = argv[i], value;
        if (option == "-h" || option == "--help") return ParseResult::help;
        const size_t equals = option.find('=');
        if (equals != std::string::npos) {
            value = option.substr(equals + 1);
            option.resize(equals);
        } else if (i + 1 < argc) {
            value = argv[++i];
        } else {
            std::fprintf(stderr, "ppm-bench intersect: %s needs a value\n", option.c_str());
            return ParseResult::error;
        }
        if (!apply(option, value, options)) return ParseResult::error;
    }
    if ((options.width == 0) != (options.height == 0)) {
        std::fprintf(stderr, "ppm-bench intersect: --width and --height must both be 0 or both positive\n");
        return ParseResult::error;
    }
    if (options.random_rays == 0 && options.width == 0) {
        std::fprintf(stderr, "ppm-bench intersect: no rays to trace (--rays 0 and a 0 x 0 image)\n");
        return ParseResult::error;
    }
    return ParseResult::run;
}

} // namespace bench
