// The benchmark's output: comparison of each method with the exact intersector, the table on
// stdout, the speed ratios, and the optional CSV file.
#pragma once

#include "method.h"

#include <cstdio>
#include <string>
#include <vector>

namespace bench {

// A method's trace against the exact one on the same rays. Distances are relative to the
// bounding-box diagonal.
struct Comparison {
    size_t hits = 0;       // rays the method hits
    size_t misses = 0;     // exact hits, method misses
    size_t false_hits = 0; // exact misses, method hits
    size_t both = 0;       // both hit: the |dt| statistics are over these
    size_t far = 0;        // both hit with |dt| > 1e-3 (a different surface or a wrong root)
    double max_dt = 0, median_dt = 0;
};

Comparison compare(const Trace &method, const Trace &exact, double diagonal);

// Rows for every (ray set, method), then "ratio exact/<mesh method>" lines. `exact` may be
// null (no comparison columns then).
void print_table(std::FILE *out, const std::vector<RaySet> &sets, const std::vector<MethodRun> &runs,
                 const MethodRun *exact, double diagonal);

// Same content as the table, one row per (ray set, method). Throws on I/O errors.
void write_csv(const std::string &path, const std::vector<RaySet> &sets,
               const std::vector<MethodRun> &runs, const MethodRun *exact, double diagonal);

} // namespace bench
