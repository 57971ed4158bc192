// SPDX-License-Identifier: Apache-2.0
#include "suspects.h"

#include <cmath>
#include <vector>

namespace bench {

namespace {

// An exact normal should agree with the reference to rounding; this leaves room for the
// reference's limit normals (taken 1e-7 inside the patch) and float storage.
constexpr double max_normal_error = 1.0; // degrees

} // namespace

void print_suspects(std::FILE *out, const std::vector<RaySet> &sets, const MethodResult &exact, double diagonal,
                    size_t max_listed) {
    // Only the exact method promises an accuracy.
    const double tolerance = exact.info.tolerance > 0 ? exact.info.tolerance : INFINITY;
    if (std::isfinite(tolerance))
        std::fprintf(out,
                     "\nDisagreements of %s with the reference (miss, false hit, |dt| above the tolerance "
                     "%g diag, or normal error above 1 degree):\n",
                     exact.info.name.c_str(), tolerance);
    else
        std::fprintf(out, "\nDisagreements of %s with the reference (miss or false hit):\n", exact.info.name.c_str());
    for (size_t s = 0; s < sets.size() && s < exact.traces.size(); ++s) {
        const RayBatch &batch = sets[s].batch(exact.info.spawn_tolerance);
        const Trace &trace = exact.traces[s];
        // Rays by kind of disagreement, listed in order of severity.
        std::vector<size_t> found[4];
        for (size_t i = 0; i < trace.size(); ++i) {
            double dt = 0;
            const TruthRoot *match = nullptr;
            const Outcome o = judge(trace, batch.rays, batch.truth, i, diagonal, &dt, &match);
            int kind = -1;
            if (o == Outcome::miss)
                kind = 0;
            else if (o == Outcome::false_hit)
                kind = 1;
            else if (o == Outcome::correct && std::isfinite(trace.t[i]) && dt > tolerance)
                kind = 2;
            else if (o == Outcome::correct && match &&
                     normal_error(&trace.ng[3 * i], batch.truth, i, match, diagonal) > max_normal_error)
                kind = 3;
            if (kind >= 0) found[kind].push_back(i);
        }
        static const char *const names[] = {"miss", "false hit", "|dt| above tolerance", "normal error"};
        size_t listed = 0;
        for (int kind = 0; kind < 4; ++kind) {
            for (size_t i : found[kind]) {
                if (listed++ >= max_listed) break;
                double dt = 0;
                judge(trace, batch.rays, batch.truth, i, diagonal, &dt);
                const ppm_ray &r = batch.rays[i];
                std::fprintf(out, "  %s ray %zu, %s: org %.17g %.17g %.17g dir %.17g %.17g %.17g tnear %.17g\n",
                             sets[s].name.c_str(), i, names[kind], r.org[0], r.org[1], r.org[2], r.dir[0], r.dir[1],
                             r.dir[2], r.tnear);
                if (std::isfinite(trace.t[i]))
                    std::fprintf(out, "    method:    t %.17g patch %u (|dt| %.3g diag) ng %.9g %.9g %.9g\n",
                                 trace.t[i], trace.patch[i], dt, trace.ng[3 * i], trace.ng[3 * i + 1],
                                 trace.ng[3 * i + 2]);
                else
                    std::fprintf(out, "    method:    miss\n");
                for (const TruthRoot *root = batch.truth.begin(i); root != batch.truth.end(i); ++root)
                    std::fprintf(out, "    reference: t %.17g patch %u normal %.9g %.9g %.9g%s\n", root->t, root->patch,
                                 root->normal[0], root->normal[1], root->normal[2],
                                 root->robust ? "" : " (tangent or too shallow: not robust)");
                if (batch.truth.begin(i) == batch.truth.end(i)) std::fprintf(out, "    reference: no root\n");
            }
        }
        const size_t counts[4] = {found[0].size(), found[1].size(), found[2].size(), found[3].size()};
        std::fprintf(out, "  %-14s %6zu misses, %6zu false hits, %6zu beyond tolerance, %6zu normals off by > %g deg\n",
                     sets[s].name.c_str(), counts[0], counts[1], counts[2], counts[3], max_normal_error);
    }
}

} // namespace bench
