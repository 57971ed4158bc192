// SPDX-License-Identifier: Apache-2.0
// Rays leaving a surface: the one rule shared by ppm_hit_spawn_ray and the renderer.
#pragma once

#include <ppm/ppm.h>

#include "math/vec3.h"

#include <cmath>

namespace ppm {

// A ray from hit.p in direction dir whose origin is moved off the surface by twice the hit's
// error bound along ng, on the side dir points to, so it cannot hit the surface it leaves.
inline ppm_ray spawn_ray(const Vec3 &p, const Vec3 &ng, double p_error, const Vec3 &dir, double tfar = INFINITY) {
    const double side = dot(dir, ng) >= 0 ? 1.0 : -1.0;
    const Vec3 org = p + ng * (2 * p_error * side);
    ppm_ray ray;
    org.store(ray.org);
    dir.store(ray.dir);
    ray.tnear = 0;
    ray.tfar = tfar;
    return ray;
}
inline ppm_ray spawn_ray(const ppm_hit &hit, const Vec3 &dir, double tfar = INFINITY) {
    return spawn_ray(Vec3::from(hit.p), Vec3::from(hit.ng), hit.p_error, dir, tfar);
}

} // namespace ppm
