// SPDX-License-Identifier: Apache-2.0
// Vertex normals for a mesh that has none, as Mitsuba 3 computes them (Mesh::compute_normals,
// after "Computing Vertex Normals from Polygonal Facets", Thuermer and Wuethrich, JGT 1998):
// each triangle adds its unit normal, weighted by its interior angle at the corner, to each
// of its three vertices, and the sums are normalised. Degenerate triangles add nothing; a
// vertex that gets nothing (unused, or only on degenerate triangles) gets (1, 0, 0), as in
// Mitsuba.
#pragma once

#include "geometry/mesh_data.h"

#include <vector>

namespace ppm {

std::vector<Vec3> angle_weighted_vertex_normals(const MeshData &mesh);

} // namespace ppm
