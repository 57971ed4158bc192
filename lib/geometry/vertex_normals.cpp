// SPDX-License-Identifier: Apache-2.0
#include "geometry/vertex_normals.h"

#include "math/warp.h"

#include <cmath>

namespace ppm {

namespace {

// The angle between unit vectors a and b, accurate near 0 and pi as well (Mitsuba's
// unit_angle): 2 asin of half the chord, not acos of the dot product.
double unit_angle(const Vec3 &a, const Vec3 &b) {
    if (dot(a, b) < 0) return kPi - 2.0 * std::asin(0.5 * length(a + b));
    return 2.0 * std::asin(0.5 * length(a - b));
}

} // namespace

std::vector<Vec3> angle_weighted_vertex_normals(const MeshData &mesh) {
    std::vector<Vec3> sums(mesh.positions.size(), Vec3{0, 0, 0});
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t i[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
        const Vec3 p[3] = {mesh.positions[i[0]], mesh.positions[i[1]], mesh.positions[i[2]]};
        const Vec3 n = cross(p[1] - p[0], p[2] - p[0]);
        const double n_length = length(n);
        if (!(n_length > 0)) continue;
        for (int k = 0; k < 3; ++k) {
            const Vec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
            const double a_length = length(a), b_length = length(b);
            if (!(a_length > 0 && b_length > 0)) continue;
            sums[i[k]] += n * (unit_angle(a / a_length, b / b_length) / n_length);
        }
    }
    for (Vec3 &n : sums) {
        const double n_length = length(n);
        n = n_length > 0 ? n / n_length : Vec3{1, 0, 0};
    }
    return sums;
}

} // namespace ppm
