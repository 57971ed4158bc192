// SPDX-License-Identifier: Apache-2.0
// Glue between Embree user geometry and double-precision hit tests.
//
// A kind supplies `bool test(const Data &, unsigned prim, RayQuery &)`, which looks for a hit
// of primitive `prim` with t in [query.tnear, query.hit.t] (any such hit when query.any_hit)
// and calls query.record() for it. These callbacks translate that into Embree's float ray,
// and tell the test whose geometry it runs for (query.tested_geom_id).
// Single rays (rtcIntersect1/rtcOccluded1) come with N = 1; streams (rtcIntersect1M) in
// Embree's packets, each lane with the query its ray id names (RayQuery::of).
#pragma once

#include "scene/geometry.h"

namespace ppm {

template <class Data, bool (*Test)(const Data &, unsigned, RayQuery &)>
void user_intersect(const RTCIntersectFunctionNArguments *args) {
    const Data &data = *static_cast<const Data *>(args->geometryUserPtr);
    RTCRayN *ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN *hit = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned lane = 0; lane < args->N; ++lane) {
        if (!args->valid[lane]) continue;
        RayQuery &query = RayQuery::of(args->context, RTCRayN_id(ray, args->N, lane));
        query.tested_geom_id = args->geomID;
        if (!Test(data, args->primID, query)) continue;
        query.hit.geom_id = args->geomID;
        RTCRayN_tfar(ray, args->N, lane) = query.embree_tfar(query.hit.t);
        RTCHitN_u(hit, args->N, lane) = static_cast<float>(query.hit.u);
        RTCHitN_v(hit, args->N, lane) = static_cast<float>(query.hit.v);
        RTCHitN_primID(hit, args->N, lane) = args->primID;
        RTCHitN_geomID(hit, args->N, lane) = args->geomID;
        RTCHitN_instID(hit, args->N, lane, 0) = args->context->instID[0];
    }
}

template <class Data, bool (*Test)(const Data &, unsigned, RayQuery &)>
void user_occluded(const RTCOccludedFunctionNArguments *args) {
    const Data &data = *static_cast<const Data *>(args->geometryUserPtr);
    for (unsigned lane = 0; lane < args->N; ++lane) {
        if (!args->valid[lane]) continue;
        RayQuery &query = RayQuery::of(args->context, RTCRayN_id(args->ray, args->N, lane));
        query.tested_geom_id = args->geomID;
        if (Test(data, args->primID, query)) RTCRayN_tfar(args->ray, args->N, lane) = -INFINITY;
    }
}

// A committed Embree user geometry with `count` primitives whose callbacks see `data`.
// Bounds callbacks get their data from geometryUserPtr: Embree 3.13 ignores the userPtr of
// rtcSetGeometryBoundsFunction.
template <class Data, bool (*Test)(const Data &, unsigned, RayQuery &)>
RTCGeometry new_user_geometry(RTCDevice device, const Data &data, size_t count, RTCBoundsFunction bounds) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    if (!geometry) return nullptr;
    rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(count));
    rtcSetGeometryUserData(geometry, const_cast<Data *>(&data));
    rtcSetGeometryBoundsFunction(geometry, bounds, nullptr);
    rtcSetGeometryIntersectFunction(geometry, user_intersect<Data, Test>);
    rtcSetGeometryOccludedFunction(geometry, user_occluded<Data, Test>);
    rtcCommitGeometry(geometry);
    return geometry;
}

} // namespace ppm
