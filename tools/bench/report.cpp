// SPDX-License-Identifier: Apache-2.0
#include "report.h"

#include <cmath>
#include <cstdarg>
#include <stdexcept>

namespace bench {

namespace {

std::string printf_string(const char *format, ...) __attribute__((format(printf, 1, 2)));
std::string printf_string(const char *format, ...) {
    char text[512];
    va_list args;
    va_start(args, format);
    std::vsnprintf(text, sizeof text, format, args);
    va_end(args);
    return text;
}

// A rate as a percentage with two significant digits; "0" when nothing happened.
std::string percent(size_t count, double rate) {
    if (count == 0) return "0";
    return printf_string("%.2g%%", 100.0 * rate);
}

// A relative error for tables: "0" or two significant digits; "-" when nothing was measured.
std::string small(double x, bool measured = true) { return !measured ? "-" : x == 0 ? "0" : printf_string("%.1e", x); }

// An angle in degrees, two significant digits.
std::string angle(double degrees, bool measured = true) { return !measured ? "-" : printf_string("%.2g", degrees); }

// Milliseconds from seconds: three significant digits, no exponent.
std::string milliseconds(double seconds) {
    const double ms = 1e3 * seconds;
    return ms >= 100 ? printf_string("%.0f", ms) : printf_string("%.3g", ms);
}

std::string mrays(double rays_per_second) {
    return rays_per_second > 0 ? printf_string("%.3g", 1e-6 * rays_per_second) : "-";
}

int find_set(const std::vector<RaySet> &sets, const char *name) {
    for (size_t s = 0; s < sets.size(); ++s)
        if (sets[s].name == name) return int(s);
    return -1;
}

std::string markdown_escape(const std::string &text) {
    std::string out;
    for (char c : text) {
        if (c == '|') out += '\\';
        out += c;
    }
    return out;
}

} // namespace

void print_set_tables(std::FILE *out, const std::vector<RaySet> &sets, const std::vector<MethodResult> &runs) {
    const int threads = runs.empty() ? 0 : runs.front().threads_all;
    for (size_t s = 0; s < sets.size(); ++s) {
        const Truth &truth = sets[s].base.truth;
        size_t hits = 0, ambiguous = 0, undecided = 0;
        for (TruthKind k : truth.kind) {
            hits += k == TruthKind::hit;
            ambiguous += k == TruthKind::ambiguous;
            undecided += k == TruthKind::undecided;
        }
        std::fprintf(out, "\n== %s: %zu rays (%s); reference: %zu hits, %zu ambiguous, %zu undecided ==\n",
                     sets[s].name.c_str(), sets[s].size(), sets[s].description.c_str(), hits, ambiguous, undecided);
        char all[24];
        std::snprintf(all, sizeof all, "Mr/s %dT", threads);
        std::fprintf(out, "%-22s %9s %9s %8s %8s %9s %9s %9s %8s %8s %8s %s\n", "method", "Mr/s 1T",
                     threads ? all : "-", "miss", "false", "med|dt|", "p999|dt|", "max|dt|", "ng med", "ng max",
                     "ns med", "");
        for (const MethodResult &run : runs) {
            const SetResult &r = run.sets[s];
            const Stats &st = r.stats;
            std::string note;
            if (r.thread_mismatches)
                note +=
                    printf_string("  %zu rays differ between 1 and %d threads", r.thread_mismatches, run.threads_all);
            if (st.over_tolerance) note += printf_string("  %zu hits beyond the tolerance", st.over_tolerance);
            const bool any = st.matched > 0;
            std::fprintf(out, "%-22s %9s %9s %8s %8s %9s %9s %9s %8s %8s %8s%s\n", run.info.name.c_str(),
                         mrays(r.rays_per_second_1t).c_str(), mrays(r.rays_per_second_all).c_str(),
                         percent(st.misses, st.miss_rate()).c_str(),
                         percent(st.false_hits, st.false_hit_rate()).c_str(), small(st.dt_median, any).c_str(),
                         small(st.dt_p999, any).c_str(), small(st.dt_max, any).c_str(),
                         angle(st.ng_median, any).c_str(), angle(st.ng_max, any).c_str(),
                         angle(st.ns_median, any).c_str(), note.c_str());
        }
    }
}

std::string summary_markdown(const std::vector<RaySet> &sets, const std::vector<MethodResult> &runs) {
    const int random = find_set(sets, "random"), camera = find_set(sets, "camera");
    if (random < 0 && camera < 0) return "";
    const int threads = runs.empty() ? 0 : runs.front().threads_all;
    const std::string nt = threads ? std::to_string(threads) + "T" : "-";
    auto pair = [](const std::string &a, const std::string &b) { return a + " / " + b; };
    auto per_set = [&](auto field) {
        return pair(random >= 0 ? field(random) : "-", camera >= 0 ? field(camera) : "-");
    };
    std::string md = "| method | primitives | build ms 1T / " + nt + " | memory MB | Mrays/s random 1T / " + nt +
                     " | Mrays/s camera 1T / " + nt +
                     " | miss random / camera | false hits random / camera | median \\|dt\\| random / camera"
                     " | p99.9 \\|dt\\| random / camera | max \\|dt\\| random / camera | normal error deg, median / "
                     "max (random) |\n";
    md += "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const MethodResult &run : runs) {
        const double mb = double(run.memory.array_bytes + run.memory.structure_bytes) / 1048576.0;
        std::string build =
            milliseconds(run.build_seconds_1t) + " / " + (run.threads_all ? milliseconds(run.build_seconds_all) : "-");
        if (run.info.tessellate_seconds > 0) build += " (+" + milliseconds(run.info.tessellate_seconds) + " tess.)";
        auto speed = [&](int s) {
            if (s < 0) return std::string("-");
            return pair(mrays(run.sets[s].rays_per_second_1t), mrays(run.sets[s].rays_per_second_all));
        };
        auto stat = [&](auto f) { return per_set([&](int s) { return f(run.sets[s].stats); }); };
        const int first = random >= 0 ? random : camera;
        const Stats &a = run.sets[first].stats;
        md += "| " + run.info.name + " | " + std::to_string(run.info.primitives) + " | " + build + " | " +
              printf_string("%.3g", mb) + " | " + speed(random) + " | " + speed(camera) + " | " +
              stat([](const Stats &st) { return percent(st.misses, st.miss_rate()); }) + " | " +
              stat([](const Stats &st) { return percent(st.false_hits, st.false_hit_rate()); }) + " | " +
              stat([](const Stats &st) { return small(st.dt_median, st.matched > 0); }) + " | " +
              stat([](const Stats &st) { return small(st.dt_p999, st.matched > 0); }) + " | " +
              stat([](const Stats &st) { return small(st.dt_max, st.matched > 0); }) + " | " +
              angle(a.ng_median, a.matched > 0) + " / " + angle(a.ng_max, a.matched > 0) + " |\n";
    }
    return md;
}

std::string stability_markdown(const std::vector<RaySet> &sets, const std::vector<MethodResult> &runs) {
    std::string md;
    for (int table = 0; table < 2; ++table) {
        md += table == 0 ? "Miss rate (reference hits the method misses / reference hits):\n\n"
                         : "\nFalse-hit rate (hits on no surface the ray meets first: no root there, the nearest "
                           "surface skipped, or the hit point more than 1e-3 diagonal off the surface / rays):\n\n";
        md += "| method |";
        std::string rule = "|---|";
        for (const RaySet &set : sets) {
            size_t hits = 0;
            for (TruthKind k : set.base.truth.kind) hits += k == TruthKind::hit;
            md += " " + markdown_escape(set.name) + " (" + std::to_string(table == 0 ? hits : set.size()) + ") |";
            rule += "---:|";
        }
        md += "\n" + rule + "\n";
        for (const MethodResult &run : runs) {
            md += "| " + run.info.name + " |";
            for (size_t s = 0; s < sets.size(); ++s) {
                const Stats &st = run.sets[s].stats;
                md += " " +
                      (table == 0 ? percent(st.misses, st.miss_rate()) : percent(st.false_hits, st.false_hit_rate())) +
                      " |";
            }
            md += "\n";
        }
    }
    return md;
}

void write_csv(const std::string &path, const std::vector<RaySet> &sets, const std::vector<MethodResult> &runs) {
    std::FILE *f = std::fopen(path.c_str(), "w");
    if (!f) throw std::runtime_error(path + ": cannot open for writing");
    std::fprintf(f, "rays,method,family,parameter,value,primitives,ray_count,undecided,reference_hits,ambiguous,"
                    "threads_all,rays_per_s_1t,rays_per_s_1t_wall,rays_per_s_all,thread_mismatches,"
                    "tessellate_s,mesh_deviation_rel,build_s_1t,build_s_all,array_bytes,structure_bytes,"
                    "hits,misses,miss_rate,false_hits,false_hit_rate,matched,over_tolerance,"
                    "dt_median_rel,dt_p999_rel,dt_max_rel,ng_err_median_deg,ng_err_p999_deg,ng_err_max_deg,"
                    "ns_err_median_deg,ns_err_max_deg\n");
    for (size_t s = 0; s < sets.size(); ++s) {
        for (const MethodResult &run : runs) {
            const SetResult &r = run.sets[s];
            const Stats &st = r.stats;
            std::fprintf(f,
                         "%s,%s,%s,%s,%.17g,%zu,%zu,%zu,%zu,%zu,%d,%.6g,%.6g,%.6g,%zu,%.6g,%.6g,%.6g,%.6g,%zu,%zu,"
                         "%zu,%zu,%.6g,%zu,%.6g,%zu,%zu,",
                         sets[s].name.c_str(), run.info.name.c_str(), run.info.family.c_str(),
                         run.info.parameter.c_str(), run.info.value, run.info.primitives, st.rays, st.undecided,
                         st.reference_hits, st.ambiguous, run.threads_all, r.rays_per_second_1t,
                         r.rays_per_second_1t_wall, r.rays_per_second_all, r.thread_mismatches,
                         run.info.tessellate_seconds, run.info.deviation, run.build_seconds_1t, run.build_seconds_all,
                         run.memory.array_bytes, run.memory.structure_bytes, st.hits, st.misses, st.miss_rate(),
                         st.false_hits, st.false_hit_rate(), st.matched, st.over_tolerance);
            if (st.matched > 0)
                std::fprintf(f, "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", st.dt_median, st.dt_p999, st.dt_max,
                             st.ng_median, st.ng_p999, st.ng_max, st.ns_median, st.ns_max);
            else
                std::fprintf(f, ",,,,,,,\n");
        }
    }
    if (std::fclose(f) != 0) throw std::runtime_error(path + ": write error");
}

void write_text(const std::string &path, const std::string &text) {
    std::FILE *f = std::fopen(path.c_str(), "w");
    if (!f) throw std::runtime_error(path + ": cannot open for writing");
    std::fputs(text.c_str(), f);
    if (std::fclose(f) != 0) throw std::runtime_error(path + ": write error");
}

} // namespace bench
