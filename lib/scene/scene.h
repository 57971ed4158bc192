// SPDX-License-Identifier: Apache-2.0
// A scene: geometries as added, and after commit an Embree BVH over them plus the double
// precision ray queries.
#pragma once

#include <ppm/ppm.h>

#include "core/context.h"
#include "scene/geometry.h"
#include "scene/ray_hints.h"
#include "scene/sphere_set.h"

#include <memory>
#include <vector>

namespace ppm {

class Scene : public RefCounted {
public:
    explicit Scene(Context &context);
    ~Scene() override;

    Context &context() const { return *context_; }

    uint32_t add(std::unique_ptr<Geometry> geometry);
    Geometry &geometry(uint32_t geom_id) const; // throws INVALID_ARGUMENT for a bad id
    size_t geometry_count() const { return geometries_.size(); }

    void set_tolerance(double relative);
    double tolerance() const { return tolerance_; }
    // Sub-patches per Bezier patch edge: memory against speed (see PatchGeometry).
    void set_patch_presplit(double per_edge);
    int patch_presplit() const { return patch_presplit_; }

    void commit();
    bool committed() const { return rtc_scene_ != nullptr && committed_; }
    const Box3 &bounds() const { return bounds_; }
    double absolute_tolerance() const { return frame_.tolerance; }

    // Single-ray queries on a committed scene; the ray must be valid (see validate_ray).
    // Without surface_uv, u and v may be left 0 where they cost extra (Geometry::compute_uv).
    // `hints` let the query skip work without changing its answer (ray_hints.h).
    void intersect(const ppm_ray &ray, ppm_hit &hit, bool surface_uv = true, const RayHints &hints = {}) const;
    bool occluded(const ppm_ray &ray, const RayHints &hints = {}) const;

    // Closest hits of up to max_stream rays at once, traced by Embree as a coherent stream
    // (a camera's rays): hits[i] as intersect(rays[i], hits[i], surface_uv, hints[i]) gives;
    // `hints` may be null (no hints). Rays beyond max_stream are ignored.
    static constexpr size_t max_stream = 32;
    void intersect_stream(const ppm_ray *rays, const RayHints *hints, size_t count, ppm_hit *hits,
                          bool surface_uv = true) const;

    // Asks that the geometry get an Embree mask bit of its own at commit, before the planar
    // geometries do, because rays will often name it in RayHints::skip_geometry. Embree has 32
    // bits; geometries beyond them are tested by their callbacks instead (same answers). Takes
    // effect at the next commit and, changing no answer, does not undo the last one.
    void prefer_mask_bit(uint32_t geom_id);

    // Batch queries: validate all rays, then run on the context's threads.
    void intersect(const ppm_ray *rays, size_t count, ppm_hit *hits) const;
    void occluded(const ppm_ray *rays, size_t count, uint8_t *occluded) const;

    void mark_modified() { committed_ = false; }

private:
    // Sets up the query and, unless the BVH is empty, Embree's float ray and context; false if
    // the ray misses the scene's box.
    bool start_query(const ppm_ray &ray, bool any_hit, const RayHints &hints, RayQuery &query,
                     RTCRay &embree_ray) const;
    // Embree's mask for a ray with these hints: every geometry except those the ray cannot meet.
    uint32_t ray_mask(const ppm_ray &ray, const RayHints &hints) const;
    // Gives up to 32 geometries a mask bit of their own (assign_mask_bits in scene.cpp).
    void assign_mask_bits();
    // intersect() in two halves around Embree's traversal: the query (and the spheres kept
    // out of the BVH) before, the hit's description after.
    bool start_intersect(const ppm_ray &ray, const RayHints &hints, RayQuery &query, RTCRayHit &rayhit) const;
    void finish_intersect(const RayQuery &query, ppm_hit &hit, bool surface_uv) const;
    void require_committed(const char *operation) const;

    Context *context_;
    std::vector<std::unique_ptr<Geometry>> geometries_;
    double tolerance_ = 1e-9;
    int patch_presplit_ = EmbreeFrame{}.patch_presplit;

    // Spheres whose box holds much of the scene's (a sphere used as a wall, a sky dome): every
    // ray overlaps them, so they stay out of the BVH, where their boxes would widen the nodes
    // above everything else and defeat the culling, and every query tests them directly. A scene of a few spheres keeps
    // them all here and its BVH empty.
    std::vector<uint32_t> direct_sphere_ids_;
    SphereSet direct_spheres_; // the same spheres, by index in direct_sphere_ids_
    bool bvh_empty_ = false;   // every geometry is a direct sphere: Embree is not called

    // Per geometry: its own Embree mask bit, or 0 if it has none (shares the full mask).
    // Rays then skip, without any callback, the planar geometry they leave and the geometry
    // their hints name: the two quads every shadow ray in a Cornell box reached (own wall, light).
    std::vector<bool> prefers_mask_bit_; // prefer_mask_bit(), per geometry
    std::vector<uint32_t> mask_bit_;
    std::vector<uint32_t> leaving_mask_bit_; // the same for planar geometries, 0 for the rest

    RTCScene rtc_scene_ = nullptr;
    bool committed_ = false;
    Box3 bounds_;
    Box3 query_box_; // bounds plus padding: rays are clipped to it before Embree sees them
    EmbreeFrame frame_;
};

// Throws INVALID_ARGUMENT naming `index` if the ray has NaN/Inf, a zero direction, or a bad
// [tnear, tfar].
void validate_ray(const ppm_ray &ray, size_t index);

} // namespace ppm
