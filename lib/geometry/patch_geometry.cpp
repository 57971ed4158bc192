#include "geometry/patch_geometry.h"

#include "geometry/patch_intersector.h"
#include "scene/user_geometry.h"

#include <cfloat>

namespace ppm {

namespace {

// Sub-patches per patch edge come from the scene setting "patch_presplit" (EmbreeFrame).
// Smaller sub-patches give Embree tighter boxes and leave the Krawczyk test less to prove,
// more cost Embree callbacks and memory (one control grid each). On the teapot 12 (the
// default) was the fastest on camera rays and about as fast as 4 on random ones, 24 only 3-5%
// faster; 1 keeps little more than the patches (ppm-bench intersect, exact-presplit-N).

// Cheap rejection before the patch math: Embree only tested a float box. Clip the ray to
// the sub-patch's box in double and check that the clipped segment reaches the slab between
// the sub-patch's bounding planes. Both are padded by the tolerance and rounding.
bool segment_misses(const PatchGeometry::SubPatch &sub, const RayQuery &query) {
    const double size = sub.box.diagonal();
    const double pad = query.tolerance + 1e-12 * (size + max_abs_component(sub.box.lower) +
                                                  max_abs_component(sub.box.upper));
    double t0 = query.tnear, t1 = query.hit.t;
    for (int axis = 0; axis < 3; ++axis) {
        const double o = query.org[axis], d = query.dir[axis];
        const double lo = sub.box.lower[axis] - pad, hi = sub.box.upper[axis] + pad;
        if (d == 0) {
            if (o < lo || o > hi) return true;
            continue;
        }
        double ta = (lo - o) / d, tb = (hi - o) / d;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    if (!(t0 <= t1)) return true;
    const double d0 = dot(sub.normal, query.org + query.dir * t0);
    const double d1 = dot(sub.normal, query.org + query.dir * t1);
    return (d0 < sub.slab_lo - pad && d1 < sub.slab_lo - pad) ||
           (d0 > sub.slab_hi + pad && d1 > sub.slab_hi + pad);
}

bool test_sub_patch(const PatchGeometry::Data &data, unsigned prim, RayQuery &query) {
    const PatchGeometry::SubPatch &sub = data.sub_patches[prim];
    if (segment_misses(sub, query)) return false;
    PatchRootQuery patch_query;
    patch_query.tnear = query.tnear;
    patch_query.tfar = query.hit.t;
    patch_query.tolerance = query.tolerance;
    patch_query.any_hit = query.any_hit;
    PatchRoot root;
    if (!intersect_patch(sub.grid, query.frame(), patch_query, root)) return false;
    const double u = sub.u0 + root.a * (sub.u1 - sub.u0), v = sub.v0 + root.b * (sub.v1 - sub.v0);
    query.record(root.t, std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0), sub.patch_index);
    return true;
}

void sub_patch_bounds(const RTCBoundsFunctionArguments *args) {
    const auto &data = *static_cast<const PatchGeometry::Data *>(args->geometryUserPtr);
    write_embree_bounds(data.sub_patches[args->primID].box, data.frame, *args->bounds_o);
}

PatchGeometry::SubPatch make_sub_patch(const BezierPatch &patch, double u0, double u1, double v0,
                                       double v1) {
    const BezierPatch part = sub_patch(patch, u0, u1, v0, v1);
    PatchGeometry::SubPatch sub;
    sub.grid = ControlGrid::from(part);
    sub.box = control_bounds(part);
    sub.u0 = u0;
    sub.u1 = u1;
    sub.v0 = v0;
    sub.v1 = v1;
    // Normal of the plane spanned by the mean chords; any direction gives a valid slab, this
    // one a thin slab for a nearly flat part.
    const Vec3 along_u = (part.at(0, 3) + part.at(3, 3)) - (part.at(0, 0) + part.at(3, 0));
    const Vec3 along_v = (part.at(3, 0) + part.at(3, 3)) - (part.at(0, 0) + part.at(0, 3));
    const Vec3 n = cross(along_u, along_v);
    sub.normal = length(n) > 0 ? normalize(n) : Vec3{0, 0, 1};
    sub.slab_lo = INFINITY;
    sub.slab_hi = -INFINITY;
    for (const Vec3 &p : part.p) {
        sub.slab_lo = std::min(sub.slab_lo, dot(sub.normal, p));
        sub.slab_hi = std::max(sub.slab_hi, dot(sub.normal, p));
    }
    return sub;
}

} // namespace

PatchGeometry::PatchGeometry(std::vector<BezierPatch> patches) : source_(std::move(patches)) {}

Box3 PatchGeometry::prepare(const Affine &transform) {
    world_ = source_;
    scale_.clear();
    magnitude_.clear();
    Box3 bounds;
    for (BezierPatch &patch : world_) {
        double magnitude = 0;
        for (Vec3 &p : patch.p) {
            p = transform.point(p);
            bounds.extend(p);
            magnitude = std::max(magnitude, max_abs_component(p));
        }
        scale_.push_back(control_bounds(patch).diagonal());
        magnitude_.push_back(magnitude);
    }

    return bounds;
}

void PatchGeometry::split_patches(int per_edge) {
    data_.sub_patches.clear();
    data_.sub_patches.shrink_to_fit(); // a smaller presplit than last commit's frees memory
    data_.sub_patches.reserve(world_.size() * per_edge * per_edge);
    const double step = 1.0 / per_edge;
    for (size_t index = 0; index < world_.size(); ++index)
        for (int i = 0; i < per_edge; ++i)
            for (int j = 0; j < per_edge; ++j) {
                // The last boundary is exactly 1, not per_edge * step.
                const double u0 = j * step, u1 = j + 1 == per_edge ? 1.0 : (j + 1) * step;
                const double v0 = i * step, v1 = i + 1 == per_edge ? 1.0 : (i + 1) * step;
                data_.sub_patches.push_back(make_sub_patch(world_[index], u0, u1, v0, v1));
                data_.sub_patches.back().patch_index = static_cast<uint32_t>(index);
            }
}

RTCGeometry PatchGeometry::create_embree(RTCDevice device, const EmbreeFrame &frame) {
    split_patches(frame.patch_presplit);
    data_.frame = frame;
    return new_user_geometry<Data, test_sub_patch>(device, data_, data_.sub_patches.size(),
                                                   sub_patch_bounds);
}

void PatchGeometry::describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const {
    const uint32_t index = query.hit.prim_id;
    const BezierPatch &patch = world_[index];
    const SurfaceDerivatives d = evaluate_derivatives(patch, query.hit.u, query.hit.v);
    const Vec3 &p = d.p;
    const Vec3 n = geometric_normal(patch, query.hit.u, query.hit.v, scale_[index], d);
    p.store(hit.p);
    n.store(hit.ng);
    n.store(hit.ns);
    // Evaluation rounds at a few ulps of the control points' magnitude; (u, v) itself is
    // exact to the tolerance.
    hit.p_error = tolerance + 32 * DBL_EPSILON * magnitude_[index];
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
