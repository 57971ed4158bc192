// SPDX-License-Identifier: Apache-2.0
#include "geometry/tessellate_edge.h"

#include "geometry/tessellate_budget.h"

#include <algorithm>
#include <cmath>

namespace ppm {
namespace tess {

namespace {

bool less(const Vec3 &a, const Vec3 &b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}
bool same(const Vec3 &a, const Vec3 &b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
// Largest distance of the n chords from the curve, sampled at eighths of each chord.
double chord_deviation(const Edge &e, uint32_t n) {
    const std::vector<Vec3> points = edge_points(e, n);
    double worst = 0;
    for (uint32_t k = 0; k < n; ++k)
        for (int s = 1; s < 8; ++s) {
            const double f = s / 8.0;
            const Vec3 x = points[k] * (1 - f) + points[k + 1] * f;
            worst = std::max(worst, curve_distance(e.c, x, (k + f) / n));
        }
    return worst;
}

} // namespace

double curve_distance(const Vec3 c[4], const Vec3 &x, double t) {
    double b[4], d1[4], d2[4];
    bernstein3(t, b);
    double best = length2(curve_sum(c, b) - x);
    for (int iteration = 0; iteration < 4; ++iteration) {
        bernstein3(t, b);
        bernstein3_derivative(t, d1);
        bernstein3_second(t, d2);
        const Vec3 r = curve_sum(c, b) - x, c1 = curve_sum(c, d1), c2 = curve_sum(c, d2);
        const double slope = dot(c1, c1) + dot(c2, r);
        if (!(slope > 0)) break;
        const double next = std::clamp(t - dot(c1, r) / slope, 0.0, 1.0);
        bernstein3(next, b);
        const double dist2 = length2(curve_sum(c, b) - x);
        if (!(dist2 < best)) break;
        best = dist2;
        if (std::fabs(next - t) < 1e-14) break;
        t = next;
    }
    return std::sqrt(best);
}

Edge patch_edge(const BezierPatch &patch, int side) {
    Vec3 q[4];
    for (int k = 0; k < 4; ++k)
        q[k] = side == side_v0   ? patch.at(0, k)
               : side == side_u1 ? patch.at(k, 3)
               : side == side_v1 ? patch.at(3, k)
                                 : patch.at(k, 0);
    Edge e;
    e.reversed = less(q[3], q[0]) || (same(q[3], q[0]) && less(q[2], q[1]));
    for (int k = 0; k < 4; ++k) e.c[k] = q[e.reversed ? 3 - k : k];
    e.collapsed = same(q[0], q[1]) && same(q[0], q[2]) && same(q[0], q[3]);
    return e;
}

std::vector<Vec3> edge_points(const Edge &e, uint32_t n) {
    std::vector<Vec3> points(size_t(n) + 1, e.c[0]);
    if (e.collapsed) return points;
    points[n] = e.c[3];
    for (uint32_t k = 1; k < n; ++k) {
        double b[4];
        bernstein3(double(k) / n, b);
        points[k] = curve_sum(e.c, b);
    }
    return points;
}

uint32_t edge_segments(const Edge &e, double tolerance) {
    if (e.collapsed) return 0;
    // |C''| is linear in t for a cubic, so its maximum is at an end, and a chord of parameter
    // length h is within max|C''| h^2 / 8 of the curve: counts from this bound always pass.
    const double c2 = 6 * std::max(length(e.c[0] - e.c[1] * 2 + e.c[2]), length(e.c[1] - e.c[2] * 2 + e.c[3]));
    const double bound = std::max(1.0, std::ceil(std::sqrt(c2 / (8 * tolerance))));
    const auto passes = [&](uint32_t n) { return n >= bound || chord_deviation(e, n) <= tolerance; };
    uint32_t hi = 1;
    while (!passes(hi)) {
        if (hi >= max_segments) over_budget(double(hi) * hi);
        hi *= 2;
    }
    uint32_t lo = hi / 2; // fails, or 0
    while (hi - lo > 1) {
        const uint32_t mid = lo + (hi - lo) / 2;
        (passes(mid) ? hi : lo) = mid;
    }
    return hi;
}

} // namespace tess
} // namespace ppm
