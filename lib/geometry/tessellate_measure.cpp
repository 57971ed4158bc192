// SPDX-License-Identifier: Apache-2.0
// measure_deviation (tessellate.h): distances from sample points of triangles to their patch.
#include "geometry/tessellate.h"

#include "geometry/tessellate_edge.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace ppm {

namespace {

using tess::curve_distance;

// Barycentric sampling of a triangle: a lattice of step 1 / coarse_grid everywhere, finer
// lattices near the maxima (see refine).
constexpr int coarse_grid = 4;

// Gauss-Newton descent from (u, v) towards the point of the patch nearest to x, kept inside
// the domain. Every accepted step brings the surface point closer, so the result is the
// squared distance to a real surface point: an upper bound for the surface. (u, v) and d end
// at that point.
double descend(const BezierPatch &patch, const Vec3 &x, double &u, double &v, SurfaceDerivatives &d) {
    double best = length2(d.p - x);
    for (int iteration = 0; iteration < 8; ++iteration) {
        const Vec3 r = d.p - x;
        // Damping keeps the step finite where a derivative vanishes (a collapsed edge).
        const double damp = 1e-12 * (length2(d.du) + length2(d.dv));
        const double a = length2(d.du) + damp, b = dot(d.du, d.dv), c = length2(d.dv) + damp;
        const double g1 = dot(d.du, r), g2 = dot(d.dv, r);
        const double det = a * c - b * b;
        if (!(det > 0)) break;
        // The Gauss-Newton step; if that does not get closer (the surface bends away, or the
        // nearest point lies on the border), half of it, then steps along one parameter.
        const double step_u = -(c * g1 - b * g2) / det, step_v = -(a * g2 - b * g1) / det;
        const double tries[4][2] = {
            {u + step_u, v + step_v}, {u + step_u / 2, v + step_v / 2}, {u - g1 / a, v}, {u, v - g2 / c}};
        const bool inside = tries[0][0] >= 0 && tries[0][0] <= 1 && tries[0][1] >= 0 && tries[0][1] <= 1;
        bool moved = false, converged = false;
        for (int k = 0; k < 4 && !moved; ++k) {
            const double next_u = std::clamp(tries[k][0], 0.0, 1.0), next_v = std::clamp(tries[k][1], 0.0, 1.0);
            const SurfaceDerivatives next = evaluate_derivatives(patch, next_u, next_v);
            const double dist2 = length2(next.p - x);
            if (!(dist2 < best)) continue;
            // A full step converges quadratically for the small residuals met here: after one
            // that gains this little, another would gain far less. Clamped or partial steps
            // converge more slowly and keep going.
            converged = k == 0 && inside && best - dist2 <= 1e-6 * best;
            best = dist2;
            d = next;
            u = next_u;
            v = next_v;
            moved = true;
        }
        if (!moved || converged) break;
    }
    return best;
}

// Distance from x to the patch by descent from (u, v). If S(u, v) itself is within `floor` of
// x, that distance is returned without the steps: callers look for a maximum that is already
// at least `floor`.
double surface_distance(const BezierPatch &patch, const Vec3 &x, double u, double v, double floor) {
    SurfaceDerivatives d = evaluate_derivatives(patch, u, v);
    if (length2(d.p - x) <= floor * floor) return length(d.p - x);
    return std::sqrt(descend(patch, x, u, v, d));
}

// The same by a search over [u0, u1] x [v0, v1]: descent from the best of a 9 x 9 grid there.
// For samples whose descent from their own (u, v) stalls in a local minimum (near a cusp or
// fold of the patch).
double surface_distance_in(const BezierPatch &patch, const Vec3 &x, double u0, double u1, double v0, double v1) {
    double best_u = u0, best_v = v0, best = INFINITY;
    for (int i = 0; i <= 8; ++i)
        for (int j = 0; j <= 8; ++j) {
            const double u = u0 + (u1 - u0) * i / 8, v = v0 + (v1 - v0) * j / 8;
            const double dist2 = length2(evaluate(patch, u, v) - x);
            if (dist2 < best) {
                best = dist2;
                best_u = u;
                best_v = v;
            }
        }
    SurfaceDerivatives d = evaluate_derivatives(patch, best_u, best_v);
    return std::sqrt(descend(patch, x, best_u, best_v, d));
}

// Distances from points of one triangle to its patch, at barycentric lattice points (i / k,
// j / k): the weights of corners 1 and 2, their uvs interpolated the same way.
class TriangleProbe {
public:
    // Samples farther than `retry_above` from the surface are searched for again over the
    // triangle's (u, v) box widened by its size on every side.
    TriangleProbe(const BezierPatch &patch, const double *positions, const double *uvs, const uint32_t corner[3],
                  double retry_above)
        : patch_(patch), retry_above_(retry_above) {
        double lo[2] = {1, 1}, hi[2] = {0, 0};
        for (int c = 0; c < 3; ++c) {
            p_[c] = Vec3::from(positions + 3 * size_t(corner[c]));
            for (int a = 0; a < 2; ++a) {
                t_[c][a] = uvs[2 * size_t(corner[c]) + a];
                lo[a] = std::min(lo[a], t_[c][a]);
                hi[a] = std::max(hi[a], t_[c][a]);
            }
        }
        for (int a = 0; a < 2; ++a) {
            box_[a][0] = std::max(0.0, 2 * lo[a] - hi[a]);
            box_[a][1] = std::min(1.0, 2 * hi[a] - lo[a]);
        }
    }

    // Whether (i, j) is a lattice point of step 1 / k other than a corner (which lies on the
    // surface by construction).
    static bool sampled(int i, int j, int k) {
        return i >= 0 && j >= 0 && i + j <= k && i != k && j != k && (i != 0 || j != 0);
    }

    double at(int i, int j, int k, double floor) const {
        const double l1 = double(i) / k, l2 = double(j) / k, l0 = 1 - l1 - l2;
        const Vec3 x = p_[0] * l0 + p_[1] * l1 + p_[2] * l2;
        const double u = t_[0][0] * l0 + t_[1][0] * l1 + t_[2][0] * l2;
        const double v = t_[0][1] * l0 + t_[1][1] * l1 + t_[2][1] * l2;
        double d = surface_distance(patch_, x, u, v, floor);
        // A sample on the patch border (a chord of an edge) is also measured to the edge's
        // curve alone, the way edge_segments measured it, which a descent across the folds
        // of a wild patch can miss.
        if (d > floor && (u == 0 || u == 1 || v == 0 || v == 1)) {
            Vec3 edge[4];
            for (int k = 0; k < 4; ++k)
                edge[k] = u == 0   ? patch_.at(k, 0)
                          : u == 1 ? patch_.at(k, 3)
                          : v == 0 ? patch_.at(0, k)
                                   : patch_.at(3, k);
            d = std::min(d, curve_distance(edge, x, u == 0 || u == 1 ? v : u));
        }
        if (d <= retry_above_) return d;
        return std::min(d, surface_distance_in(patch_, x, box_[0][0], box_[0][1], box_[1][0], box_[1][1]));
    }

private:
    const BezierPatch &patch_;
    double retry_above_;
    Vec3 p_[3];
    double t_[3][2];
    double box_[2][2];
};

constexpr int neighbours[6][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, -1}, {-1, 1}};

using CoarseLattice = double[coarse_grid + 1][coarse_grid + 1];

// All coarse lattice points (0 at the corners and outside); returns their maximum. A point
// whose parametric distance is below `floor` or the running maximum keeps that upper bound.
double coarse_pass(const TriangleProbe &probe, CoarseLattice value, double floor) {
    double worst = 0;
    for (int i = 0; i <= coarse_grid; ++i)
        for (int j = 0; j <= coarse_grid; ++j) {
            value[i][j] = 0;
            if (TriangleProbe::sampled(i, j, coarse_grid))
                worst = std::max(worst, value[i][j] = probe.at(i, j, coarse_grid, std::max(worst, floor)));
        }
    return worst;
}

// Climbs from every coarse local maximum within 10% of the top to a local maximum on the
// lattices 2, 4 and 8 times as fine (moving to the best of six neighbours while it improves).
// The error over a triangle is close to a quadratic bump, whose maximum the finest lattice
// misses by a fraction of a percent.
double refine(const TriangleProbe &probe, const CoarseLattice value, double top) {
    double worst = top;
    for (int i = 0; i <= coarse_grid; ++i)
        for (int j = 0; i + j <= coarse_grid; ++j) {
            if (!TriangleProbe::sampled(i, j, coarse_grid) || value[i][j] < 0.9 * top) continue;
            bool local_max = true;
            for (const auto &n : neighbours) {
                const int a = i + n[0], b = j + n[1];
                if (a >= 0 && b >= 0 && a <= coarse_grid && b <= coarse_grid && value[a][b] > value[i][j])
                    local_max = false;
            }
            if (!local_max) continue;
            int a = i, b = j, k = coarse_grid;
            // The coarse value may be an upper bound that skipped the search (see coarse_pass).
            double here = probe.at(i, j, coarse_grid, 0.0);
            for (int level = 0; level < 3; ++level) {
                a *= 2;
                b *= 2;
                k *= 2;
                for (;;) {
                    int best_a = a, best_b = b;
                    double best = here;
                    for (const auto &n : neighbours) {
                        const int na = a + n[0], nb = b + n[1];
                        if (!TriangleProbe::sampled(na, nb, k)) continue;
                        const double d = probe.at(na, nb, k, best);
                        if (d > best) {
                            best = d;
                            best_a = na;
                            best_b = nb;
                        }
                    }
                    if (best_a == a && best_b == b) break;
                    a = best_a;
                    b = best_b;
                    here = best;
                }
            }
            worst = std::max(worst, here);
        }
    return worst;
}

} // namespace

double measure_deviation(const BezierPatch &patch, const std::vector<double> &positions, const std::vector<double> &uvs,
                         const uint32_t *indices, size_t triangle_count, double focus) {
    // Triangles within 80% of the focus are refined at once; which others come within 80% of
    // the largest coarse value is known only at the end.
    const double early = 0.8 * focus;
    std::vector<double> coarse(triangle_count);
    std::vector<char> refined(triangle_count, 0);
    double coarse_max = 0, worst = 0;
    CoarseLattice lattice;
    for (size_t t = 0; t < triangle_count; ++t) {
        const TriangleProbe probe(patch, positions.data(), uvs.data(), indices + 3 * t, focus);
        // Values below this can neither be refined nor be the maximum.
        const double floor = 0.8 * std::min(focus, coarse_max);
        double d = coarse[t] = coarse_pass(probe, lattice, floor);
        coarse_max = std::max(coarse_max, d);
        if (d >= early && d > 0) {
            d = refine(probe, lattice, d);
            refined[t] = 1;
        }
        worst = std::max(worst, d);
    }
    const double threshold = 0.8 * std::min(focus, coarse_max);
    for (size_t t = 0; t < triangle_count; ++t) {
        if (refined[t] || !(threshold > 0) || coarse[t] < threshold) continue;
        const TriangleProbe probe(patch, positions.data(), uvs.data(), indices + 3 * t, focus);
        worst = std::max(worst, refine(probe, lattice, coarse_pass(probe, lattice, 0.9 * coarse[t])));
    }
    return worst;
}

} // namespace ppm
