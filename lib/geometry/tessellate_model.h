// SPDX-License-Identifier: Apache-2.0
// The error model for a patch's interior grid: the surface's bending sampled over the patch,
// the grid lines placed by it, and the grid counts whose predicted deviation meets a target.
#pragma once

#include "geometry/bezier.h"

#include <cstdint>
#include <vector>

namespace ppm {
namespace tess {

// Samples per direction of the curvature that drives the per-patch grid counts.
constexpr int curvature_samples = 25;

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

PatchModel make_model(const BezierPatch &patch);

// Lines 0 = t_0 < ... < t_n = 1 with equal integrals of the density between neighbours (the
// density taken constant between samples, at the larger of its two ends).
std::vector<double> place_lines(const std::vector<double> &density, uint32_t n);

struct GridCounts {
    uint32_t nu = 2, nv = 2;
    bool operator==(const GridCounts &o) const { return nu == o.nu && nv == o.nv; }
};

// Triangles of a patch: inner cells, and the ring (one per edge segment and per inner segment).
double patch_triangles(const GridCounts &g, const uint32_t segments[4]);

// The counts (at least 2 each, so that an inner grid exists) with the fewest cells whose
// model error is within target. The cost (nu - 1)(nv - 1) is flat near its minimum, so nu
// steps geometrically by 1% and the walk stops once the cost has clearly passed its minimum.
GridCounts choose_counts(const PatchModel &m, double target);

} // namespace tess
} // namespace ppm
