#include "tessellate.h"

#include <stdexcept>

namespace bench {

namespace {

void bernstein3(double t, double b[4]) {
    const double s = 1.0 - t;
    b[0] = s * s * s;
    b[1] = 3.0 * t * s * s;
    b[2] = 3.0 * t * t * s;
    b[3] = t * t * t;
}

// The vertex index of grid point (r, c) of `patch`.
uint32_t grid_vertex(size_t patch, int n, int r, int c) {
    return static_cast<uint32_t>(patch * (n + 1) * (n + 1) + size_t(r) * (n + 1) + c);
}

} // namespace

Mesh tessellate_patches(const double *control_points, size_t patch_count, int n) {
    if (n < 1 || n > 4096) throw std::invalid_argument("tessellation: n must be in [1, 4096]");
    const size_t vertices = patch_count * (n + 1) * (n + 1);
    if (vertices > 0xFFFFFFFFu) throw std::invalid_argument("tessellation: too many vertices");
    Mesh mesh;
    mesh.n = n;
    mesh.patch_count = patch_count;
    mesh.positions.reserve(vertices * 3);
    mesh.indices.reserve(patch_count * mesh.triangles_per_patch() * 3);

    for (size_t p = 0; p < patch_count; ++p) {
        const double *P = control_points + p * 48;
        for (int r = 0; r <= n; ++r) {
            double bv[4];
            bernstein3(double(r) / n, bv);
            for (int c = 0; c <= n; ++c) {
                double bu[4];
                bernstein3(double(c) / n, bu);
                // Row sums first, then across rows: at v = 0 or 1 the zero weights add exact
                // zeros, so patches sharing an edge get bit-identical edge vertices.
                double s[3] = {0, 0, 0};
                for (int i = 0; i < 4; ++i) {
                    double row[3] = {0, 0, 0};
                    for (int j = 0; j < 4; ++j)
                        for (int k = 0; k < 3; ++k) row[k] += bu[j] * P[(i * 4 + j) * 3 + k];
                    for (int k = 0; k < 3; ++k) s[k] += bv[i] * row[k];
                }
                mesh.positions.insert(mesh.positions.end(), s, s + 3);
            }
        }
        for (int r = 0; r < n; ++r) {
            for (int c = 0; c < n; ++c) {
                const uint32_t a = grid_vertex(p, n, r, c), b = grid_vertex(p, n, r, c + 1);
                const uint32_t d = grid_vertex(p, n, r + 1, c), e = grid_vertex(p, n, r + 1, c + 1);
                mesh.indices.insert(mesh.indices.end(), {a, b, e});
                mesh.indices.insert(mesh.indices.end(), {a, e, d});
            }
        }
    }
    return mesh;
}

void triangle_patch_uv(const Mesh &mesh, size_t tri, double b1, double b2, uint32_t *patch,
                       double *u, double *v) {
    const size_t per_patch = mesh.triangles_per_patch();
    *patch = static_cast<uint32_t>(tri / per_patch);
    const size_t local = tri % per_patch;
    const int cell = static_cast<int>(local / 2), n = mesh.n;
    const int r = cell / n, c = cell % n;
    // Grid offsets (du, dv) of the triangle's three vertices, in the order of tessellate.
    static const int first[3][2] = {{0, 0}, {1, 0}, {1, 1}};
    static const int second[3][2] = {{0, 0}, {1, 1}, {0, 1}};
    const int(*corner)[2] = (local % 2 == 0) ? first : second;
    const double b0 = 1.0 - b1 - b2;
    *u = (c + b0 * corner[0][0] + b1 * corner[1][0] + b2 * corner[2][0]) / n;
    *v = (r + b0 * corner[0][1] + b1 * corner[1][1] + b2 * corner[2][1]) / n;
}

} // namespace bench
