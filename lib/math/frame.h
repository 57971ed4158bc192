// SPDX-License-Identifier: Apache-2.0
// Orthonormal shading frame: local coordinates have z along the normal, as the BSDFs expect.
#pragma once

#include "math/vec3.h"

namespace ppm {

struct Frame {
    Vec3 s{1, 0, 0}, t{0, 1, 0}, n{0, 0, 1};

    // n must be unit length; the tangents follow orthonormal_basis (Duff et al. 2017).
    static Frame from_normal(const Vec3 &n) {
        Frame f;
        f.n = n;
        orthonormal_basis(n, f.s, f.t);
        return f;
    }
    Vec3 to_local(const Vec3 &v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    Vec3 to_world(const Vec3 &v) const { return s * v.x + t * v.y + n * v.z; }
};

} // namespace ppm
