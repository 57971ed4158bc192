// The exact double-precision ray/sphere test shared by SphereGeometry (Embree's callbacks)
// and SphereSet (the huge spheres tested outside the BVH).
#pragma once

#include "scene/ray_query.h"

#include <cfloat>
#include <cmath>
#include <utility>

namespace ppm {

// The ray's terms for one sphere: the quadratic |org + t dir - centre|^2 - r^2 =
// a t^2 + 2 b t + c with a = |dir|^2, and |f|^2 for error bounds.
struct SphereTerms {
    Vec3 f; // org - centre
    double b, ff, r2, c;
};

inline SphereTerms sphere_terms(const Vec3 &center, double radius, const RayQuery &query) {
    SphereTerms t;
    t.f = query.org - center;
    t.b = dot(t.f, query.dir);
    t.ff = dot(t.f, t.f);
    t.r2 = radius * radius;
    t.c = t.ff - t.r2;
    return t;
}

// Outside the sphere (beyond the rounding of c): then both roots have the sign of -b.
inline bool surely_outside(double c, double ff) { return c > 4 * DBL_EPSILON * ff; }

// Whether the quadratic may have a root in [query.tnear, query.hit.t], decided without a sqrt
// or division; false only when it surely has none:
//  - outside and moving away from the centre: both roots are behind the origin (their
//    product c/a > 0, their sum -2b/a <= 0) and tnear >= 0;
//  - f(t) = a t^2 + 2 b t + c, convex, is negative at both ends of the interval (inside the
//    sphere all along: Hachisuka's room lies inside all six wall spheres, and a ray that has
//    found one wall skips the walls it would leave the sphere through later), or positive at
//    the far end before its vertex (both roots beyond). The margins cover f's rounding.
//    With hit.t infinite these comparisons are false (inf or NaN), so nothing is skipped.
// Written without branches so that SphereSet runs it on all its spheres in SIMD lanes.
inline bool sphere_may_hit(double b, double ff, double r2, double c, double a, double tnear, double t_far) {
    const double far_value = (a * t_far + 2 * b) * t_far + c;
    const double far_margin = 1e-12 * (a * t_far * t_far + 2 * std::fabs(b) * t_far + ff + r2);
    const double near_value = (a * tnear + 2 * b) * tnear + c;
    const double near_margin = 1e-12 * (a * tnear * tnear + 2 * std::fabs(b) * tnear + ff + r2);
    const bool receding_outside = (b >= 0) & surely_outside(c, ff);
    const bool roots_beyond = (far_value > far_margin) & (b < -a * t_far);
    const bool inside_all_along = (far_value < -far_margin) & (near_value < -near_margin);
    return !(receding_outside | roots_beyond | inside_all_along);
}

// Roots of |org + t dir - c|^2 = r^2 in the cancellation-free form of "Precision Improvements
// for Ray/Sphere Intersection" (Haines et al., Ray Tracing Gems, ch. 7). Records a hit with t
// in [query.tnear, query.hit.t] (the nearer root if both are) and returns true.
inline bool test_sphere_terms(const SphereTerms &terms, RayQuery &query) {
    const double b = terms.b, r2 = terms.r2, c = terms.c;
    const double a = query.dir_length2, inv_a = query.inv_dir_length2;
    if (!sphere_may_hit(b, terms.ff, r2, c, a, query.tnear, query.hit.t)) return false;
    const Vec3 l = terms.f - query.dir * (b * inv_a);
    const double disc = a * (r2 - dot(l, l));
    if (!(disc >= 0)) return false;
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    double t0 = q * inv_a, t1 = q != 0 ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    for (double t : {t0, t1})
        if (t >= query.tnear && t <= query.hit.t) {
            query.record(t, 0, 0, 0);
            return true;
        }
    return false;
}

} // namespace ppm
