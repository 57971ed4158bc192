// SPDX-License-Identifier: Apache-2.0
#include "evaluate.h"

#include <algorithm>
#include <cmath>

namespace bench {

double normal_error(const float *n, const Truth &truth, size_t i, const TruthRoot *match, double diagonal) {
    // Roots of several patches at one point differ in t only by rounding.
    const double same_point = 1e-9 * diagonal;
    double best = -1;
    for (const TruthRoot *r = truth.begin(i); r != truth.end(i); ++r) {
        if (std::fabs(r->t - match->t) > same_point) continue;
        if (r->normal[0] == 0 && r->normal[1] == 0 && r->normal[2] == 0) continue;
        const double a = normal_angle(n, r->normal);
        if (best < 0 || a < best) best = a;
    }
    return best;
}

namespace {

constexpr double degrees = 57.29577951308232;

} // namespace

// Patches are two-sided, so normals are compared as lines; a method that gave no normal
// scores 90 degrees.
double normal_angle(const float *a, const float *b) {
    const double la = std::sqrt(double(a[0]) * a[0] + double(a[1]) * a[1] + double(a[2]) * a[2]);
    const double lb = std::sqrt(double(b[0]) * b[0] + double(b[1]) * b[1] + double(b[2]) * b[2]);
    if (!(la > 0) || !(lb > 0)) return 90.0;
    const double c = std::fabs(double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2]) / (la * lb);
    // acos loses precision near 0; the cross product's length gives the small angles.
    const double x = double(a[1]) * b[2] - double(a[2]) * b[1], y = double(a[2]) * b[0] - double(a[0]) * b[2],
                 z = double(a[0]) * b[1] - double(a[1]) * b[0];
    return std::atan2(std::sqrt(x * x + y * y + z * z) / (la * lb), c) * degrees;
}

namespace {

// Sorts `values` partially and returns the q-quantile (q in [0, 1], nearest rank).
double quantile(std::vector<double> &values, double q) {
    if (values.empty()) return 0;
    size_t k = size_t(std::ceil(q * double(values.size())));
    k = std::min(values.size() - 1, k > 0 ? k - 1 : 0);
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return values[k];
}

double maximum(const std::vector<double> &values) {
    return values.empty() ? 0 : *std::max_element(values.begin(), values.end());
}

} // namespace

Outcome judge(const Trace &trace, const std::vector<ppm_ray> &rays, const Truth &truth, size_t i, double diagonal,
              double *dt_out, const TruthRoot **match_out) {
    const TruthKind kind = truth.kind[i];
    if (kind == TruthKind::undecided) return Outcome::undecided;
    if (!std::isfinite(trace.t[i])) {
        if (kind == TruthKind::hit) return Outcome::miss;
        return kind == TruthKind::ambiguous ? Outcome::ambiguous : Outcome::correct;
    }
    if (kind == TruthKind::none) return Outcome::false_hit;
    // The hit belongs to the reference root nearest to it along the ray.
    const TruthRoot *match = nullptr;
    double dt = INFINITY;
    for (const TruthRoot *r = truth.begin(i); r != truth.end(i); ++r) {
        const double d = std::fabs(trace.t[i] - r->t);
        if (d < dt) {
            dt = d;
            match = r;
        }
    }
    if (dt_out) *dt_out = dt / diagonal;
    if (match_out) *match_out = match;
    const double limit = false_hit_distance * diagonal;
    // A root behind the ray's first surface: the method went through that surface.
    const TruthRoot *first = truth.robust(i);
    if (first && match->t > first->t + limit) return Outcome::false_hit;
    // How far the hit point lies from the surface there, measured from the root's tangent
    // plane: a mesh displaced from the surface by e is hit e / sin(angle) away along a ray at
    // that angle to the surface, which is an inaccurate hit, not a false one.
    const float *n = match->normal;
    const double *d = rays[i].dir;
    const double sine = std::fabs(n[0] * d[0] + n[1] * d[1] + n[2] * d[2]);
    const double off_surface = (n[0] != 0 || n[1] != 0 || n[2] != 0) ? dt * sine : dt;
    if (off_surface > limit) return Outcome::false_hit;
    return match->robust ? Outcome::correct : Outcome::ambiguous;
}

Stats evaluate(const Trace &trace, const std::vector<ppm_ray> &rays, const Truth &truth, double diagonal,
               double accuracy) {
    Stats s;
    s.rays = trace.size();
    std::vector<double> dts, ng, ns;
    for (size_t i = 0; i < trace.size(); ++i) {
        switch (truth.kind[i]) {
        case TruthKind::undecided: ++s.undecided; continue;
        case TruthKind::hit: ++s.reference_hits; break;
        case TruthKind::ambiguous: ++s.ambiguous; break;
        case TruthKind::none: break;
        }
        s.hits += std::isfinite(trace.t[i]);
        double dt = 0;
        const TruthRoot *match = nullptr;
        const Outcome outcome = judge(trace, rays, truth, i, diagonal, &dt, &match);
        s.misses += outcome == Outcome::miss;
        s.false_hits += outcome == Outcome::false_hit;
        if (outcome != Outcome::correct || !match) continue; // match is null on a correct miss
        ++s.matched;
        dts.push_back(dt);
        s.over_tolerance += accuracy > 0 && dt > accuracy;
        const double g = normal_error(&trace.ng[3 * i], truth, i, match, diagonal);
        if (g >= 0) {
            ng.push_back(g);
            ns.push_back(normal_error(&trace.ns[3 * i], truth, i, match, diagonal));
        }
    }
    s.dt_max = maximum(dts);
    s.dt_p999 = quantile(dts, 0.999);
    s.dt_median = quantile(dts, 0.5);
    s.ng_max = maximum(ng);
    s.ng_p999 = quantile(ng, 0.999);
    s.ng_median = quantile(ng, 0.5);
    s.ns_max = maximum(ns);
    s.ns_median = quantile(ns, 0.5);
    return s;
}

std::string statistics_definitions() {
    return "definitions (truth = the reference's roots of the same ray; diag = bounding-box diagonal):\n"
           "  reference hit  the ray has a robust root: it dips through the surface deeper than 1e-15 diag,\n"
           "                 or crosses a collapsed edge. Rays with only tangent touches (within 2e-9 diag)\n"
           "                 or shallower roots are 'ambiguous': a hit near such a root and a miss are both\n"
           "                 right, and such hits are left out of the |dt| and normal statistics.\n"
           "  miss rate      reference hits the method misses / reference hits\n"
           "  false-hit rate hits on no surface the ray meets first / rays (undecided ones left out). A hit is\n"
           "                 attributed to the reference root nearest to it along the ray; it is false when\n"
           "                 the ray has no root at all, when that root lies more than 1e-3 diag beyond the\n"
           "                 first robust root (the nearest surface was skipped), or when the hit point lies\n"
           "                 more than 1e-3 diag from that root's tangent plane (a surface that is not there;\n"
           "                 a mesh 1e-4 off the surface, hit far along a grazing ray, is inaccurate, not false)\n"
           "  |dt|           |t_method - t_root| / diag over the other hits (t is a distance: unit directions)\n"
           "  normal error   angle between the method's geometric normal (meshes: the facet's; 'ns' the\n"
           "                 interpolated vertex normal) and the surface normal at that root, as unoriented\n"
           "                 lines (patches are two-sided); 90 degrees where a method returns none\n"
           "  rays/s         1 thread: rays / process CPU time; all threads: rays / wall time; each set is\n"
           "                 traced again until --min-time has passed\n"
           "  build          wall time of the acceleration structure's build (meshes: tessellation apart)\n"
           "  memory         input arrays kept (control points, vertices + indices) + acceleration structure\n";
}

} // namespace bench
