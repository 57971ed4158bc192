// SPDX-License-Identifier: Apache-2.0
// A geometry of a scene: the user's data as added, turned into world-space data and an Embree
// geometry at commit, and the final hit description (point, normals) on request.
#pragma once

#include <ppm/ppm.h>

#include "math/vec3.h"
#include "scene/ray_query.h"

#include <embree3/rtcore.h>

#include <cstddef>
#include <string>

namespace ppm {

// Embree works in single precision around the scene centre: Embree coordinates are world
// coordinates minus `center`. User-geometry boxes are padded by `box_padding` so that the
// float ray Embree traverses never misses a box the double ray enters.
struct EmbreeFrame {
    Vec3 center;
    double box_padding = 0;
    double tolerance = 0;    // absolute hit tolerance of the scene
    int patch_presplit = 12; // scene setting "patch_presplit": sub-patches per patch edge
};

// Range of the scene setting "patch_presplit" (see ppm.h).
constexpr int min_patch_presplit = 1, max_patch_presplit = 32;

class Geometry {
public:
    virtual ~Geometry() = default;

    virtual const char *kind() const = 0;
    virtual size_t primitive_count() const = 0;

    // Throws INVALID_ARGUMENT (naming the geometry) if this kind cannot take the transform.
    virtual void check_transform(const Affine &transform) const { (void)transform; }

    // The bounds prepare(transform) would return, without changing anything (a committed
    // scene's queries read the prepared data).
    virtual Box3 world_bounds(const Affine &transform) const = 0;
    // Commit, step 1: applies the transform to the stored data; returns world bounds.
    virtual Box3 prepare(const Affine &transform) = 0;
    // Commit, step 2: a new Embree geometry (committed, not attached) for the prepared data.
    virtual RTCGeometry create_embree(RTCDevice device, const EmbreeFrame &frame) = 0;

    // Fills p, p_error, ng and ns of a hit from its t/u/v/prim_id.
    virtual void describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const = 0;
    // Fills u and v of a described hit where they cost more than the hit itself (a sphere's
    // atan2 and acos); the others have them from the intersection already. Separate so that
    // the renderer pays only for textured surfaces.
    virtual void compute_uv(ppm_hit &hit) const { (void)hit; }

    // Whether a ray spawned from one of its hits (spawn_ray) never meets it again: true for
    // flat shapes, whose plane such a ray leaves. The scene then hides the geometry from that
    // ray by an Embree mask, before any callback runs (Scene::ray_mask).
    virtual bool planar() const { return false; }

    // Texture coordinates (s, t) of a hit: its (u, v) unless the kind maps them (mesh vertex
    // uvs, a patch set's per-patch rectangles).
    virtual void texture_coordinates(const ppm_hit &hit, double *s, double *t) const {
        *s = hit.u;
        *t = hit.v;
    }

    Affine transform;
    // The caller's tag for the geometry, reported in every hit (ppm_hit::material); the scene
    // does not interpret it (the renderer looks its material up by it).
    uint32_t material = 0;
    // Mitsuba's `flip_normals`: every hit reports -ng and -ns (the scene negates what
    // describe_hit wrote), and an area light on the geometry emits on the other side.
    bool flip_normals = false;
};

// Pads a box so Embree's single-precision traversal keeps it (see EmbreeFrame). Every bounds
// callback ends here.
void write_embree_bounds(const Box3 &world, const EmbreeFrame &frame, RTCBounds &out);

// For ThreadSanitizer builds; a no-op otherwise. rtcCommitScene runs the bounds callbacks on
// TBB workers and waits for them through TBB code inlined into Embree, which TSan cannot see
// (Debian's Embree is not instrumented), so it would take every later write to the data they
// read for a race. write_embree_bounds releases, and the scene calls this after
// rtcCommitScene returns, when every callback has finished: the join Embree performs becomes
// visible to TSan.
void embree_build_joined();

} // namespace ppm
