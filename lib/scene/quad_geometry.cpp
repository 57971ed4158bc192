// SPDX-License-Identifier: Apache-2.0
#include "scene/quad_geometry.h"

#include "scene/user_geometry.h"

#include <cfloat>

namespace ppm {

namespace {

bool test_quad(const QuadGeometry::Data &q, unsigned, RayQuery &query) {
    // A ray spawned from this quad starts off its plane, past the hit's error bound, on the
    // side it travels to (spawn_ray): it meets the plane only behind its origin.
    if (query.origin.geom_id == query.tested_geom_id && query.tnear >= 0) return false;
    const double denominator = dot(query.dir, q.normal);
    if (denominator == 0) return false; // parallel: a two-sided quad has no area to hit
    const double t = dot(q.origin - query.org, q.normal) / denominator;
    if (!(t >= query.tnear && t <= query.hit.t)) return false;
    const Vec3 w = query.org + query.dir * t - q.origin;
    const double wu = dot(w, q.edge_u), wv = dot(w, q.edge_v);
    const double s = (wu * q.vv - wv * q.uv) / q.det;
    const double r = (wv * q.uu - wu * q.uv) / q.det;
    if (!(s >= 0 && s <= 1 && r >= 0 && r <= 1)) return false;
    query.record(t, s, r, 0);
    return true;
}

void quad_bounds(const RTCBoundsFunctionArguments *args) {
    const auto &q = *static_cast<const QuadGeometry::Data *>(args->geometryUserPtr);
    write_embree_bounds(q.box, q.frame, *args->bounds_o);
}

} // namespace

QuadGeometry::QuadGeometry(const Vec3 &origin, const Vec3 &edge_u, const Vec3 &edge_v)
    : source_{origin, edge_u, edge_v} {}

Box3 QuadGeometry::world_bounds(const Affine &transform) const {
    const Vec3 origin = transform.point(source_[0]), u = transform.vector(source_[1]), v = transform.vector(source_[2]);
    Box3 box;
    for (const Vec3 &corner : {origin, origin + u, origin + v, origin + u + v}) box.extend(corner);
    return box;
}

Box3 QuadGeometry::prepare(const Affine &transform) {
    Data &q = data_;
    q.origin = transform.point(source_[0]);
    q.edge_u = transform.vector(source_[1]);
    q.edge_v = transform.vector(source_[2]);
    q.normal = cross(q.edge_u, q.edge_v);
    q.uu = dot(q.edge_u, q.edge_u);
    q.uv = dot(q.edge_u, q.edge_v);
    q.vv = dot(q.edge_v, q.edge_v);
    q.det = q.uu * q.vv - q.uv * q.uv;
    q.box = Box3{};
    for (const Vec3 &corner : {q.origin, q.origin + q.edge_u, q.origin + q.edge_v, q.origin + q.edge_u + q.edge_v})
        q.box.extend(corner);
    q.unit_normal = normalize(q.normal);
    q.rounding = 32 * DBL_EPSILON * std::max(max_abs_component(q.box.lower), max_abs_component(q.box.upper));
    return q.box;
}

RTCGeometry QuadGeometry::create_embree(RTCDevice device, const EmbreeFrame &frame) {
    data_.frame = frame;
    return new_user_geometry<Data, test_quad>(device, data_, 1, quad_bounds);
}

void QuadGeometry::describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const {
    const Vec3 p = data_.origin + data_.edge_u * query.hit.u + data_.edge_v * query.hit.v;
    p.store(hit.p);
    data_.unit_normal.store(hit.ng);
    data_.unit_normal.store(hit.ns);
    hit.p_error = tolerance + data_.rounding;
}

} // namespace ppm
