// SPDX-License-Identifier: Apache-2.0
// A triangle mesh as plain data: what a mesh reader produces and a mesh geometry keeps.
#pragma once

#include "math/vec3.h"

#include <cstdint>
#include <vector>

namespace ppm {

struct MeshData {
    std::vector<Vec3> positions;
    std::vector<uint32_t> indices; // 3 per triangle
    std::vector<Vec3> normals;     // empty or one per vertex
    std::vector<double> uvs;       // empty or two per vertex
};

} // namespace ppm
