// SPDX-License-Identifier: Apache-2.0
#include "scene/disk_geometry.h"

#include "scene/user_geometry.h"

#include <cfloat>
#include <cmath>

namespace ppm {

namespace {

// The disk's plane as the quad's (quad_geometry.cpp), then the local coordinates (x, y) of
// the plane point from the Gram matrix of the axes; a hit when x^2 + y^2 <= 1. The query
// keeps (x, y) as its (u, v) until describe_hit.
bool test_disk(const DiskGeometry::Data &d, unsigned, RayQuery &query) {
    if (query.origin.geom_id == query.tested_geom_id && query.tnear >= 0) return false;
    const double denominator = dot(query.dir, d.normal);
    if (denominator == 0) return false;
    const double t = dot(d.center - query.org, d.normal) / denominator;
    if (!(t >= query.tnear && t <= query.hit.t)) return false;
    const Vec3 w = query.org + query.dir * t - d.center;
    const double wu = dot(w, d.axis_u), wv = dot(w, d.axis_v);
    const double x = (wu * d.vv - wv * d.uv) / d.det;
    const double y = (wv * d.uu - wu * d.uv) / d.det;
    if (!(x * x + y * y <= 1)) return false;
    query.record(t, x, y, 0);
    return true;
}

void disk_bounds(const RTCBoundsFunctionArguments *args) {
    const auto &d = *static_cast<const DiskGeometry::Data *>(args->geometryUserPtr);
    write_embree_bounds(d.box, d.frame, *args->bounds_o);
}

// Box of an ellipse: along each axis, centre +- sqrt(u_i^2 + v_i^2).
Box3 ellipse_box(const Vec3 &c, const Vec3 &u, const Vec3 &v) {
    const Vec3 half{std::sqrt(u.x * u.x + v.x * v.x), std::sqrt(u.y * u.y + v.y * v.y),
                    std::sqrt(u.z * u.z + v.z * v.z)};
    Box3 box;
    box.extend(c - half);
    box.extend(c + half);
    return box;
}

} // namespace

DiskGeometry::DiskGeometry(const Vec3 &center, const Vec3 &axis_u, const Vec3 &axis_v)
    : source_{center, axis_u, axis_v} {}

Box3 DiskGeometry::world_bounds(const Affine &transform) const {
    return ellipse_box(transform.point(source_[0]), transform.vector(source_[1]), transform.vector(source_[2]));
}

Box3 DiskGeometry::prepare(const Affine &transform) {
    Data &d = data_;
    d.center = transform.point(source_[0]);
    d.axis_u = transform.vector(source_[1]);
    d.axis_v = transform.vector(source_[2]);
    d.normal = cross(d.axis_u, d.axis_v);
    d.uu = dot(d.axis_u, d.axis_u);
    d.uv = dot(d.axis_u, d.axis_v);
    d.vv = dot(d.axis_v, d.axis_v);
    d.det = d.uu * d.vv - d.uv * d.uv;
    d.box = ellipse_box(d.center, d.axis_u, d.axis_v);
    d.unit_normal = normalize(d.normal);
    d.rounding = 32 * DBL_EPSILON * std::max(max_abs_component(d.box.lower), max_abs_component(d.box.upper));
    return d.box;
}

RTCGeometry DiskGeometry::create_embree(RTCDevice device, const EmbreeFrame &frame) {
    data_.frame = frame;
    return new_user_geometry<Data, test_disk>(device, data_, 1, disk_bounds);
}

void DiskGeometry::describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const {
    const double x = query.hit.u, y = query.hit.v;
    const Vec3 p = data_.center + data_.axis_u * x + data_.axis_v * y;
    p.store(hit.p);
    data_.unit_normal.store(hit.ng);
    data_.unit_normal.store(hit.ns);
    hit.p_error = tolerance + data_.rounding;
    double phi = std::atan2(y, x);
    if (phi < 0) phi += 2 * M_PI;
    hit.u = std::sqrt(x * x + y * y);
    hit.v = phi / (2 * M_PI);
}

} // namespace ppm
