// SPDX-License-Identifier: Apache-2.0
#include "targets_report.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bench {

namespace {

// The design targets of libppm's exact intersector against the uniform mesh: speed on
// random rays relative to each mesh method (exact / mesh), memory relative to each (mesh /
// exact).
struct Target {
    const char *set;         // ray set of a speed target; nullptr for memory
    const char *peer_family; // the mesh method it is measured against
    double at_least;
};
constexpr Target targets[] = {
    {"random", "embree-uniform", 0.5},
    {"random", "cgal-uniform", 5},
    {nullptr, "embree-uniform", 1000},
    {nullptr, "cgal-uniform", 1000},
};
// Reported next to the targets, without a verdict.
constexpr const char *informational_set = "camera";

// Median and range of the valid (finite, positive) values; count 0 if there are none.
struct Spread {
    double median = 0, min = 0, max = 0;
    size_t count = 0;
};

Spread spread(std::vector<double> values) {
    values.erase(std::remove_if(values.begin(), values.end(), [](double x) { return !(x > 0) || !std::isfinite(x); }),
                 values.end());
    Spread s;
    s.count = values.size();
    if (values.empty()) return s;
    std::sort(values.begin(), values.end());
    const size_t mid = values.size() / 2;
    s.median = values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
    s.min = values.front();
    s.max = values.back();
    return s;
}

// Three significant digits with trailing zeros kept (0.500, 2.10), so that figures side by
// side read alike; whole numbers from 100 up, without an exponent.
std::string number(double x) {
    char text[32];
    if (std::fabs(x) >= 100)
        std::snprintf(text, sizeof text, "%.0f", x);
    else
        std::snprintf(text, sizeof text, "%#.3g", x);
    return text;
}

double mib(size_t bytes) { return double(bytes) / 1048576.0; }

int find_set(const std::vector<RaySet> &sets, const char *name) {
    for (size_t s = 0; s < sets.size(); ++s)
        if (sets[s].name == name) return int(s);
    return -1;
}

int find_family(const std::vector<BuiltMethod> &methods, const char *family) {
    for (size_t m = 0; m < methods.size(); ++m)
        if (methods[m].method->info().family == family) return int(m);
    return -1;
}

const std::string &name_of(const std::vector<BuiltMethod> &methods, size_t m) { return methods[m].method->info().name; }

// Per-round ratio of `exact`'s rays/s to `peer`'s on `set`.
Spread speed_ratio(const RoundsResult &rounds, size_t exact, size_t peer, size_t set) {
    const std::vector<double> a = rounds.rates(exact, set), b = rounds.rates(peer, set);
    std::vector<double> ratios;
    for (size_t r = 0; r < a.size(); ++r)
        if (a[r] > 0 && b[r] > 0) ratios.push_back(a[r] / b[r]);
    return spread(ratios);
}

std::string speed_line(const char *set_name, const std::string &exact, const std::string &peer, const Spread &s) {
    if (s.count == 0) return std::string(set_name) + " rays: " + exact + " / " + peer + " = n/a (no round timed both)";
    return std::string(set_name) + " rays: " + exact + " / " + peer + " = " + number(s.median) + " (" + number(s.min) +
           "-" + number(s.max) + " over " + std::to_string(s.count) + " rounds)";
}

std::string verdict(double value, bool measured, double at_least) {
    char threshold[32];
    std::snprintf(threshold, sizeof threshold, "%g", at_least);
    return std::string("  target >= ") + threshold + "  " +
           (!measured           ? "NOT CHECKED"
            : value >= at_least ? "PASS"
                                : "FAIL");
}

// The verdict lines of one exact method; returns how many targets it meets and how many were
// checked.
std::pair<int, int> print_method_verdicts(std::FILE *out, const std::vector<RaySet> &sets,
                                          const std::vector<BuiltMethod> &methods, const RoundsResult &rounds,
                                          size_t exact) {
    int met = 0, checked = 0;
    const std::string &name = name_of(methods, exact);
    for (const Target &target : targets) {
        const int peer = find_family(methods, target.peer_family);
        if (peer < 0) continue;
        const std::string &peer_name = name_of(methods, size_t(peer));
        std::string line;
        bool measured = false;
        double value = 0;
        if (target.set) {
            const int set = find_set(sets, target.set);
            if (set < 0) {
                std::fprintf(out, "%s rays: not traced, so %s / %s is not checked\n", target.set, name.c_str(),
                             peer_name.c_str());
                continue;
            }
            const Spread s = speed_ratio(rounds, exact, size_t(peer), size_t(set));
            line = speed_line(target.set, name, peer_name, s);
            measured = s.count > 0;
            value = s.median;
        } else {
            const size_t exact_bytes = methods[exact].bytes(), peer_bytes = methods[size_t(peer)].bytes();
            measured = exact_bytes > 0;
            value = measured ? double(peer_bytes) / double(exact_bytes) : 0;
            line = "memory: " + peer_name + " / " + name + " = " + (measured ? number(value) : "n/a") + " (" +
                   number(mib(peer_bytes)) + " MiB / " + number(mib(exact_bytes)) + " MiB)";
        }
        std::fprintf(out, "%s%s\n", line.c_str(), verdict(value, measured, target.at_least).c_str());
        checked += measured;
        met += measured && value >= target.at_least;
    }
    return {met, checked};
}

} // namespace

void print_speed_tables(std::FILE *out, const std::vector<RaySet> &sets, const std::vector<BuiltMethod> &methods,
                        const RoundsResult &rounds) {
    const std::string &reference = name_of(methods, 0);
    for (size_t s = 0; s < sets.size(); ++s) {
        std::fprintf(out, "\n== %s: %zu rays (%s) ==\n", sets[s].name.c_str(), sets[s].size(),
                     sets[s].description.c_str());
        const std::string differs = "hit/miss differs from " + reference;
        std::fprintf(out, "%-20s %10s %10s %17s  %s\n", "method", "memory MiB", "Mrays/s", "min-max", differs.c_str());
        for (size_t m = 0; m < methods.size(); ++m) {
            const Spread rate = spread(rounds.rates(m, s));
            const size_t diff = rounds.hit_differences[m][s];
            std::string median = "-", range = "-";
            if (rate.count) {
                median = number(1e-6 * rate.median);
                range = number(1e-6 * rate.min) + "-" + number(1e-6 * rate.max);
            }
            std::fprintf(out, "%-20s %10s %10s %17s  %zu rays (%.2g%%)\n", name_of(methods, m).c_str(),
                         number(mib(methods[m].bytes())).c_str(), median.c_str(), range.c_str(), diff,
                         sets[s].size() ? 100.0 * double(diff) / double(sets[s].size()) : 0.0);
        }
    }
}

void print_verdicts(std::FILE *out, const std::vector<RaySet> &sets, const std::vector<BuiltMethod> &methods,
                    const RoundsResult &rounds) {
    std::fprintf(out, "\n== targets: speed is the median over rounds of exact rays/s / mesh rays/s within a round "
                      "(min-max in brackets); memory is mesh bytes / exact bytes ==\n");
    if (find_family(methods, "cgal-uniform") < 0)
        std::fprintf(out, "CGAL targets not checked: this ppm-bench was built without CGAL\n");
    const int camera = find_set(sets, informational_set);
    for (size_t m = 0; m < methods.size(); ++m) {
        if (methods[m].method->info().family != "exact-presplit") continue;
        std::fprintf(out, "\n");
        const std::pair<int, int> score = print_method_verdicts(out, sets, methods, rounds, m);
        if (camera >= 0)
            for (const char *family : {"embree-uniform", "cgal-uniform"}) {
                const int peer = find_family(methods, family);
                if (peer < 0) continue;
                const Spread s = speed_ratio(rounds, m, size_t(peer), size_t(camera));
                std::fprintf(
                    out, "%s  (no target)\n",
                    speed_line(informational_set, name_of(methods, m), name_of(methods, size_t(peer)), s).c_str());
            }
        std::fprintf(out, "%s meets %d of %d targets checked\n", name_of(methods, m).c_str(), score.first,
                     score.second);
    }
}

void write_rounds_csv(const std::string &path, const std::vector<RaySet> &sets, const std::vector<BuiltMethod> &methods,
                      const RoundsResult &rounds) {
    std::FILE *f = std::fopen(path.c_str(), "w");
    if (!f) throw std::runtime_error(path + ": cannot open for writing");
    std::fprintf(f, "round,position,method,family,set,rays,cpu_seconds,wall_seconds,rays_per_second,memory_bytes\n");
    for (const Sample &s : rounds.samples) {
        const BuiltMethod &method = methods[s.method];
        std::fprintf(f, "%d,%d,%s,%s,%s,%zu,%.9g,%.9g,%.9g,%zu\n", s.round + 1, s.position + 1,
                     method.method->info().name.c_str(), method.method->info().family.c_str(), sets[s.set].name.c_str(),
                     s.timing.rays, s.timing.cpu, s.timing.wall, s.rays_per_second(), method.bytes());
    }
    if (std::fclose(f) != 0) throw std::runtime_error(path + ": write failed");
}

} // namespace bench
