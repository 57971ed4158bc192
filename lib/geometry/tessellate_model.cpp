// SPDX-License-Identifier: Apache-2.0
#include "geometry/tessellate_model.h"

#include "geometry/tessellate.h"
#include "geometry/tessellate_budget.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ppm {
namespace tess {

namespace {

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

} // namespace

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

std::vector<double> place_lines(const std::vector<double> &density, uint32_t n) {
    const size_t intervals = density.size() - 1;
    std::vector<double> cumulative(intervals + 1, 0.0);
    for (size_t k = 0; k < intervals; ++k) cumulative[k + 1] = cumulative[k] + std::max(density[k], density[k + 1]);
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

double patch_triangles(const GridCounts &g, const uint32_t segments[4]) {
    const double nu = g.nu, nv = g.nv;
    return 2 * (nu - 2) * (nv - 2) + 2 * (nu - 2) + 2 * (nv - 2) + segments[0] + segments[1] + segments[2] +
           segments[3];
}

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

} // namespace tess
} // namespace ppm
