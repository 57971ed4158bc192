#include "geometry/patch_geometry.h"

#include "geometry/patch_intersector.h"
#include "scene/user_geometry.h"

#include <cfloat>

namespace ppm {

namespace {

// Sub-patches per patch edge. Smaller sub-patches give Embree tighter boxes and leave the
// Krawczyk test less to prove, more cost Embree callbacks; 12 x 12 measured best on the
// teapot (instruction counts of random rays, see ppm-bench).
constexpr int presplit_per_edge = 12;
// Margin around each sub-patch's own domain, as a fraction of its width: a root close to
// the edge of the domain is then far from the edge of the searched patch, where the interval
// test proves it unique without subdividing.
constexpr double search_margin = 0.1;

bool test_sub_patch(const PatchGeometry::Data &data, unsigned prim, RayQuery &query) {
    const PatchGeometry::SubPatch &sub = data.sub_patches[prim];
    PatchRootQuery patch_query;
    patch_query.tnear = query.tnear;
    patch_query.tfar = query.hit.t;
    patch_query.tolerance = query.tolerance;
    patch_query.any_hit = query.any_hit;
    PatchRoot root;
    if (!intersect_patch(sub.patch, query.frame(), patch_query, root)) return false;
    const double u = sub.u0 + root.a * (sub.u1 - sub.u0), v = sub.v0 + root.b * (sub.v1 - sub.v0);
    query.record(root.t, std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0), sub.patch_index);
    return true;
}

void sub_patch_bounds(const RTCBoundsFunctionArguments *args) {
    const auto &data = *static_cast<const PatchGeometry::Data *>(args->geometryUserPtr);
    write_embree_bounds(control_bounds(data.sub_patches[args->primID].patch), data.frame,
                        *args->bounds_o);
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

    data_.sub_patches.clear();
    data_.sub_patches.reserve(world_.size() * presplit_per_edge * presplit_per_edge);
    const double step = 1.0 / presplit_per_edge;
    for (size_t index = 0; index < world_.size(); ++index)
        for (int i = 0; i < presplit_per_edge; ++i)
            for (int j = 0; j < presplit_per_edge; ++j) {
                const double u0 = j * step, u1 = (j + 1) * step;
                const double v0 = i * step, v1 = (i + 1) * step;
                data_.sub_patches.push_back({sub_patch(world_[index], u0, u1, v0, v1), u0, u1, v0,
                                             v1, static_cast<uint32_t>(index)});
            }
    return bounds;
}

RTCGeometry PatchGeometry::create_embree(RTCDevice device, const EmbreeFrame &frame) {
    data_.frame = frame;
    return new_user_geometry<Data, test_sub_patch>(device, data_, data_.sub_patches.size(),
                                                   sub_patch_bounds);
}

void PatchGeometry::describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const {
    const uint32_t index = query.hit.prim_id;
    const BezierPatch &patch = world_[index];
    const Vec3 p = evaluate(patch, query.hit.u, query.hit.v);
    const Vec3 n = geometric_normal(patch, query.hit.u, query.hit.v, scale_[index]);
    p.store(hit.p);
    n.store(hit.ng);
    n.store(hit.ns);
    // Evaluation rounds at a few ulps of the control points' magnitude; (u, v) itself is
    // exact to the tolerance.
    hit.p_error = tolerance + 32 * DBL_EPSILON * magnitude_[index];
}

} // namespace ppm
