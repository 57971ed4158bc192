#include "suspects.h"

#include <algorithm>
#include <cmath>

namespace bench {

namespace {

constexpr double agree_dt = 1e-3;  // relative to the diagonal; N = 32 errors are ~1e-4
constexpr float grazing_cos = 0.05f;
constexpr float edge_band = 0.02f;
constexpr size_t explained_listed = 2; // a sample, to check the explanation by eye

enum Kind { exact_miss, exact_false_hit, exact_wrong_t, kind_count };
const char *const kind_names[kind_count] = {"exact miss", "exact false hit", "exact wrong t"};

bool near_edge(const Trace &trace, size_t i) {
    const float u = trace.u[i], v = trace.v[i];
    return std::min({u, 1.0f - u, v, 1.0f - v}) < edge_band;
}

struct Case {
    size_t ray;
    Kind kind;
    const char *explanation; // nullptr when unexplained
};

// The class of ray i, or kind_count when the exact result agrees with the meshes (or the
// meshes disagree among themselves, which says nothing about the exact intersector).
Kind classify(size_t i, const Trace &exact, const std::vector<const Trace *> &meshes, double diagonal) {
    size_t mesh_hits = 0;
    double t_min = INFINITY, t_max = -INFINITY;
    for (const Trace *m : meshes) {
        if (!std::isfinite(m->t[i])) continue;
        ++mesh_hits;
        t_min = std::min(t_min, m->t[i]);
        t_max = std::max(t_max, m->t[i]);
    }
    const bool e = std::isfinite(exact.t[i]);
    if (mesh_hits == 0) return e ? exact_false_hit : kind_count;
    if (mesh_hits != meshes.size() || t_max - t_min > agree_dt * diagonal) return kind_count;
    if (!e) return exact_miss;
    // Tessellation moves the surface along its normal, so a ray at angle theta to the normal
    // sees it moved by offset / cos(theta): compare the normal offset, not dt.
    const double dt = std::max(std::fabs(exact.t[i] - t_min), std::fabs(exact.t[i] - t_max));
    return dt * exact.cos_normal[i] > agree_dt * diagonal ? exact_wrong_t : kind_count;
}

void print_ray(std::FILE *out, const ppm_ray &ray, size_t index, const Trace &exact,
               const std::vector<const MethodRun *> &mesh_runs, size_t set) {
    std::fprintf(out, "    ray %zu org %.17g %.17g %.17g dir %.17g %.17g %.17g\n", index, ray.org[0],
                 ray.org[1], ray.org[2], ray.dir[0], ray.dir[1], ray.dir[2]);
    auto line = [&](const char *name, const Trace &t) {
        if (std::isfinite(t.t[index]))
            std::fprintf(out, "      %-12s t %.17g patch %u uv %.4f %.4f |cos| %.4f\n", name, t.t[index],
                         t.patch[index], t.u[index], t.v[index], t.cos_normal[index]);
        else
            std::fprintf(out, "      %-12s miss\n", name);
    };
    line("exact", exact);
    for (const MethodRun *m : mesh_runs) line(m->name.c_str(), m->traces[set]);
}

} // namespace

void print_suspects(std::FILE *out, const std::vector<RaySet> &sets, const std::vector<MethodRun> &runs,
                    const MethodRun &exact, double diagonal, size_t max_listed) {
    std::vector<const MethodRun *> mesh_runs;
    for (const MethodRun &run : runs)
        if (&run != &exact) mesh_runs.push_back(&run);
    if (mesh_runs.empty()) return;
    const MethodRun *finest = *std::max_element(mesh_runs.begin(), mesh_runs.end(),
        [](const MethodRun *a, const MethodRun *b) { return a->grid < b->grid; });

    std::fprintf(out, "\nDisagreements with every mesh (%zu mesh runs agreeing within %g diagonal);\n"
                      "explained = the exact or finest mesh hit is grazing (|cos| < %g) or within %g "
                      "of a patch edge in (u, v):\n",
                 mesh_runs.size(), agree_dt, grazing_cos, edge_band);
    for (size_t s = 0; s < sets.size(); ++s) {
        const Trace &e = exact.traces[s];
        std::vector<const Trace *> meshes;
        for (const MethodRun *m : mesh_runs) meshes.push_back(&m->traces[s]);
        const Trace &witness = finest->traces[s];

        size_t explained[kind_count] = {}, unexplained[kind_count] = {};
        std::vector<Case> listed;
        for (size_t i = 0; i < sets[s].rays.size(); ++i) {
            const Kind kind = classify(i, e, meshes, diagonal);
            if (kind == kind_count) continue;
            // Either side's hit may be the grazing or edge one: a mesh bulging past a concave
            // surface hits a ray that passes the surface at 1e-5, and the exact hit behind is
            // then steep.
            const char *why = nullptr;
            for (const Trace *about : {&e, &witness}) {
                if (!std::isfinite(about->t[i]) || why) continue;
                if (about->cos_normal[i] < grazing_cos) why = "grazing";
                else if (near_edge(*about, i)) why = "patch edge";
            }
            size_t &count = why ? explained[kind] : unexplained[kind];
            if (count++ < (why ? explained_listed : max_listed)) listed.push_back({i, kind, why});
        }
        for (int k = 0; k < kind_count; ++k)
            std::fprintf(out, "  %-6s %-16s unexplained %7zu   grazing/edge %7zu\n", sets[s].name.c_str(),
                         kind_names[k], unexplained[k], explained[k]);
        for (const Case &c : listed) {
            std::fprintf(out, "  %s, %s%s%s:\n", sets[s].name.c_str(), kind_names[c.kind],
                         c.explanation ? ", explained: " : "", c.explanation ? c.explanation : "");
            print_ray(out, sets[s].rays[c.ray], c.ray, e, mesh_runs, s);
        }
    }
}

} // namespace bench
