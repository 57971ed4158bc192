// SPDX-License-Identifier: Apache-2.0
#include "scene/sphere_geometry.h"

#include "core/error.h"
#include "scene/user_geometry.h"

#include <cfloat>
#include <cmath>
#include <utility>

namespace ppm {

namespace {

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

// Whether the quadratic surely has no root in [tnear, t_far], decided without a sqrt or
// division:
//  - outside and moving away from the centre: both roots are behind the origin (their
//    product c/a > 0, their sum -2b/a <= 0) and tnear >= 0;
//  - f(t) = a t^2 + 2 b t + c, convex, is negative at both ends of the interval (inside the
//    sphere all along: Hachisuka's room lies inside all six wall spheres, and a ray that has
//    found one wall skips the walls it would leave the sphere through later), or positive at
//    the far end before its vertex (both roots beyond). The margins cover f's rounding.
//    With t_far infinite these comparisons are false (inf or NaN), so nothing is ruled out.
// abs_b = |b|.
inline bool sphere_ruled_out(double b, double abs_b, double ff, double r2, double c, double a, double tnear,
                             double t_far) {
    const double far_value = (a * t_far + 2 * b) * t_far + c;
    const double far_margin = 1e-12 * (a * t_far * t_far + 2 * abs_b * t_far + ff + r2);
    const double near_value = (a * tnear + 2 * b) * tnear + c;
    const double near_margin = 1e-12 * (a * tnear * tnear + 2 * abs_b * tnear + ff + r2);
    const bool receding_outside = b >= 0 && c > 4 * DBL_EPSILON * ff;
    const bool roots_beyond = far_value > far_margin && b < -a * t_far;
    const bool inside_all_along = far_value < -far_margin && near_value < -near_margin;
    return receding_outside || roots_beyond || inside_all_along;
}

// Roots of |org + t dir - c|^2 = r^2 in the cancellation-free form of "Precision Improvements
// for Ray/Sphere Intersection" (Haines et al., Ray Tracing Gems, ch. 7). Records a hit with t
// in [query.tnear, query.hit.t] (the nearer root if both are) and returns true.
inline bool test_sphere_terms(const SphereTerms &terms, RayQuery &query) {
    const double b = terms.b, r2 = terms.r2, c = terms.c;
    const double a = query.dir_length2, inv_a = query.inv_dir_length2;
    if (sphere_ruled_out(b, std::fabs(b), terms.ff, r2, c, a, query.tnear, query.hit.t)) return false;
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

bool test_sphere(const SphereGeometry::Data &s, unsigned, RayQuery &query) {
    return test_sphere_terms(sphere_terms(s.center, s.radius, query), query);
}

void sphere_bounds(const RTCBoundsFunctionArguments *args) {
    const auto &s = *static_cast<const SphereGeometry::Data *>(args->geometryUserPtr);
    Box3 box;
    box.extend(s.center - Vec3{1, 1, 1} * s.radius);
    box.extend(s.center + Vec3{1, 1, 1} * s.radius);
    write_embree_bounds(box, s.frame, *args->bounds_o);
}

} // namespace

SphereGeometry::SphereGeometry(const Vec3 &center, double radius) : source_center_(center), source_radius_(radius) {}

void SphereGeometry::check_transform(const Affine &transform) const {
    const Vec3 x = transform.vector({1, 0, 0}), y = transform.vector({0, 1, 0}), z = transform.vector({0, 0, 1});
    const double lx = length(x), ly = length(y), lz = length(z);
    const double tolerance = 1e-9 * std::max({lx, ly, lz});
    if (std::fabs(lx - ly) > tolerance || std::fabs(lx - lz) > tolerance || std::fabs(dot(x, y)) > tolerance * lx ||
        std::fabs(dot(y, z)) > tolerance * ly || std::fabs(dot(x, z)) > tolerance * lx)
        invalid_argument("a sphere takes only rotations, translations and uniform scaling");
}

Box3 SphereGeometry::world_bounds(const Affine &transform) const {
    const Vec3 center = transform.point(source_center_);
    const double radius = source_radius_ * length(transform.vector({1, 0, 0}));
    Box3 box;
    box.extend(center - Vec3{1, 1, 1} * radius);
    box.extend(center + Vec3{1, 1, 1} * radius);
    return box;
}

Box3 SphereGeometry::prepare(const Affine &transform) {
    data_.center = transform.point(source_center_);
    const Vec3 x = transform.vector({1, 0, 0});
    data_.radius = source_radius_ * length(x);
    data_.axis[0] = normalize(x);
    data_.axis[1] = normalize(transform.vector({0, 1, 0}));
    data_.axis[2] = normalize(transform.vector({0, 0, 1}));
    data_.inv_radius = 1 / data_.radius;
    data_.rounding = 32 * DBL_EPSILON * (max_abs_component(data_.center) + data_.radius);
    Box3 box;
    box.extend(data_.center - Vec3{1, 1, 1} * data_.radius);
    box.extend(data_.center + Vec3{1, 1, 1} * data_.radius);
    return box;
}

RTCGeometry SphereGeometry::create_embree(RTCDevice device, const EmbreeFrame &frame) {
    data_.frame = frame;
    return new_user_geometry<Data, test_sphere>(device, data_, 1, sphere_bounds);
}

void SphereGeometry::describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const {
    const Vec3 along = query.org + query.dir * query.hit.t - data_.center;
    const Vec3 n = normalize(along * data_.inv_radius); // nearly unit: no square root (vec3.h)
    const Vec3 p = data_.center + n * data_.radius;     // back onto the sphere
    p.store(hit.p);
    n.store(hit.ng);
    n.store(hit.ns);
    hit.p_error = tolerance + data_.rounding;
}

// Spherical coordinates of the normal in the object's frame: u = phi / 2 pi from its x axis
// towards y, v = theta / pi from its z axis.
void SphereGeometry::compute_uv(ppm_hit &hit) const {
    const Vec3 n = Vec3::from(hit.ng);
    const double lx = dot(n, data_.axis[0]), ly = dot(n, data_.axis[1]), lz = dot(n, data_.axis[2]);
    double phi = std::atan2(ly, lx);
    if (phi < 0) phi += 2 * M_PI;
    hit.u = phi / (2 * M_PI);
    hit.v = std::acos(std::clamp(lz, -1.0, 1.0)) / M_PI;
}

} // namespace ppm
