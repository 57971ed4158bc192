// SPDX-License-Identifier: Apache-2.0
// One ray's state during an Embree traversal. Embree's ray is single precision; the exact
// double ray and the best double hit so far live here, in an extension of
// RTCIntersectContext that every callback casts back to.
#pragma once

#include "geometry/patch_intersector.h"
#include "math/vec3.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace ppm {

// std::nextafter(f, INFINITY) without the libm call (it runs per ray): the float above f,
// f itself for +inf and NaN.
inline float next_float_up(float f) {
    if (!(f < INFINITY)) return f;
    if (f == 0) return std::numeric_limits<float>::denorm_min();
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    bits = f > 0 ? bits + 1 : bits - 1; // sign-magnitude: a negative f grows as its magnitude shrinks
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

struct HitRecord {
    double t = INFINITY;
    double u = 0, v = 0;
    uint32_t geom_id = 0xFFFFFFFFu;
    uint32_t prim_id = 0;
};

// The surface point a ray leaves, when the caller knows it (the hit a renderer spawned the
// ray from): a geometry may then rule out the root the ray starts on without a search.
struct RayOrigin {
    uint32_t geom_id = 0xFFFFFFFFu; // none
    uint32_t prim_id = 0;
    double u = 0, v = 0;
    Vec3 p; // the hit's point: the surface at (u, v), rounded
};

struct RayQuery {
    RTCIntersectContext embree; // first member: Embree hands back a pointer to it

    Vec3 org, dir;                               // the double ray, world space
    double tnear = 0;                            // accepted hits: t in [tnear, hit.t]
    double t_shift = 0;                          // Embree's ray starts at org + t_shift * dir ...
    double dir_length = 1;                       // ... and runs along dir / |dir|: t = t_shift + t_embree / |dir|
    double dir_length2 = 1, inv_dir_length2 = 1; // |dir|^2 and its inverse, for quadrics
    double tolerance = 0;                        // absolute, from the scene
    bool any_hit = false;
    bool found = false;
    HitRecord hit;                         // best hit so far; hit.t is the current far limit
    RayOrigin origin;                      // where the ray leaves a surface, if known
    uint32_t tested_geom_id = 0xFFFFFFFEu; // the geometry whose callback runs (user_geometry.h)

    // The ray frame for patches, built on first use.
    const RayFrame &frame() {
        if (!frame_ready_) {
            frame_ = RayFrame::from_ray(org, dir, dir_length);
            frame_ready_ = true;
        }
        return frame_;
    }
    // 1 / dir per axis (infinite for a zero component), for clipping to boxes: three
    // divisions per ray instead of six per box. Built on first use.
    const Vec3 &inv_dir() {
        if (!inv_dir_ready_) {
            inv_dir_ = {1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z};
            inv_dir_ready_ = true;
        }
        return inv_dir_;
    }

    // The query of the Embree ray with this id that a callback got `context` for.
    static RayQuery &of(RTCIntersectContext *context, unsigned ray_id);

    // Records a hit known to lie in [tnear, hit.t]; the caller sets hit.geom_id.
    void record(double t, double u, double v, uint32_t prim_id) {
        hit.t = t;
        hit.u = u;
        hit.v = v;
        hit.prim_id = prim_id;
        found = true;
    }

    // Embree's far limit for a double t: rounded up so that no box at t is culled.
    float embree_tfar(double t) const { return next_float_up(static_cast<float>((t - t_shift) * dir_length)); }

private:
    RayFrame frame_;
    Vec3 inv_dir_;
    bool frame_ready_ = false, inv_dir_ready_ = false;
};

// Embree ray ids. A single ray's query is its own context (RayQuery::embree) and its ray has
// kSingleRayId; the rays of a stream (Scene::intersect_stream) are numbered 0, 1, ... and
// share a StreamContext that lists their queries.
constexpr unsigned kSingleRayId = 0xFFFFFFFFu;

struct StreamContext {
    RTCIntersectContext embree; // first member, as in RayQuery
    RayQuery *queries = nullptr;
};

inline RayQuery &RayQuery::of(RTCIntersectContext *context, unsigned ray_id) {
    if (ray_id == kSingleRayId) return *reinterpret_cast<RayQuery *>(context);
    return reinterpret_cast<StreamContext *>(context)->queries[ray_id];
}

} // namespace ppm
