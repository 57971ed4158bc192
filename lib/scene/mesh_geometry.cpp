// SPDX-License-Identifier: Apache-2.0
#include "scene/mesh_geometry.h"

#include "geometry/vertex_normals.h"

#include <cfloat>

namespace ppm {

namespace {

// Double-precision ray / triangle (Moller-Trumbore). Embree already found the triangle in
// single precision, so a double "miss" here is an edge case of rounding: keep the hit and
// clamp the barycentrics instead of losing it.
void exact_triangle_hit(const MeshData &m, unsigned prim, const RayQuery &query, double &t, double &u, double &v) {
    const Vec3 &p0 = m.positions[m.indices[3 * prim]];
    const Vec3 &p1 = m.positions[m.indices[3 * prim + 1]];
    const Vec3 &p2 = m.positions[m.indices[3 * prim + 2]];
    const Vec3 e1 = p1 - p0, e2 = p2 - p0;
    const Vec3 pv = cross(query.dir, e2);
    const double det = dot(e1, pv);
    if (det == 0) return; // parallel: keep Embree's values
    const Vec3 tv = query.org - p0;
    const Vec3 qv = cross(tv, e1);
    u = std::clamp(dot(tv, pv) / det, 0.0, 1.0);
    v = std::clamp(dot(query.dir, qv) / det, 0.0, 1.0 - u);
    t = dot(e2, qv) / det;
}

void mesh_filter(const RTCFilterFunctionNArguments *args) {
    const auto &mesh = *static_cast<const MeshData *>(args->geometryUserPtr);
    for (unsigned lane = 0; lane < args->N; ++lane) {
        if (!args->valid[lane]) continue;
        RayQuery &query = RayQuery::of(args->context, RTCRayN_id(args->ray, args->N, lane));
        const unsigned prim = RTCHitN_primID(args->hit, args->N, lane);
        double t = query.t_shift + RTCRayN_tfar(args->ray, args->N, lane) / query.dir_length;
        double u = RTCHitN_u(args->hit, args->N, lane), v = RTCHitN_v(args->hit, args->N, lane);
        exact_triangle_hit(mesh, prim, query, t, u, v);
        if (!(t >= query.tnear && t <= query.hit.t)) {
            args->valid[lane] = 0;
            continue;
        }
        query.record(t, u, v, prim);
        query.hit.geom_id = RTCHitN_geomID(args->hit, args->N, lane);
    }
}

} // namespace

MeshGeometry::MeshGeometry(MeshData mesh) : source_(std::move(mesh)) {}

Box3 MeshGeometry::world_bounds(const Affine &transform) const {
    Box3 bounds;
    for (const Vec3 &p : source_.positions) bounds.extend(transform.point(p));
    return bounds;
}

Box3 MeshGeometry::prepare(const Affine &transform) {
    world_ = std::make_shared<MeshData>(source_);
    Box3 bounds;
    magnitude_ = 0;
    for (Vec3 &p : world_->positions) {
        p = transform.point(p);
        bounds.extend(p);
        magnitude_ = std::max(magnitude_, max_abs_component(p));
    }
    for (Vec3 &n : world_->normals) {
        n = transform.normal(n);
        const double len = length(n);
        if (len > 0) n = n / len;
    }
    if (computes_vertex_normals_) world_->normals = angle_weighted_vertex_normals(*world_);
    return bounds;
}

RTCGeometry MeshGeometry::create_embree(RTCDevice device, const EmbreeFrame &frame) {
    const MeshData &world = *world_;
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!geometry) return nullptr;
    float *vertices = static_cast<float *>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), world.positions.size()));
    unsigned *indices = static_cast<unsigned *>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), world.indices.size() / 3));
    if (!vertices || !indices) {
        rtcReleaseGeometry(geometry);
        return nullptr;
    }
    for (size_t k = 0; k < world.positions.size(); ++k) {
        const Vec3 p = world.positions[k] - frame.center;
        vertices[3 * k] = static_cast<float>(p.x);
        vertices[3 * k + 1] = static_cast<float>(p.y);
        vertices[3 * k + 2] = static_cast<float>(p.z);
    }
    std::copy(world.indices.begin(), world.indices.end(), indices);
    rtcSetGeometryUserData(geometry, world_.get());
    rtcSetGeometryIntersectFilterFunction(geometry, mesh_filter);
    rtcSetGeometryOccludedFilterFunction(geometry, mesh_filter);
    rtcCommitGeometry(geometry);
    return geometry;
}

void MeshGeometry::describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const {
    const unsigned prim = query.hit.prim_id;
    const uint32_t i0 = world_->indices[3 * prim], i1 = world_->indices[3 * prim + 1],
                   i2 = world_->indices[3 * prim + 2];
    const double u = query.hit.u, v = query.hit.v, w = 1.0 - u - v;
    const Vec3 &p0 = world_->positions[i0], &p1 = world_->positions[i1], &p2 = world_->positions[i2];
    const Vec3 p = p0 * w + p1 * u + p2 * v;
    const Vec3 ng = normalize(cross(p1 - p0, p2 - p0));
    Vec3 ns = ng;
    if (!world_->normals.empty()) {
        const Vec3 interpolated = world_->normals[i0] * w + world_->normals[i1] * u + world_->normals[i2] * v;
        if (length(interpolated) > 0) ns = normalize(interpolated);
    }
    p.store(hit.p);
    ng.store(hit.ng);
    ns.store(hit.ns);
    hit.p_error = tolerance + 32 * DBL_EPSILON * magnitude_;
}

void MeshGeometry::texture_coordinates(const ppm_hit &hit, double *s, double *t) const {
    if (world_->uvs.empty() || hit.prim_id >= primitive_count()) {
        Geometry::texture_coordinates(hit, s, t);
        return;
    }
    const uint32_t *tri = &world_->indices[3 * hit.prim_id];
    const double u = hit.u, v = hit.v, w = 1.0 - u - v;
    *s = world_->uvs[2 * tri[0]] * w + world_->uvs[2 * tri[1]] * u + world_->uvs[2 * tri[2]] * v;
    *t = world_->uvs[2 * tri[0] + 1] * w + world_->uvs[2 * tri[1] + 1] * u + world_->uvs[2 * tri[2] + 1] * v;
}

} // namespace ppm
