// SPDX-License-Identifier: Apache-2.0
// The tessellation's two entry points: each patch's piece built and measured in parallel,
// refined where it fails, then assembled.
#include "geometry/tessellate.h"

#include "core/error.h"
#include "geometry/tessellate_assemble.h"
#include "geometry/tessellate_budget.h"
#include "geometry/tessellate_edge.h"
#include "geometry/tessellate_model.h"
#include "geometry/tessellate_piece.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace ppm {

using namespace tess;

namespace {

// A measured deviation must stay below this share of the tolerance: the measured maximum of a
// triangle (on a lattice of step 1/32) lies within about 0.1% of the true one.
constexpr double accept_share = 0.997;
// Edge chords get this share of the tolerance, leaving room for the ring triangles beside them
// (whose error adds the surface's bending away from the edge).
constexpr double edge_share = 0.6;
// Rounds of refinement before a tolerance is given up as unreachable: each round aims just
// below the last measurement, so a reachable tolerance is met within a few.
constexpr int max_refinements = 16;

template <class Body> void for_each_patch(size_t count, Body &&body) {
    tbb::parallel_for(size_t(0), count, [&](size_t p) { body(p); });
}

void measure(const BezierPatch &patch, Piece &piece, double focus) {
    piece.deviation =
        measure_deviation(patch, piece.positions, piece.uvs, piece.indices.data(), piece.triangle_count(), focus);
}

} // namespace

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
