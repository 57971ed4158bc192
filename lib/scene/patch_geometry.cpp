// SPDX-License-Identifier: Apache-2.0
#include "scene/patch_geometry.h"

#include "geometry/chord_slope.h"
#include "geometry/patch_intersector.h"
#include "scene/user_geometry.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace ppm {

namespace {

// Sub-patches per patch edge come from the scene setting "patch_presplit" (EmbreeFrame).
// Smaller sub-patches give Embree tighter boxes and leave the Krawczyk test less to prove,
// more cost Embree callbacks and memory (52 bytes of culling data each plus Embree's ~90
// bytes). The default is chosen by `ppm-bench intersect` (methods exact-presplit-N; figures
// in docs/bench/code-history.md).

// A hit point is the patch evaluated at the hit's (u, v): Bernstein sums of 16 control
// points, which round by a few ulps of their magnitude; this many covers them.
constexpr double kHitPointUlps = 32;
// The clipping below runs in double on coordinates of the float box: its relative rounding
// is a few ulps, this pad covers it ten thousandfold.
constexpr double kClipRounding = 1e-12;

float round_down(double x) {
    const float f = static_cast<float>(x);
    return double(f) > x ? std::nextafter(f, -INFINITY) : f;
}
float round_up(double x) {
    const float f = static_cast<float>(x);
    return double(f) < x ? std::nextafter(f, INFINITY) : f;
}

Box3 box_of(const PatchGeometry::SubPatch &sub) {
    return {{sub.lower[0], sub.lower[1], sub.lower[2]}, {sub.upper[0], sub.upper[1], sub.upper[2]}};
}

// Domain [u0, u1] x [v0, v1] of sub-patch (row, column) when each edge is cut in per_edge.
struct Domain {
    double u0, u1, v0, v1;
};

// Sub-patch `prim`: its patch, row and column there (sub-patches are stored row by row,
// per_edge x per_edge per patch), and its domain in the patch.
struct SubPatchPlace {
    unsigned patch = 0;
    int row = 0, column = 0;
    Domain domain{};
    static SubPatchPlace of(unsigned prim, const PatchGeometry::Data &data) {
        const unsigned per_edge = unsigned(data.per_edge), per_patch = per_edge * per_edge;
        const unsigned within = prim % per_patch;
        SubPatchPlace p;
        p.patch = prim / per_patch;
        p.row = int(within / per_edge);
        p.column = int(within % per_edge);
        p.domain = {data.cuts[p.column], data.cuts[p.column + 1], data.cuts[p.row], data.cuts[p.row + 1]};
        return p;
    }
};

// Cheap rejection before the patch math: Embree only tested a float box. Clip the ray to
// the sub-patch's box in double and check that the clipped segment reaches the slab between
// the sub-patch's bounding planes. Both are padded by the tolerance and rounding.
bool segment_misses(const PatchGeometry::SubPatch &sub, RayQuery &query) {
    const Box3 box = box_of(sub);
    // The sum of the box's extents bounds its diagonal (no square root needed for a pad).
    const Vec3 extent = box.upper - box.lower;
    const double pad = query.tolerance + kClipRounding * (extent.x + extent.y + extent.z +
                                                          max_abs_component(box.lower) + max_abs_component(box.upper));
    const Vec3 &inv_dir = query.inv_dir();
    double t0 = query.tnear, t1 = query.hit.t;
    for (int axis = 0; axis < 3; ++axis) {
        const double o = query.org[axis], d = query.dir[axis];
        const double lo = box.lower[axis] - pad, hi = box.upper[axis] + pad;
        if (d == 0) {
            if (o < lo || o > hi) return true;
            continue;
        }
        // A reciprocal rounds t by an ulp more than a division: far below the pad. A tiny d
        // gives an infinite reciprocal, and 0 * inf a NaN, which max/min below ignore (the
        // axis then clips nothing).
        double ta = (lo - o) * inv_dir[axis], tb = (hi - o) * inv_dir[axis];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    if (!(t0 <= t1)) return true;
    const Vec3 normal{sub.normal[0], sub.normal[1], sub.normal[2]};
    const double d0 = dot(normal, query.org + query.dir * t0);
    const double d1 = dot(normal, query.org + query.dir * t1);
    return (d0 < sub.slab_lo - pad && d1 < sub.slab_lo - pad) || (d0 > sub.slab_hi + pad && d1 > sub.slab_hi + pad);
}

Vec3 stored_normal(const PatchGeometry::SubPatch &sub) { return {sub.normal[0], sub.normal[1], sub.normal[2]}; }

// Whether the ray leaves a point of this sub-patch (the caller said where it starts) and
// cannot meet it again: chord_slope.h. The hit point the ray was spawned from is the
// patch evaluated at the hit's (u, v), to rounding of kHitPointUlps of the patch's magnitude
// (as PatchGeometry::describe_hit states); twice that is allowed for.
bool leaves_own_sub_patch(const PatchGeometry::Data &data, const PatchGeometry::SubPatch &sub, unsigned patch_index,
                          const Domain &d, const RayQuery &query) {
    const RayOrigin &from = query.origin;
    if (from.prim_id != patch_index || !(query.tnear >= 0)) return false;
    if (!(from.u >= d.u0 && from.u <= d.u1 && from.v >= d.v0 && from.v <= d.v1)) return false;
    const double offset_error = 2 * kHitPointUlps * DBL_EPSILON * (*data.magnitudes)[patch_index];
    return leaves_for_good(stored_normal(sub), sub.chord_slope, query.org - from.p, offset_error, query.dir);
}

bool test_sub_patch(const PatchGeometry::Data &data, unsigned prim, RayQuery &query) {
    const PatchGeometry::SubPatch &sub = data.sub_patches[prim];
    // Where the sub-patch lies in its patch: rays leaving this geometry need it first, the
    // others only once past the culling.
    SubPatchPlace at;
    const bool leaves_this_geometry = query.origin.geom_id == query.tested_geom_id;
    if (leaves_this_geometry) {
        at = SubPatchPlace::of(prim, data);
        if (leaves_own_sub_patch(data, sub, at.patch, at.domain, query)) return false;
    }
    if (segment_misses(sub, query)) return false;
    if (!leaves_this_geometry) at = SubPatchPlace::of(prim, data);
    const unsigned patch_index = at.patch;
    const Domain &d = at.domain;
    ControlGrid grid;
    sub_patch_soa((*data.patches)[patch_index], data.intervals[at.column], data.intervals[at.row], grid.x, grid.y,
                  grid.z);
    grid.derivative_bound = sub.derivative_bound;
    PatchRootQuery patch_query;
    patch_query.tnear = query.tnear;
    patch_query.tfar = query.hit.t;
    patch_query.tolerance = query.tolerance;
    patch_query.any_hit = query.any_hit;
    PatchRoot root;
    if (!intersect_patch(grid, query.frame(), patch_query, root)) return false;
    const double u = d.u0 + root.a * (d.u1 - d.u0), v = d.v0 + root.b * (d.v1 - d.v0);
    query.record(root.t, std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0), patch_index);
    return true;
}

void sub_patch_bounds(const RTCBoundsFunctionArguments *args) {
    const auto &data = *static_cast<const PatchGeometry::Data *>(args->geometryUserPtr);
    write_embree_bounds(box_of(data.sub_patches[args->primID]), data.frame, *args->bounds_o);
}

PatchGeometry::SubPatch make_sub_patch(const BezierPatch &patch, const IntervalMatrix &along_u,
                                       const IntervalMatrix &along_v) {
    // The control points exactly as test_sub_patch will cut them.
    ControlGrid grid;
    sub_patch_soa(patch, along_u, along_v, grid.x, grid.y, grid.z);
    BezierPatch part;
    for (int k = 0; k < 16; ++k) part.p[k] = {grid.x[k], grid.y[k], grid.z[k]};
    PatchGeometry::SubPatch sub;
    const Box3 box = control_bounds(part);
    for (int axis = 0; axis < 3; ++axis) {
        sub.lower[axis] = round_down(box.lower[axis]);
        sub.upper[axis] = round_up(box.upper[axis]);
    }
    // Normal of the plane spanned by the mean chords; any direction gives a valid slab, this
    // one a thin slab for a nearly flat part. The offsets are taken along the normal as
    // stored, so rounding it costs nothing but a slightly other slab.
    const Vec3 along_u_chord = (part.at(0, 3) + part.at(3, 3)) - (part.at(0, 0) + part.at(3, 0));
    const Vec3 along_v_chord = (part.at(3, 0) + part.at(3, 3)) - (part.at(0, 0) + part.at(0, 3));
    const Vec3 n = cross(along_u_chord, along_v_chord);
    const Vec3 unit = length(n) > 0 ? normalize(n) : Vec3{0, 0, 1};
    const float rounded[3] = {float(unit.x), float(unit.y), float(unit.z)};
    const Vec3 normal{rounded[0], rounded[1], rounded[2]};
    double lo = INFINITY, hi = -INFINITY;
    for (const Vec3 &p : part.p) {
        lo = std::min(lo, dot(normal, p));
        hi = std::max(hi, dot(normal, p));
    }
    std::copy(rounded, rounded + 3, sub.normal);
    sub.slab_lo = round_down(lo);
    sub.slab_hi = round_up(hi);
    sub.derivative_bound = round_up(grid.bound_derivatives());
    sub.chord_slope = round_up(chord_slope_bound(grid, normalize(stored_normal(sub))));
    return sub;
}

} // namespace

PatchGeometry::PatchGeometry(std::vector<BezierPatch> patches) : source_(std::move(patches)) {}

Box3 PatchGeometry::world_bounds(const Affine &transform) const {
    Box3 bounds;
    for (const BezierPatch &patch : source_)
        for (const Vec3 &p : patch.p) bounds.extend(transform.point(p));
    return bounds;
}

Box3 PatchGeometry::prepare(const Affine &transform) {
    // Under the identity the source patches are the world patches; a copy would double the
    // memory of a patch set's geometry at small presplits.
    bool identity = true;
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 4; ++column)
            identity = identity && transform.m[row][column] == (row == column ? 1.0 : 0.0);
    world_.clear();
    world_.shrink_to_fit();
    if (!identity) {
        world_ = source_;
        for (BezierPatch &patch : world_)
            for (Vec3 &p : patch.p) p = transform.point(p);
    }
    scale_.clear();
    magnitude_.clear();
    Box3 bounds;
    for (const BezierPatch &patch : world_patches()) {
        double magnitude = 0;
        for (const Vec3 &p : patch.p) {
            bounds.extend(p);
            magnitude = std::max(magnitude, max_abs_component(p));
        }
        scale_.push_back(control_bounds(patch).diagonal());
        magnitude_.push_back(magnitude);
    }
    return bounds;
}

void PatchGeometry::split_patches(int per_edge) {
    // The cuts of [0, 1], the last exactly 1 (not per_edge * step), and the interval matrices
    // between them.
    std::vector<double> &cuts = data_.cuts;
    cuts.clear();
    const double step = 1.0 / per_edge;
    for (int k = 0; k < per_edge; ++k) cuts.push_back(k * step);
    cuts.push_back(1.0);
    data_.intervals.clear();
    for (int k = 0; k < per_edge; ++k) data_.intervals.push_back(IntervalMatrix::of(cuts[k], cuts[k + 1]));
    data_.sub_patches.clear();
    data_.sub_patches.shrink_to_fit(); // a smaller presplit than last commit's frees memory
    data_.sub_patches.reserve(world_patches().size() * per_edge * per_edge);
    for (const BezierPatch &patch : world_patches())
        for (int row = 0; row < per_edge; ++row)
            for (int column = 0; column < per_edge; ++column)
                data_.sub_patches.push_back(make_sub_patch(patch, data_.intervals[column], data_.intervals[row]));
    data_.patches = &world_patches();
    data_.magnitudes = &magnitude_;
    data_.per_edge = per_edge;
}

RTCGeometry PatchGeometry::create_embree(RTCDevice device, const EmbreeFrame &frame) {
    split_patches(frame.patch_presplit);
    data_.frame = frame;
    return new_user_geometry<Data, test_sub_patch>(device, data_, data_.sub_patches.size(), sub_patch_bounds);
}

void PatchGeometry::describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const {
    const uint32_t index = query.hit.prim_id;
    const BezierPatch &patch = world_patches()[index];
    const SurfaceDerivatives d = evaluate_derivatives(patch, query.hit.u, query.hit.v);
    const Vec3 &p = d.p;
    const Vec3 n = geometric_normal(patch, query.hit.u, query.hit.v, scale_[index], d);
    p.store(hit.p);
    n.store(hit.ng);
    n.store(hit.ns);
    // Evaluation rounds at a few ulps of the control points' magnitude; (u, v) itself is
    // exact to the tolerance.
    hit.p_error = tolerance + kHitPointUlps * DBL_EPSILON * magnitude_[index];
}

void PatchGeometry::texture_coordinates(const ppm_hit &hit, double *s, double *t) const {
    if (uv_rects_.size() != 4 * source_.size() || hit.prim_id >= source_.size()) {
        Geometry::texture_coordinates(hit, s, t);
        return;
    }
    const double *r = &uv_rects_[4 * hit.prim_id];
    *s = r[0] + (r[2] - r[0]) * hit.u;
    *t = r[1] + (r[3] - r[1]) * hit.v;
}

} // namespace ppm
