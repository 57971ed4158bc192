// SPDX-License-Identifier: Apache-2.0
// Triangle meshes of the patches, made by libppm's ppm_tessellate_patches (uniform grids and
// adaptive tessellations), in the form the mesh baselines consume.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bench {

struct Mesh {
    std::string label;             // "N32" (uniform grid) or "adaptive-1e-4" (relative tolerance)
    int grid = 0;                  // segments per patch edge; 0 for an adaptive mesh
    double relative_tolerance = 0; // adaptive: requested tolerance / diagonal
    double deviation = 0;          // measured max distance from the patches / diagonal
    double seconds = 0;            // wall time of ppm_tessellate_patches
    // Welded, crack-free mesh: distinct positions and triangles indexing them.
    std::vector<double> positions; // 3 per welded vertex
    std::vector<uint32_t> indices; // 3 per triangle, into positions
    // Per triangle corner (3 per triangle): the unit surface normal of that corner's unwelded
    // vertex (its own patch's normal), for the interpolated shading normal of a hit.
    std::vector<float> corner_normal; // 3 per corner
    std::vector<uint32_t> triangle_patch;

    size_t vertex_count() const { return positions.size() / 3; }
    size_t triangle_count() const { return indices.size() / 3; }
    // Bytes of positions + indices as an intersector would keep them in float / uint32.
    size_t float_array_bytes() const { return vertex_count() * 12 + triangle_count() * 12; }
};

// grid > 0: uniform grid x grid quads per patch; grid == 0: adaptive with absolute tolerance
// relative_tolerance * diagonal. Throws with libppm's message on failure.
Mesh tessellate(const std::vector<double> &control_points, int grid, double relative_tolerance, double diagonal);

// Interpolated unit shading normal at barycentric (b1, b2) (weights of the triangle's second
// and third corner, Embree's convention) of triangle `tri`.
void interpolate_normal(const Mesh &mesh, size_t tri, double b1, double b2, float out[3]);

} // namespace bench
