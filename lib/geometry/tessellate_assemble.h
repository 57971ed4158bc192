// SPDX-License-Identifier: Apache-2.0
// Joins the patches' pieces into one mesh, giving border vertices at one position one welded
// index.
#pragma once

#include "geometry/tessellate.h"
#include "geometry/tessellate_piece.h"

#include <vector>

namespace ppm {
namespace tess {

// The pieces in patch order; each is released once copied (the mesh may be large).
PatchMesh assemble(std::vector<Piece> &pieces);

} // namespace tess
} // namespace ppm
