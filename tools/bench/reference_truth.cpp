// SPDX-License-Identifier: Apache-2.0
#include "reference_truth.h"

#include "parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bench {

namespace {

using ref::real;

// The test suite's definition (tests/geometry/test_teapot_reference.cpp): a root is robust when the
// ray dips through the surface deeper than 1e-15 of the diagonal (~20 ulps of the
// coordinates), or sits on a collapsed edge. A ray tangent in real arithmetic, rounded to
// double, crosses or misses by ~1e-17: no double-precision method can tell which.
bool is_robust(const ref::Root &r, real diagonal) {
    return r.kind != ref::RootKind::tangent && (r.degenerate_normal || r.dip > 1e-15L * diagonal);
}

bool unit(real n[3]) {
    const real l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(l > 0) || !std::isfinite(l)) return false;
    for (int c = 0; c < 3; ++c) n[c] /= l;
    return true;
}

bool raw_normal(const ref::Patch &patch, real u, real v, real n[3]) {
    real s[3], su[3], sv[3];
    ref::evaluate(patch, u, v, s, su, sv);
    n[0] = su[1] * sv[2] - su[2] * sv[1];
    n[1] = su[2] * sv[0] - su[0] * sv[2];
    n[2] = su[0] * sv[1] - su[1] * sv[0];
    const real lu = std::sqrt(su[0] * su[0] + su[1] * su[1] + su[2] * su[2]);
    const real lv = std::sqrt(sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2]);
    const real ln = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    // As the reference's own test: next to a collapsed edge the vanishing derivative is
    // rounding noise and so is the cross product's direction.
    return ln > 1e-8L * lu * lv && std::min(lu, lv) > 1e-8L * std::max(lu, lv) && unit(n);
}

} // namespace

bool reference_normal(const ref::Patch &patch, real u, real v, real n[3]) {
    if (raw_normal(patch, u, v, n)) return true;
    // At a collapsed edge the normal's limit is its value a hair towards the patch centre:
    // 1e-7 in (u, v) turns the direction by ~1e-7 rad, far below what the bench resolves.
    const real h = 1e-7L;
    return raw_normal(patch, u + (u < 0.5L ? h : -h), v + (v < 0.5L ? h : -h), n);
}

std::string reference_description(const ref::Intersector &reference) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "reference: tools/reference/reference_intersector (independent of libppm: "
                  "world-space De Casteljau subdivision to leaves of 1e-6 diagonal, long-double "
                  "Newton on (u, v, t)); model diagonal %.6Lg",
                  reference.diagonal());
    return text;
}

Truth compute_truth(const ref::Intersector &reference, const std::vector<ppm_ray> &rays, int threads) {
    const size_t n = rays.size();
    std::vector<TruthKind> kind(n, TruthKind::none);
    std::vector<std::vector<TruthRoot>> per_ray(n);
    const real diagonal = reference.diagonal();
    parallel_chunks(n, threads, 64, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            const ppm_ray &r = rays[i];
            const real o[3] = {r.org[0], r.org[1], r.org[2]}, d[3] = {r.dir[0], r.dir[1], r.dir[2]};
            const ref::Result result = reference.intersect(o, d, r.tnear, r.tfar);
            if (!result.decided) {
                kind[i] = TruthKind::undecided;
                continue;
            }
            const real length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (const ref::Root &root : result.roots) {
                TruthRoot out;
                out.t = static_cast<double>(root.t * length);
                out.patch = static_cast<uint32_t>(root.patch);
                out.robust = is_robust(root, diagonal);
                real normal[3] = {0, 0, 0};
                reference_normal(reference.patches()[root.patch], root.u, root.v, normal);
                for (int c = 0; c < 3; ++c) out.normal[c] = static_cast<float>(normal[c]);
                per_ray[i].push_back(out);
                if (out.robust)
                    kind[i] = TruthKind::hit;
                else if (kind[i] == TruthKind::none)
                    kind[i] = TruthKind::ambiguous;
            }
        }
    });
    Truth truth;
    truth.kind = std::move(kind);
    truth.first.reserve(n + 1);
    truth.first_robust.reserve(n);
    for (const std::vector<TruthRoot> &roots : per_ray) {
        truth.first.push_back(static_cast<uint32_t>(truth.roots.size()));
        uint32_t robust = Truth::no_root;
        for (size_t k = 0; k < roots.size() && robust == Truth::no_root; ++k)
            if (roots[k].robust) robust = static_cast<uint32_t>(truth.roots.size() + k);
        truth.first_robust.push_back(robust);
        truth.roots.insert(truth.roots.end(), roots.begin(), roots.end());
    }
    truth.first.push_back(static_cast<uint32_t>(truth.roots.size()));
    return truth;
}

} // namespace bench
