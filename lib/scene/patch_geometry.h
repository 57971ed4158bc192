// SPDX-License-Identifier: Apache-2.0
// Bicubic Bezier patches as Embree user geometry. Each patch is pre-split into n x n
// sub-patches (n: the scene setting "patch_presplit"), which are Embree's primitives, so the
// BVH culls most of a patch before any patch math.
#pragma once

#include "geometry/bezier.h"
#include "geometry/patch_intersector.h"
#include "scene/geometry.h"

#include <cstdint>
#include <vector>

namespace ppm {

class PatchGeometry : public Geometry {
public:
    explicit PatchGeometry(std::vector<BezierPatch> patches);

    const char *kind() const override { return "Bezier patches"; }
    size_t primitive_count() const override { return source_.size(); }
    Box3 world_bounds(const Affine &transform) const override;
    Box3 prepare(const Affine &transform) override;
    RTCGeometry create_embree(RTCDevice device, const EmbreeFrame &frame) override;
    void describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const override;
    // (u, v) of the patch, or mapped into the patch's rectangle when set_uv_rects was called.
    void texture_coordinates(const ppm_hit &hit, double *s, double *t) const override;

    const std::vector<BezierPatch> &world_patches() const { return world_.empty() ? source_ : world_; }

    // One texture across the set: patch i's (u, v) maps linearly onto
    // [rects[4i], rects[4i+2]] x [rects[4i+1], rects[4i+3]]. Empty means per-patch (u, v).
    void set_uv_rects(std::vector<double> rects) { uv_rects_ = std::move(rects); }

    // What a sub-patch keeps between rays: culling data in single precision, rounded outward.
    // Its control points are cut from the world patch when a ray gets past this culling
    // (about a microsecond's work less than the search itself); keeping them would take 400
    // bytes per sub-patch, 8x the rest (ppm-bench intersect, memory).
    struct SubPatch {
        float lower[3], upper[3]; // bounds of its control points
        float normal[3];          // unit normal of a slab holding the control points ...
        float slab_lo, slab_hi;   // ... between these offsets along it (a "fat plane")
        float derivative_bound;   // ControlGrid::derivative_bound, rounded up
        float chord_slope;        // chord_slope_bound for the normal, rounded up (chord_slope.h)
    };
    struct Data {
        const std::vector<BezierPatch> *patches = nullptr; // world space
        const std::vector<double> *magnitudes = nullptr;   // per patch: largest |coordinate|
        std::vector<SubPatch> sub_patches;                 // per_edge x per_edge per patch, row by row
        int per_edge = 1;
        std::vector<IntervalMatrix> intervals; // cutting [0, 1] into per_edge pieces
        std::vector<double> cuts;              // per_edge + 1 cuts of [0, 1], the last exactly 1
        EmbreeFrame frame;
    };
    const Data &data() const { return data_; } // valid after the scene's commit

private:
    // Fills data_.sub_patches with per_edge x per_edge sub-patches of each world patch.
    void split_patches(int per_edge);

    std::vector<BezierPatch> source_;
    std::vector<double> uv_rects_;
    std::vector<BezierPatch> world_; // empty under the identity transform: source_ is the world
    std::vector<double> scale_;      // per world patch: diagonal of its control points
    std::vector<double> magnitude_;  // per world patch: largest absolute coordinate
    Data data_;
};

} // namespace ppm
