#include "report.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bench {

namespace {

double rays_per_second(const Trace &trace, size_t rays) {
    return trace.cpu_seconds > 0 ? double(rays) / trace.cpu_seconds : 0.0;
}

double wall_rays_per_second(const Trace &trace, size_t rays) {
    return trace.wall_seconds > 0 ? double(rays) / trace.wall_seconds : 0.0;
}

// The ratios are quoted against the finest grid of each mesh family, N = 128 by default.
const MethodRun *finest(const std::vector<MethodRun> &runs, const std::string &family) {
    const MethodRun *best = nullptr;
    for (const MethodRun &run : runs)
        if (run.family == family && (!best || run.grid > best->grid)) best = &run;
    return best;
}

void print_ratios(std::FILE *out, const std::vector<RaySet> &sets, const std::vector<MethodRun> &runs,
                  const MethodRun &exact) {
    for (const char *family : {"embree", "cgal"}) {
        const MethodRun *mesh = finest(runs, family);
        if (!mesh) continue;
        for (size_t s = 0; s < sets.size(); ++s) {
            const size_t n = sets[s].rays.size();
            const double e = rays_per_second(exact.traces[s], n), m = rays_per_second(mesh->traces[s], n);
            std::fprintf(out, "ratio exact/%s %-6s rays/s: %.4f  (exact %.3f Mrays/s, %s %.3f Mrays/s)\n",
                         mesh->name.c_str(), sets[s].name.c_str(), m > 0 ? e / m : 0.0, 1e-6 * e,
                         mesh->name.c_str(), 1e-6 * m);
        }
    }
}

} // namespace

Comparison compare(const Trace &method, const Trace &exact, double diagonal) {
    Comparison c;
    std::vector<double> dts;
    for (size_t i = 0; i < method.t.size(); ++i) {
        const bool m = std::isfinite(method.t[i]), e = std::isfinite(exact.t[i]);
        c.hits += m;
        if (e && !m) ++c.misses;
        if (m && !e) ++c.false_hits;
        if (m && e) {
            const double dt = std::fabs(method.t[i] - exact.t[i]) / diagonal;
            dts.push_back(dt);
            c.max_dt = std::max(c.max_dt, dt);
            c.far += dt > 1e-3;
        }
    }
    c.both = dts.size();
    if (!dts.empty()) {
        std::nth_element(dts.begin(), dts.begin() + dts.size() / 2, dts.end());
        c.median_dt = dts[dts.size() / 2];
    }
    return c;
}

void print_table(std::FILE *out, const std::vector<RaySet> &sets, const std::vector<MethodRun> &runs,
                 const MethodRun *exact, double diagonal) {
    std::fprintf(out, "Intersection benchmark: one thread per method; rays/s from process CPU time "
                      "(wall in brackets);\n"
                      "build = CPU ms; arrays = vertex+index (or control point) bytes; struct = "
                      "acceleration structure bytes;\n"
                      "misses / false hits / |dt| relative to the exact intersector; |dt| in units "
                      "of the bbox diagonal %.6g.\n\n",
                 diagonal);
    std::fprintf(out, "%-7s %-12s %9s %9s %9s %9s %9s %8s %7s %7s %10s %10s %7s\n", "rays", "method",
                 "Mrays/s", "(wall)", "build ms", "arrays MB", "struct MB", "hits", "misses", "false",
                 "max|dt|", "med|dt|", ">1e-3");
    for (size_t s = 0; s < sets.size(); ++s) {
        const size_t n = sets[s].rays.size();
        for (const MethodRun &run : runs) {
            const Trace &trace = run.traces[s];
            std::fprintf(out, "%-7s %-12s %9.4f %9.4f %9.2f %9.3f %9.3f", sets[s].name.c_str(),
                         run.name.c_str(), 1e-6 * rays_per_second(trace, n),
                         1e-6 * wall_rays_per_second(trace, n), 1e3 * run.build_seconds,
                         run.array_bytes / 1048576.0, run.structure_bytes / 1048576.0);
            if (exact && &run != exact) {
                const Comparison c = compare(trace, exact->traces[s], diagonal);
                std::fprintf(out, " %8zu %7zu %7zu %10.3e %10.3e %7zu\n", c.hits, c.misses,
                             c.false_hits, c.max_dt, c.median_dt, c.far);
            } else {
                size_t hits = 0;
                for (double t : trace.t) hits += std::isfinite(t);
                std::fprintf(out, " %8zu %7s %7s %10s %10s %7s\n", hits, "-", "-", "-", "-", "-");
            }
        }
        std::fprintf(out, "\n");
    }
    if (exact) print_ratios(out, sets, runs, *exact);
}

void write_csv(const std::string &path, const std::vector<RaySet> &sets,
               const std::vector<MethodRun> &runs, const MethodRun *exact, double diagonal) {
    std::FILE *f = std::fopen(path.c_str(), "w");
    if (!f) throw std::runtime_error(path + ": cannot open for writing");
    std::fprintf(f, "rays,method,family,grid,ray_count,cpu_s,wall_s,rays_per_s_cpu,rays_per_s_wall,"
                    "build_cpu_s,array_bytes,structure_bytes,hits,misses,false_hits,both_hit,"
                    "max_dt_rel,median_dt_rel,dt_over_1e-3\n");
    for (size_t s = 0; s < sets.size(); ++s) {
        const size_t n = sets[s].rays.size();
        for (const MethodRun &run : runs) {
            const Trace &trace = run.traces[s];
            Comparison c;
            const bool compared = exact && &run != exact;
            if (compared) c = compare(trace, exact->traces[s], diagonal);
            else for (double t : trace.t) c.hits += std::isfinite(t);
            std::fprintf(f, "%s,%s,%s,%d,%zu,%.6f,%.6f,%.1f,%.1f,%.6f,%zu,%zu,%zu,", sets[s].name.c_str(),
                         run.name.c_str(), run.family.c_str(), run.grid, n, trace.cpu_seconds,
                         trace.wall_seconds, rays_per_second(trace, n), wall_rays_per_second(trace, n),
                         run.build_seconds, run.array_bytes, run.structure_bytes, c.hits);
            if (compared)
                std::fprintf(f, "%zu,%zu,%zu,%.6e,%.6e,%zu\n", c.misses, c.false_hits, c.both,
                             c.max_dt, c.median_dt, c.far);
            else
                std::fprintf(f, ",,,,,\n");
        }
    }
    if (std::fclose(f) != 0) throw std::runtime_error(path + ": write error");
}

} // namespace bench
