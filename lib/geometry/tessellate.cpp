#include "geometry/tessellate.h"

#include "core/error.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <unordered_map>

namespace ppm {

namespace {

// A measured deviation must stay below this share of the tolerance: the measured maximum of a
// triangle (on a lattice of step 1/32) lies within about 0.1% of the true one.
constexpr double accept_share = 0.997;
// Edge chords get this share of the tolerance, leaving room for the ring triangles beside them
// (whose error adds the surface's bending away from the edge).
constexpr double edge_share = 0.6;
// Barycentric sampling of a triangle: a lattice of step 1 / coarse_grid everywhere, finer
// lattices near the maxima (see refine).
constexpr int coarse_grid = 4;
// Samples per direction of the curvature that drives the per-patch grid counts.
constexpr int curvature_samples = 25;
constexpr uint32_t max_segments = 1u << 22;
constexpr int max_refinements = 16;

[[noreturn]] void over_budget(double triangles) {
    invalid_argument("the tessellation would need about " + format_number(std::round(triangles)) +
                     " triangles, more than the limit of " +
                     format_number(max_tessellation_triangles) + ": use a larger tolerance or grid");
}

// ---- Bezier helpers ----------------------------------------------------------------------

Vec3 curve_sum(const Vec3 c[4], const double b[4]) {
    return c[0] * b[0] + c[1] * b[1] + c[2] * b[2] + c[3] * b[3];
}

// Distance from x to the cubic curve c, by Newton steps on C'(t) . (C(t) - x) from t. Every
// accepted step brings the curve point closer, so the result bounds the true distance.
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

// ---- Edges -------------------------------------------------------------------------------

// Sides of a patch, each run in the direction of increasing parameter.
enum Side { side_v0 = 0, side_u1 = 1, side_v1 = 2, side_u0 = 3 };

// A patch edge's four control points in a canonical direction (the lexicographically smaller
// of the two readings), so that two patches sharing the edge in either direction see the same
// curve, count the same segments and compute bit-identical points.
struct Edge {
    Vec3 c[4];
    bool reversed = false; // the canonical direction runs against the patch parameter
    bool collapsed = false;
};

bool less(const Vec3 &a, const Vec3 &b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}
bool same(const Vec3 &a, const Vec3 &b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

Edge patch_edge(const BezierPatch &patch, int side) {
    Vec3 q[4];
    for (int k = 0; k < 4; ++k)
        q[k] = side == side_v0 ? patch.at(0, k)
             : side == side_u1 ? patch.at(k, 3)
             : side == side_v1 ? patch.at(3, k)
                               : patch.at(k, 0);
    Edge e;
    e.reversed = less(q[3], q[0]) || (same(q[3], q[0]) && less(q[2], q[1]));
    for (int k = 0; k < 4; ++k) e.c[k] = q[e.reversed ? 3 - k : k];
    e.collapsed = same(q[0], q[1]) && same(q[0], q[2]) && same(q[0], q[3]);
    return e;
}

// Points k / n of the edge, k = 0..n, in canonical order. The ends are the control points
// exactly, and a collapsed edge is its one point, so corners and apexes weld across patches.
// The only place that evaluates edge points, so that both patches of a seam run the same code.
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

// Fewest segments whose chords stay within `tolerance` of the edge: a function of the edge's
// curve alone, so the two patches of a seam agree.
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

// ---- Error model for the interior grid -----------------------------------------------------

// Normal components of the second derivatives (the second fundamental form) at one point.
struct Curvature {
    double a, b, c; // n . S_uu, n . S_uv, n . S_vv
};

// The surface's bending sampled on a regular grid over the patch, and from it the density of
// grid lines in each direction.
struct PatchModel {
    std::vector<Curvature> samples;           // curvature_samples^2: row j (v), column i (u)
    std::vector<double> density_u, density_v; // per sample column / row
};

PatchModel make_model(const BezierPatch &patch) {
    const int n = curvature_samples;
    const double scale = control_bounds(patch).diagonal();
    PatchModel m;
    m.samples.reserve(size_t(n) * n);
    m.density_u.assign(n, 0.0);
    m.density_v.assign(n, 0.0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double u = double(i) / (n - 1), v = double(j) / (n - 1);
            const Vec3 normal = geometric_normal(patch, u, v, scale);
            const SecondDerivatives d = second_derivatives(patch, u, v);
            const Curvature k{dot(normal, d.uu), dot(normal, d.uv), dot(normal, d.vv)};
            m.samples.push_back(k);
            m.density_u[i] = std::max(m.density_u[i], std::fabs(k.a) + std::fabs(k.b));
            m.density_v[j] = std::max(m.density_v[j], std::fabs(k.c) + std::fabs(k.b));
        }
    // The error of a cell grows with its width squared times the bending, so lines are spaced
    // like 1 / sqrt(bending); the floor keeps cells in flat stretches at most 20 times the finest.
    for (std::vector<double> *density : {&m.density_u, &m.density_v}) {
        double top = 0;
        for (double &x : *density) top = std::max(top, x = std::sqrt(x));
        for (double &x : *density) x = top > 0 ? std::max(x, 0.05 * top) : 1.0;
    }
    return m;
}

// Lines 0 = t_0 < ... < t_n = 1 with equal integrals of the density between neighbours (the
// density taken constant between samples, at the larger of its two ends).
std::vector<double> place_lines(const std::vector<double> &density, uint32_t n) {
    const size_t intervals = density.size() - 1;
    std::vector<double> cumulative(intervals + 1, 0.0);
    for (size_t k = 0; k < intervals; ++k)
        cumulative[k + 1] = cumulative[k] + std::max(density[k], density[k + 1]);
    std::vector<double> lines(size_t(n) + 1);
    lines[0] = 0;
    lines[n] = 1;
    size_t k = 0;
    for (uint32_t i = 1; i < n; ++i) {
        const double target = cumulative[intervals] * i / n;
        while (k + 1 < intervals && cumulative[k + 1] < target) ++k;
        const double f = std::clamp((target - cumulative[k]) / (cumulative[k + 1] - cumulative[k]), 0.0, 1.0);
        lines[i] = (k + f) / intervals;
    }
    return lines;
}

// Width of the cell at each sample position k / (samples - 1); on a line, the wider neighbour.
std::vector<double> widths_at_samples(const std::vector<double> &lines, int samples) {
    std::vector<double> widths(samples);
    const size_t cells = lines.size() - 1;
    size_t cell = 0;
    for (int k = 0; k < samples; ++k) {
        const double t = double(k) / (samples - 1);
        while (cell + 1 < cells && lines[cell + 1] <= t) ++cell;
        double w = lines[cell + 1] - lines[cell];
        if (cell > 0 && lines[cell] == t) w = std::max(w, lines[cell] - lines[cell - 1]);
        widths[k] = w;
    }
    return widths;
}

// Largest |error| of linear interpolation over the triangle (0,0), (1,0), (0,1) of the
// quadratic (a s^2 + 2 b s t + c t^2) / 2, which is (a s(1-s) + c t(1-t) - 2 b s t) / 2: on
// the three sides the maxima are at the midpoints, inside at the critical point.
double triangle_error(double a, double b, double c) {
    double e = std::max({std::fabs(a), std::fabs(c), std::fabs(a + c - 2 * b)}) / 8;
    const double det = a * c - b * b;
    if (det != 0) {
        const double s = c * (a - b) / (2 * det), t = a * (c - b) / (2 * det);
        if (s > 0 && t > 0 && s + t < 1)
            e = std::max(e, std::fabs(a * s * (1 - s) + c * t * (1 - t) - 2 * b * s * t) / 2);
    }
    return e;
}

// Predicted deviation of a grid with cell widths hu, hv at the samples: per sample, the local
// quadratic over its cell split along the better diagonal (the other diagonal mirrors u, which
// flips the sign of b).
double model_error(const PatchModel &m, const std::vector<double> &hu, const std::vector<double> &hv) {
    const int n = curvature_samples;
    double worst = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const Curvature &k = m.samples[size_t(j) * n + i];
            const double a = k.a * hu[i] * hu[i], b = k.b * hu[i] * hv[j], c = k.c * hv[j] * hv[j];
            worst = std::max(worst, std::min(triangle_error(a, b, c), triangle_error(a, -b, c)));
        }
    return worst;
}

struct GridCounts {
    uint32_t nu = 2, nv = 2;
    bool operator==(const GridCounts &o) const { return nu == o.nu && nv == o.nv; }
};

// Triangles of a patch: inner cells, and the ring (one per edge segment and per inner segment).
double patch_triangles(const GridCounts &g, const uint32_t segments[4]) {
    const double nu = g.nu, nv = g.nv;
    return 2 * (nu - 2) * (nv - 2) + 2 * (nu - 2) + 2 * (nv - 2) + segments[0] + segments[1] +
           segments[2] + segments[3];
}

// The counts (at least 2 each, so that an inner grid exists) with the fewest cells whose
// model error is within target. The cost (nu - 1)(nv - 1) is flat near its minimum, so nu
// steps geometrically by 1% and the walk stops once the cost has clearly passed its minimum.
GridCounts choose_counts(const PatchModel &m, double target) {
    const int n = curvature_samples;
    const auto widths_u = [&](double nu) { return widths_at_samples(place_lines(m.density_u, uint32_t(nu)), n); };
    const auto widths_v = [&](double nv) { return widths_at_samples(place_lines(m.density_v, uint32_t(nv)), n); };
    // With the other direction infinitely fine only |a| hu^2 / 8 (or |c| hv^2 / 8) is left.
    std::vector<double> a_max(n, 0.0), c_max(n, 0.0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            a_max[i] = std::max(a_max[i], std::fabs(m.samples[size_t(j) * n + i].a));
            c_max[j] = std::max(c_max[j], std::fabs(m.samples[size_t(j) * n + i].c));
        }
    const auto lowest = [&](const std::vector<double> &bend, auto &&widths) {
        const auto fits_alone = [&](double count) {
            const std::vector<double> h = widths(count);
            double e = 0;
            for (int k = 0; k < n; ++k) e = std::max(e, bend[k] * h[k] * h[k] / 8);
            return e <= target;
        };
        double lo = 1, hi = 2;
        while (!fits_alone(hi)) {
            if (hi > max_segments) over_budget(2 * hi * hi);
            lo = hi;
            hi *= 2;
        }
        while (hi - lo > 1) {
            const double mid = std::floor((lo + hi) / 2);
            (fits_alone(mid) ? hi : lo) = mid;
        }
        return hi;
    };
    const double nu_lo = lowest(a_max, widths_u), nv_lo = lowest(c_max, widths_v);
    if (2 * nu_lo * nv_lo > max_tessellation_triangles) over_budget(2 * nu_lo * nv_lo);
    // Smallest nv that fits with cell widths hu, given that `hi` fits; hi = 0: search upwards.
    const auto smallest_nv = [&](const std::vector<double> &hu, double hi) -> double {
        const auto fits = [&](double nv) { return model_error(m, hu, widths_v(nv)) <= target; };
        double lo = nv_lo;
        if (fits(lo)) return lo;
        if (hi == 0 || !fits(hi)) {
            hi = 2 * lo;
            while (!fits(hi)) {
                if (hi > max_segments) return 0;
                lo = hi;
                hi *= 2;
            }
        }
        while (hi - lo > 1) {
            const double mid = std::floor((lo + hi) / 2);
            (fits(mid) ? hi : lo) = mid;
        }
        return hi;
    };
    double best = std::numeric_limits<double>::infinity(), nv = 0;
    GridCounts result;
    for (double nu = nu_lo; nu <= max_segments && (nu - 1) * (nv_lo - 1) < best;
         nu = std::max(nu + 1, std::ceil(nu * 1.01))) {
        nv = smallest_nv(widths_u(nu), nv);
        if (nv == 0) continue;
        const double cost = (nu - 1) * (nv - 1);
        if (cost < best) {
            best = cost;
            result = {uint32_t(nu), uint32_t(nv)};
        } else if (cost > 1.25 * best) {
            break;
        }
    }
    if (!std::isfinite(best)) over_budget(2.0 * max_segments * max_segments);
    return result;
}

// ---- Building one patch's triangles ----------------------------------------------------------

struct Piece {
    std::vector<double> positions, normals, uvs;
    std::vector<uint8_t> on_border; // vertex on the patch border: welded with the neighbours
    std::vector<uint32_t> indices;
    double deviation = 0;

    size_t triangle_count() const { return indices.size() / 3; }
};

class PieceBuilder {
public:
    PieceBuilder(const BezierPatch &patch, Piece &piece)
        : patch_(patch), piece_(piece), scale_(control_bounds(patch).diagonal()) {}

    uint32_t vertex(const Vec3 &p, double u, double v, bool border) {
        const uint32_t id = uint32_t(piece_.uvs.size() / 2);
        p.store(push(piece_.positions, 3));
        geometric_normal(patch_, u, v, scale_).store(push(piece_.normals, 3));
        piece_.uvs.push_back(u);
        piece_.uvs.push_back(v);
        piece_.on_border.push_back(border);
        return id;
    }
    uint32_t vertex(double u, double v) { return vertex(evaluate(patch_, u, v), u, v, false); }

    // Orders the corners counter-clockwise in (u, v), so that the triangle's winding normal
    // agrees with dS/du x dS/dv.
    void triangle(uint32_t a, uint32_t b, uint32_t c) {
        const double *uv = piece_.uvs.data();
        const double area = (uv[2 * b] - uv[2 * a]) * (uv[2 * c + 1] - uv[2 * a + 1]) -
                            (uv[2 * b + 1] - uv[2 * a + 1]) * (uv[2 * c] - uv[2 * a]);
        if (area < 0) std::swap(b, c);
        piece_.indices.insert(piece_.indices.end(), {a, b, c});
    }

    // Two triangles, split along the diagonal whose midpoint lies closer to the surface point
    // at the cell's centre.
    void quad(uint32_t v00, uint32_t v10, uint32_t v11, uint32_t v01, double uc, double vc) {
        const Vec3 centre = evaluate(patch_, uc, vc);
        const double d1 = length2((position(v00) + position(v11)) * 0.5 - centre);
        const double d2 = length2((position(v10) + position(v01)) * 0.5 - centre);
        if (d1 <= d2) {
            triangle(v00, v10, v11);
            triangle(v00, v11, v01);
        } else {
            triangle(v00, v10, v01);
            triangle(v10, v11, v01);
        }
    }

    // Triangulates the strip between the outer sequence (patch border) and the inner one (an
    // outermost row of the inner grid), both ordered by the parameter along the side: always
    // advance on the side whose next segment's midpoint comes first.
    void stitch(const std::vector<uint32_t> &outer, const std::vector<double> &outer_t,
                const std::vector<uint32_t> &inner, const std::vector<double> &inner_t) {
        size_t a = 0, b = 0;
        while (a + 1 < outer.size() || b + 1 < inner.size()) {
            const bool advance_outer =
                b + 1 == inner.size() ||
                (a + 1 < outer.size() && outer_t[a] + outer_t[a + 1] <= inner_t[b] + inner_t[b + 1]);
            if (advance_outer) {
                triangle(outer[a], outer[a + 1], inner[b]);
                ++a;
            } else {
                triangle(outer[a], inner[b + 1], inner[b]);
                ++b;
            }
        }
    }

    Vec3 position(uint32_t id) const { return Vec3::from(&piece_.positions[3 * size_t(id)]); }

private:
    static double *push(std::vector<double> &values, size_t n) {
        values.resize(values.size() + n);
        return values.data() + values.size() - n;
    }

    const BezierPatch &patch_;
    Piece &piece_;
    double scale_;
};

// Point m of n along a side, in the patch's direction.
const Vec3 &side_point(const std::vector<Vec3> &points, const Edge &e, uint32_t m, uint32_t n) {
    return points[e.reversed ? n - m : m];
}

Piece build_grid(const BezierPatch &patch, uint32_t n) {
    Piece piece;
    PieceBuilder builder(patch, piece);
    Edge edges[4];
    std::vector<Vec3> points[4];
    for (int s = 0; s < 4; ++s) {
        edges[s] = patch_edge(patch, s);
        points[s] = edge_points(edges[s], n);
    }
    std::vector<uint32_t> ids(size_t(n + 1) * (n + 1));
    for (uint32_t j = 0; j <= n; ++j)
        for (uint32_t i = 0; i <= n; ++i) {
            const double u = double(i) / n, v = double(j) / n;
            const Vec3 *border = j == 0   ? &side_point(points[side_v0], edges[side_v0], i, n)
                               : j == n   ? &side_point(points[side_v1], edges[side_v1], i, n)
                               : i == 0   ? &side_point(points[side_u0], edges[side_u0], j, n)
                               : i == n   ? &side_point(points[side_u1], edges[side_u1], j, n)
                                          : nullptr;
            ids[size_t(j) * (n + 1) + i] = border ? builder.vertex(*border, u, v, true) : builder.vertex(u, v);
        }
    piece.indices.reserve(size_t(6) * n * n);
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) {
            const size_t k = size_t(j) * (n + 1) + i;
            builder.quad(ids[k], ids[k + 1], ids[k + n + 2], ids[k + n + 1], (i + 0.5) / n, (j + 0.5) / n);
        }
    return piece;
}

// Inner grid lines us[1..nu-1] and vs[1..nv-1], edge vertices from each edge's own
// segment count, a ring stitching the two; a collapsed edge is a fan with one apex vertex per
// triangle, at the (u, v) that interpolates best.
Piece build_adaptive(const BezierPatch &patch, const Edge edges[4], const uint32_t segments[4],
                     const std::vector<double> &us, const std::vector<double> &vs) {
    Piece piece;
    PieceBuilder builder(patch, piece);
    const uint32_t nu = uint32_t(us.size() - 1), nv = uint32_t(vs.size() - 1);
    const auto u_at = [&](uint32_t i) { return us[i]; };
    const auto v_at = [&](uint32_t j) { return vs[j]; };

    const uint32_t c00 = builder.vertex(patch.at(0, 0), 0, 0, true);
    const uint32_t c10 = builder.vertex(patch.at(0, 3), 1, 0, true);
    const uint32_t c11 = builder.vertex(patch.at(3, 3), 1, 1, true);
    const uint32_t c01 = builder.vertex(patch.at(3, 0), 0, 1, true);
    const uint32_t side_start[4] = {c00, c10, c01, c00}, side_end[4] = {c10, c11, c11, c01};

    std::vector<uint32_t> inner((nu - 1) * size_t(nv - 1));
    const auto inner_id = [&](uint32_t i, uint32_t j) -> uint32_t & { return inner[(j - 1) * size_t(nu - 1) + (i - 1)]; };
    for (uint32_t j = 1; j < nv; ++j)
        for (uint32_t i = 1; i < nu; ++i) inner_id(i, j) = builder.vertex(u_at(i), v_at(j));
    for (uint32_t j = 1; j + 1 < nv; ++j)
        for (uint32_t i = 1; i + 1 < nu; ++i)
            builder.quad(inner_id(i, j), inner_id(i + 1, j), inner_id(i + 1, j + 1), inner_id(i, j + 1),
                         (u_at(i) + u_at(i + 1)) / 2, (v_at(j) + v_at(j + 1)) / 2);

    for (int s = 0; s < 4; ++s) {
        const bool along_u = s == side_v0 || s == side_v1;
        const double fixed = s == side_v0 || s == side_u0 ? 0.0 : 1.0;
        // The inner row or column next to this side.
        std::vector<uint32_t> row;
        std::vector<double> row_t;
        if (along_u) {
            const uint32_t j = s == side_v0 ? 1 : nv - 1;
            for (uint32_t i = 1; i < nu; ++i) {
                row.push_back(inner_id(i, j));
                row_t.push_back(u_at(i));
            }
        } else {
            const uint32_t i = s == side_u0 ? 1 : nu - 1;
            for (uint32_t j = 1; j < nv; ++j) {
                row.push_back(inner_id(i, j));
                row_t.push_back(v_at(j));
            }
        }
        const Edge &e = edges[s];
        if (e.collapsed) {
            for (size_t k = 0; k + 1 < row.size(); ++k) {
                const double t = (row_t[k] + row_t[k + 1]) / 2;
                const uint32_t apex = along_u ? builder.vertex(e.c[0], t, fixed, true)
                                              : builder.vertex(e.c[0], fixed, t, true);
                builder.triangle(apex, row[k], row[k + 1]);
            }
            continue;
        }
        const uint32_t n = segments[s];
        const std::vector<Vec3> points = edge_points(e, n);
        std::vector<uint32_t> outer{side_start[s]};
        std::vector<double> outer_t{0.0};
        for (uint32_t m = 1; m < n; ++m) {
            const double t = double(m) / n;
            outer.push_back(along_u ? builder.vertex(side_point(points, e, m, n), t, fixed, true)
                                    : builder.vertex(side_point(points, e, m, n), fixed, t, true));
            outer_t.push_back(t);
        }
        outer.push_back(side_end[s]);
        outer_t.push_back(1.0);
        builder.stitch(outer, outer_t, row, row_t);
    }
    return piece;
}

// ---- Measuring ---------------------------------------------------------------------------

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
                edge[k] = u == 0 ? patch_.at(k, 0) : u == 1 ? patch_.at(k, 3) : v == 0 ? patch_.at(0, k) : patch_.at(3, k);
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

void measure(const BezierPatch &patch, Piece &piece, double focus) {
    piece.deviation = measure_deviation(patch, piece.positions, piece.uvs, piece.indices.data(),
                                        piece.triangle_count(), focus);
}

// ---- Assembling --------------------------------------------------------------------------

struct PositionKey {
    double x, y, z;
    bool operator==(const PositionKey &o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PositionHash {
    size_t operator()(const PositionKey &k) const {
        uint64_t h = 0xcbf29ce484222325ull;
        for (double d : {k.x, k.y, k.z}) {
            uint64_t bits;
            std::memcpy(&bits, &d, sizeof bits);
            h = (h ^ bits) * 0x100000001b3ull;
            h ^= h >> 29;
        }
        return size_t(h);
    }
};

PatchMesh assemble(std::vector<Piece> &pieces) {
    PatchMesh mesh;
    size_t vertices = 0, triangles = 0;
    for (const Piece &piece : pieces) {
        vertices += piece.uvs.size() / 2;
        triangles += piece.triangle_count();
    }
    if (vertices >= 0xFFFFFFFFu) over_budget(double(triangles));
    mesh.positions.reserve(3 * vertices);
    mesh.normals.reserve(3 * vertices);
    mesh.uvs.reserve(2 * vertices);
    mesh.welded.reserve(vertices);
    mesh.indices.reserve(3 * triangles);
    mesh.triangle_patch.reserve(triangles);
    // Only border vertices can coincide with another patch's; the rest get ids of their own.
    std::unordered_map<PositionKey, uint32_t, PositionHash> border_ids;
    uint32_t next_id = 0;
    for (size_t p = 0; p < pieces.size(); ++p) {
        Piece &piece = pieces[p];
        const uint32_t base = uint32_t(mesh.uvs.size() / 2);
        for (size_t v = 0; v < piece.on_border.size(); ++v) {
            if (piece.on_border[v]) {
                // + 0.0 turns -0 into +0, which compares equal but hashes differently.
                const PositionKey key{piece.positions[3 * v] + 0.0, piece.positions[3 * v + 1] + 0.0,
                                      piece.positions[3 * v + 2] + 0.0};
                const auto inserted = border_ids.emplace(key, next_id);
                if (inserted.second) ++next_id;
                mesh.welded.push_back(inserted.first->second);
            } else {
                mesh.welded.push_back(next_id++);
            }
        }
        mesh.positions.insert(mesh.positions.end(), piece.positions.begin(), piece.positions.end());
        mesh.normals.insert(mesh.normals.end(), piece.normals.begin(), piece.normals.end());
        mesh.uvs.insert(mesh.uvs.end(), piece.uvs.begin(), piece.uvs.end());
        for (uint32_t index : piece.indices) mesh.indices.push_back(base + index);
        mesh.triangle_patch.insert(mesh.triangle_patch.end(), piece.triangle_count(), uint32_t(p));
        mesh.max_deviation = std::max(mesh.max_deviation, piece.deviation);
        piece = Piece(); // release as we go: the mesh may be large
    }
    mesh.welded_count = next_id;
    return mesh;
}

template <class Body> void for_each_patch(size_t count, Body &&body) {
    tbb::parallel_for(size_t(0), count, [&](size_t p) { body(p); });
}

} // namespace

double measure_deviation(const BezierPatch &patch, const std::vector<double> &positions,
                         const std::vector<double> &uvs, const uint32_t *indices,
                         size_t triangle_count, double focus) {
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

PatchMesh tessellate_uniform(const std::vector<BezierPatch> &patches, uint32_t grid) {
    const double triangles = 2.0 * grid * grid * double(patches.size());
    if (triangles > max_tessellation_triangles) over_budget(triangles);
    std::vector<Piece> pieces(patches.size());
    for_each_patch(patches.size(), [&](size_t p) {
        pieces[p] = build_grid(patches[p], grid);
        measure(patches[p], pieces[p], std::numeric_limits<double>::infinity());
    });
    return assemble(pieces);
}

PatchMesh tessellate_adaptive(const std::vector<BezierPatch> &patches, double tolerance) {
    const double accept = accept_share * tolerance;
    const size_t count = patches.size();
    std::vector<std::array<Edge, 4>> edges(count);
    std::vector<std::array<uint32_t, 4>> segments(count);
    std::vector<PatchModel> models(count);
    std::vector<double> sigma(count, 1.0); // measured error / model error, learnt per patch
    std::vector<GridCounts> grids(count);
    std::vector<char> dirty(count, 1);
    // Counts for the interiors first: they refuse absurd tolerances cheaply, before the edges'
    // searches measure anything.
    for_each_patch(count, [&](size_t p) {
        models[p] = make_model(patches[p]);
        grids[p] = choose_counts(models[p], accept);
    });
    const auto check_budget = [&] {
        double triangles = 0;
        for (size_t p = 0; p < count; ++p) triangles += patch_triangles(grids[p], segments[p].data());
        if (triangles > max_tessellation_triangles) over_budget(triangles);
    };
    check_budget();
    for_each_patch(count, [&](size_t p) {
        for (int s = 0; s < 4; ++s) {
            edges[p][s] = patch_edge(patches[p], s);
            segments[p][s] = edge_segments(edges[p][s], edge_share * accept);
        }
    });
    check_budget();

    std::vector<Piece> pieces(count);
    for (int round = 0;; ++round) {
        for_each_patch(count, [&](size_t p) {
            if (!dirty[p]) return;
            pieces[p] = build_adaptive(patches[p], edges[p].data(), segments[p].data(),
                                       place_lines(models[p].density_u, grids[p].nu),
                                       place_lines(models[p].density_v, grids[p].nv));
            measure(patches[p], pieces[p], accept);
        });
        bool all_pass = true;
        for (size_t p = 0; p < count; ++p) {
            dirty[p] = pieces[p].deviation > accept;
            if (!dirty[p]) continue;
            all_pass = false;
            if (round == max_refinements)
                fail(PPM_ERROR_UNSUPPORTED,
                     "patch " + std::to_string(p) + " still deviates by " + format_number(pieces[p].deviation) +
                         " after " + std::to_string(round) + " refinements for tolerance " + format_number(tolerance) +
                         ": the tolerance is below what double precision resolves on it, or the patch folds so "
                         "sharply that the nearest-point search stalls");
            // The error falls with the square of the cell size: aim just below the measurement.
            sigma[p] *= std::max(1.02, 1.02 * pieces[p].deviation / accept);
            GridCounts next = choose_counts(models[p], accept / sigma[p]);
            // A flat patch's model predicts no error at all; the ring must be what fails.
            if (next == grids[p])
                next = {uint32_t(std::ceil(grids[p].nu * 1.25)), uint32_t(std::ceil(grids[p].nv * 1.25))};
            grids[p] = next;
        }
        if (all_pass) break;
        check_budget();
    }
    return assemble(pieces);
}

} // namespace ppm
