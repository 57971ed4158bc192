// SPDX-License-Identifier: Apache-2.0
#include "scene/cylinder_geometry.h"

#include "core/error.h"
#include "scene/user_geometry.h"

#include <cfloat>
#include <cmath>
#include <utility>

namespace ppm {

namespace {

// |o_perp + t d_perp|^2 = r^2 with the components across the axis, roots in the
// cancellation-free form (as the sphere's, Haines et al.), each kept when its height along the
// axis lies in [0, height]: an open tube, so the far root counts when the near one misses.
bool test_cylinder(const CylinderGeometry::Data &c, unsigned, RayQuery &query) {
    const Vec3 &w = c.frame_axis.n;
    const Vec3 o = query.org - c.p0;
    const double oz = dot(o, w), dz = dot(query.dir, w);
    const Vec3 op = o - w * oz, dp = query.dir - w * dz;
    const double a = dot(dp, dp);
    if (!(a > 0)) return false; // parallel to the axis: only the rim's measure-zero line
    const double b = dot(op, dp), cc = dot(op, op) - c.radius * c.radius;
    const Vec3 l = op - dp * (b / a);
    const double disc = a * (c.radius * c.radius - dot(l, l));
    if (!(disc >= 0)) return false;
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    double t0 = q / a, t1 = q != 0 ? cc / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    for (double t : {t0, t1}) {
        if (!(t >= query.tnear && t <= query.hit.t)) continue;
        const double z = oz + dz * t;
        if (!(z >= 0 && z <= c.height)) continue;
        query.record(t, 0, 0, 0);
        return true;
    }
    return false;
}

void cylinder_bounds(const RTCBoundsFunctionArguments *args) {
    const auto &c = *static_cast<const CylinderGeometry::Data *>(args->geometryUserPtr);
    write_embree_bounds(c.box, c.frame, *args->bounds_o);
}

// Box of the tube: each end's circle extends sqrt(1 - w_i^2) r along axis i.
Box3 tube_box(const Vec3 &p0, const Vec3 &p1, double radius) {
    const Vec3 w = normalize(p1 - p0);
    const Vec3 half = Vec3{std::sqrt(std::max(0.0, 1 - w.x * w.x)), std::sqrt(std::max(0.0, 1 - w.y * w.y)),
                           std::sqrt(std::max(0.0, 1 - w.z * w.z))} *
                      radius;
    Box3 box;
    for (const Vec3 &p : {p0, p1}) {
        box.extend(p - half);
        box.extend(p + half);
    }
    return box;
}

} // namespace

CylinderGeometry::CylinderGeometry(const Vec3 &p0, const Vec3 &p1, double radius)
    : source_p0_(p0), source_p1_(p1), source_radius_(radius) {}

void CylinderGeometry::check_transform(const Affine &transform) const {
    const Vec3 x = transform.vector({1, 0, 0}), y = transform.vector({0, 1, 0}), z = transform.vector({0, 0, 1});
    const double lx = length(x), ly = length(y), lz = length(z);
    const double tolerance = 1e-9 * std::max({lx, ly, lz});
    if (std::fabs(lx - ly) > tolerance || std::fabs(lx - lz) > tolerance || std::fabs(dot(x, y)) > tolerance * lx ||
        std::fabs(dot(y, z)) > tolerance * ly || std::fabs(dot(x, z)) > tolerance * lx)
        invalid_argument("a cylinder takes only rotations, translations and uniform scaling");
}

Box3 CylinderGeometry::world_bounds(const Affine &transform) const {
    return tube_box(transform.point(source_p0_), transform.point(source_p1_),
                    source_radius_ * length(transform.vector({1, 0, 0})));
}

Box3 CylinderGeometry::prepare(const Affine &transform) {
    Data &c = data_;
    c.p0 = transform.point(source_p0_);
    c.p1 = transform.point(source_p1_);
    c.radius = source_radius_ * length(transform.vector({1, 0, 0}));
    c.height = length(c.p1 - c.p0);
    c.frame_axis = Frame::from_normal((c.p1 - c.p0) / c.height);
    c.box = tube_box(c.p0, c.p1, c.radius);
    c.rounding = 32 * DBL_EPSILON * std::max(max_abs_component(c.box.lower), max_abs_component(c.box.upper));
    return c.box;
}

RTCGeometry CylinderGeometry::create_embree(RTCDevice device, const EmbreeFrame &frame) {
    data_.frame = frame;
    return new_user_geometry<Data, test_cylinder>(device, data_, 1, cylinder_bounds);
}

void CylinderGeometry::describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const {
    const Data &c = data_;
    const Vec3 along = query.org + query.dir * query.hit.t - c.p0;
    const double z = std::clamp(dot(along, c.frame_axis.n), 0.0, c.height);
    const double x = dot(along, c.frame_axis.s), y = dot(along, c.frame_axis.t);
    const double r = std::sqrt(x * x + y * y);
    const Vec3 n = r > 0 ? (c.frame_axis.s * x + c.frame_axis.t * y) / r : c.frame_axis.s;
    const Vec3 p = c.p0 + c.frame_axis.n * z + n * c.radius; // back onto the tube
    p.store(hit.p);
    n.store(hit.ng);
    n.store(hit.ns);
    hit.p_error = tolerance + c.rounding;
    double phi = std::atan2(y, x);
    if (phi < 0) phi += 2 * M_PI;
    hit.u = phi / (2 * M_PI);
    hit.v = z / c.height;
}

} // namespace ppm
