// Uniform tessellation of bicubic Bezier patches into triangles: the mesh baselines of the
// benchmark. (A library API for this will come; until then it lives with the tool.)
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bench {

// Each patch becomes an (n+1) x (n+1) grid of vertices at (u, v) = (c / n, r / n), vertex
// (r, c) at patch * (n+1)^2 + r * (n+1) + c, and 2 n^2 triangles: cell (r, c) gives triangles
// patch * 2n^2 + (r * n + c) * 2 + {0, 1}. Vertices are not shared between patches.
struct Mesh {
    int n = 0;
    size_t patch_count = 0;
    std::vector<double> positions; // 3 per vertex
    std::vector<uint32_t> indices;  // 3 per triangle

    size_t vertex_count() const { return positions.size() / 3; }
    size_t triangle_count() const { return indices.size() / 3; }
    size_t triangles_per_patch() const { return size_t(2) * n * n; }
};

// `control_points`: 48 doubles per patch, P[i][j] at i * 4 + j; evaluated in double as
// S(u, v) = sum_i B_i(v) sum_j B_j(u) P[i][j]. n in [1, 4096].
Mesh tessellate_patches(const double *control_points, size_t patch_count, int n);

// Patch index and patch parameters (u, v) of the point with barycentric coordinates (b1, b2)
// (Embree's: weights of the triangle's second and third vertex) in triangle `tri`.
void triangle_patch_uv(const Mesh &mesh, size_t tri, double b1, double b2, uint32_t *patch,
                       double *u, double *v);

} // namespace bench
