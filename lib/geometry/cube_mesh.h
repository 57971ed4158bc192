// SPDX-License-Identifier: Apache-2.0
// Mitsuba 3's `cube` shape as a triangle mesh: [-1, 1]^3, normals out of its six faces, and
// every face mapped onto [0, 1]^2 in uv with the same corners as Mitsuba's, so that a
// textured cube looks the same in both renderers.
#pragma once

#include "geometry/mesh_data.h"

namespace ppm {

// 24 vertices (4 per face, with the face's normal) and 12 triangles.
MeshData cube_mesh();

} // namespace ppm
