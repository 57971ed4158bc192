// SPDX-License-Identifier: Apache-2.0
// Where a patch model is special: shared edges (seams), corners shared by several patches,
// and edges collapsed to a point (poles). Found by exact comparison of control points, as
// patches that join without cracks share them bit for bit.
#pragma once

#include "reference_intersector.h"

#include <vector>

namespace bench {

// Edge e of a patch: 0: v = 0 (row 0), 1: v = 1 (row 3), 2: u = 0 (column 0), 3: u = 1
// (column 3), each in the order of its running parameter.
struct Seam {
    int patch_a, edge_a, patch_b, edge_b;
    bool reversed; // the edges run in opposite directions
};

struct Corner {
    ref::real point[3];
    int patches;         // patches having a corner control point here
    bool has_normal;     // whether the mean of their unit normals there is defined
    ref::real normal[3]; // that mean (sign-aligned), normalised
};

struct CollapsedPoint {
    ref::real point[3];
};

// (u, v) of edge e at running parameter s.
void edge_parameter(int e, ref::real s, ref::real &u, ref::real &v);

// Pairs of patches sharing an edge (its four control points equal, either way round);
// collapsed edges are not seams.
std::vector<Seam> find_seams(const std::vector<ref::Patch> &patches);

// Corner points shared by at least `min_patches` patches.
std::vector<Corner> find_corners(const std::vector<ref::Patch> &patches, int min_patches);

// Distinct points to which a patch edge collapses (four equal control points).
std::vector<CollapsedPoint> find_collapsed_points(const std::vector<ref::Patch> &patches);

} // namespace bench
