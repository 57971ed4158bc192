// SPDX-License-Identifier: Apache-2.0
#include "scene/scene.h"

#include "core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

namespace ppm {

namespace {

// The spheres that stay out of the BVH (see Scene::direct_sphere_ids_), the largest first, at
// most SphereSet::kCapacity (16): those whose box takes at least 1/64 of the scene box's volume
// (a box wider than a quarter of the scene's on every axis), or every sphere when the scene is
// nothing but 16 or fewer spheres. A BVH cannot cull a big sphere's box, and in it the box
// would widen the nodes above everything else; and a handful of spheres is tested in SIMD
// lanes for less than calls into Embree cost.
std::vector<uint32_t> direct_sphere_ids(const std::vector<std::unique_ptr<Geometry>> &geometries,
                                        const Box3 &scene_box) {
    constexpr double min_volume_fraction = 1.0 / 64;
    constexpr size_t max_direct = SphereSet::kCapacity;
    const Vec3 extent = scene_box.upper - scene_box.lower;
    const double scene_volume = extent.x * extent.y * extent.z;
    const bool only_few_spheres =
        geometries.size() <= max_direct && std::all_of(geometries.begin(), geometries.end(), [](const auto &g) {
            return dynamic_cast<const SphereGeometry *>(g.get()) != nullptr;
        });
    std::vector<std::pair<double, uint32_t>> big;
    for (size_t id = 0; id < geometries.size(); ++id) {
        const auto *sphere = dynamic_cast<const SphereGeometry *>(geometries[id].get());
        if (!sphere) continue;
        const double side = 2 * sphere->data().radius, volume = side * side * side;
        if (only_few_spheres || volume >= min_volume_fraction * scene_volume)
            big.push_back({volume, static_cast<uint32_t>(id)});
    }
    std::sort(big.begin(), big.end(), [](const auto &a, const auto &b) { return a.first > b.first; });
    std::vector<uint32_t> ids;
    for (size_t k = 0; k < big.size() && k < max_direct; ++k) ids.push_back(big[k].second);
    return ids;
}

// Batches smaller than this are traced on the calling thread: waking workers costs more.
constexpr size_t parallel_batch_threshold = 256;
constexpr size_t rays_per_task = 64;

void write_miss(ppm_hit &hit) {
    std::memset(&hit, 0, sizeof hit);
    hit.t = INFINITY;
    hit.geom_id = PPM_INVALID_ID;
}

} // namespace

void validate_ray(const ppm_ray &ray, size_t index) {
    auto bad = [&](const char *what) { invalid_argument("ray " + std::to_string(index) + ": " + what); };
    const Vec3 org = Vec3::from(ray.org), dir = Vec3::from(ray.dir);
    if (!is_finite(org)) bad("origin is not finite");
    if (!is_finite(dir)) bad("direction is not finite");
    const double dir_length2 = length2(dir);
    if (!(dir_length2 >= DBL_MIN) || !std::isfinite(dir_length2)) bad("direction is zero or too large to square");
    if (!(ray.tnear >= 0) || !std::isfinite(ray.tnear)) bad("tnear must be finite and >= 0");
    if (!(ray.tfar >= ray.tnear)) bad("tfar must be >= tnear (INFINITY allowed)");
}

Scene::Scene(Context &context) : context_(&context) { context_->retain(); }

Scene::~Scene() {
    if (rtc_scene_) rtcReleaseScene(rtc_scene_);
    geometries_.clear();
    context_->release();
}

uint32_t Scene::add(std::unique_ptr<Geometry> geometry) {
    if (geometries_.size() >= PPM_INVALID_ID - 1) invalid_argument("too many geometries in a scene");
    geometries_.push_back(std::move(geometry));
    prefers_mask_bit_.push_back(false);
    committed_ = false;
    return static_cast<uint32_t>(geometries_.size() - 1);
}

Geometry &Scene::geometry(uint32_t geom_id) const {
    if (geom_id >= geometries_.size())
        invalid_argument("geom_id " + std::to_string(geom_id) + " does not exist (the scene has " +
                         std::to_string(geometries_.size()) + " geometries)");
    return *geometries_[geom_id];
}

void Scene::prefer_mask_bit(uint32_t geom_id) {
    geometry(geom_id); // checks the id
    prefers_mask_bit_[geom_id] = true;
}

void Scene::set_tolerance(double relative) {
    if (!(relative >= 1e-14 && relative <= 1e-2))
        invalid_argument("tolerance " + format_number(relative) + " is outside [1e-14, 1e-2]");
    tolerance_ = relative;
    committed_ = false;
}

void Scene::set_patch_presplit(double per_edge) {
    if (!(per_edge >= min_patch_presplit && per_edge <= max_patch_presplit) || per_edge != std::floor(per_edge))
        invalid_argument("patch_presplit " + format_number(per_edge) + " is not a whole number in [" +
                         std::to_string(min_patch_presplit) + ", " + std::to_string(max_patch_presplit) + "]");
    patch_presplit_ = static_cast<int>(per_edge);
    committed_ = false;
}

void Scene::commit() {
    if (geometries_.empty()) fail(PPM_ERROR_INVALID_OPERATION, "cannot commit a scene without geometry");
    if (rtc_scene_) {
        rtcReleaseScene(rtc_scene_);
        rtc_scene_ = nullptr;
    }
    committed_ = false;

    Box3 bounds;
    for (auto &geometry : geometries_) bounds.extend(geometry->prepare(geometry->transform));
    const double diagonal = bounds.diagonal();
    if (!(diagonal > 0) || !std::isfinite(diagonal))
        invalid_argument("the scene's bounding box is empty, a point, or not finite");

    const Vec3 center = bounds.center();
    const double radius = std::max(max_abs_component(bounds.lower - center), max_abs_component(bounds.upper - center));
    // Float rounding of Embree's ray moves it by about 1e-7 of the scene's size; pad boxes by
    // a hundred times that, plus the tolerance within which a hit may be reported.
    frame_.center = center;
    frame_.tolerance = tolerance_ * diagonal;
    frame_.box_padding = 1e-5 * radius + frame_.tolerance;
    frame_.patch_presplit = patch_presplit_;

    RTCDevice device = context_->device();
    RTCScene rtc = rtcNewScene(device);
    context_->check_embree("rtcNewScene");
    rtcSetSceneFlags(rtc, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(rtc, RTC_BUILD_QUALITY_HIGH);
    try {
        direct_sphere_ids_ = direct_sphere_ids(geometries_, bounds);
        bvh_empty_ = direct_sphere_ids_.size() == geometries_.size();
        direct_spheres_.clear();
        for (uint32_t id : direct_sphere_ids_) {
            const SphereGeometry::Data &sphere = static_cast<const SphereGeometry &>(*geometries_[id]).data();
            direct_spheres_.add(sphere.center, sphere.radius);
        }
        assign_mask_bits();
        for (size_t id = 0; id < geometries_.size(); ++id) {
            if (std::find(direct_sphere_ids_.begin(), direct_sphere_ids_.end(), id) != direct_sphere_ids_.end())
                continue;
            RTCGeometry g = geometries_[id]->create_embree(device, frame_);
            context_->check_embree("creating Embree geometry");
            if (!g) fail(PPM_ERROR_OUT_OF_MEMORY, "creating Embree geometry failed");
            if (mask_bit_[id] != 0) {
                rtcSetGeometryMask(g, mask_bit_[id]);
                rtcCommitGeometry(g);
            }
            rtcAttachGeometryByID(rtc, g, static_cast<unsigned>(id));
            rtcReleaseGeometry(g);
            context_->check_embree("rtcAttachGeometryByID");
        }
        context_->run([&] { rtcCommitScene(rtc); });
        embree_build_joined();
        context_->check_embree("rtcCommitScene");
    } catch (...) {
        rtcReleaseScene(rtc);
        throw;
    }
    rtc_scene_ = rtc;
    bounds_ = bounds;
    query_box_ = bounds;
    query_box_.lower -= Vec3{1, 1, 1} * (2 * frame_.box_padding);
    query_box_.upper += Vec3{1, 1, 1} * (2 * frame_.box_padding);
    committed_ = true;
}

// Embree masks have 32 bits. The geometries that rays can skip get one each, those that asked
// first (prefer_mask_bit: the renderer's area lights, which every shadow ray runs to), then the
// other planar ones (rays leaving them); the rest keep
// Embree's full mask, so a ray's mask, all bits but those it skips, still reaches them. With
// more such geometries than bits, the callbacks skip the others themselves (test_quad).
void Scene::assign_mask_bits() {
    mask_bit_.assign(geometries_.size(), 0);
    leaving_mask_bit_.assign(geometries_.size(), 0);
    unsigned next_bit = 0;
    for (const bool preferred : {true, false})
        for (size_t id = 0; id < geometries_.size() && next_bit < 32; ++id) {
            const bool wanted = preferred ? prefers_mask_bit_[id] : geometries_[id]->planar();
            if (wanted && mask_bit_[id] == 0) mask_bit_[id] = 1u << next_bit++;
        }
    for (size_t id = 0; id < geometries_.size(); ++id)
        if (geometries_[id]->planar()) leaving_mask_bit_[id] = mask_bit_[id];
}

uint32_t Scene::ray_mask(const ppm_ray &ray, const RayHints &hints) const {
    uint32_t skip = 0;
    // A ray starting behind its origin (tnear < 0) may meet the plane it left.
    const ppm_hit *leaving = hints.leaving;
    if (leaving && ray.tnear >= 0 && leaving->geom_id < leaving_mask_bit_.size())
        skip |= leaving_mask_bit_[leaving->geom_id];
    if (hints.skip_geometry < mask_bit_.size()) skip |= mask_bit_[hints.skip_geometry];
    return ~skip;
}

void Scene::require_committed(const char *operation) const {
    if (!committed())
        fail(PPM_ERROR_INVALID_OPERATION,
             std::string(operation) + ": the scene is not committed (call ppm_scene_commit after changes)");
}

bool Scene::start_query(const ppm_ray &ray, bool any_hit, const RayHints &hints, RayQuery &query,
                        RTCRay &embree_ray) const {
    if (const ppm_hit *leaving = hints.leaving) {
        query.origin.geom_id = leaving->geom_id;
        query.origin.prim_id = leaving->prim_id;
        query.origin.u = leaving->u;
        query.origin.v = leaving->v;
        query.origin.p = Vec3::from(leaving->p);
    }
    query.org = Vec3::from(ray.org);
    query.dir = Vec3::from(ray.dir);
    query.tnear = ray.tnear;
    query.hit.t = ray.tfar;
    query.tolerance = frame_.tolerance;
    query.any_hit = any_hit;
    query.dir_length2 = dot(query.dir, query.dir);
    if (nearly_unit(query.dir_length2)) { // first-order terms, exact to rounding (vec3.h)
        query.inv_dir_length2 = 1 - (query.dir_length2 - 1);
        query.dir_length = 1 + 0.5 * (query.dir_length2 - 1);
    } else {
        query.inv_dir_length2 = 1.0 / query.dir_length2;
        query.dir_length = std::sqrt(query.dir_length2);
    }

    // Clip to the padded scene box in double, so Embree's float ray starts near the geometry
    // and its rounding stays relative to the scene's size, not to the origin's distance. A ray
    // starting inside the box (every ray a renderer spawns) starts at tnear either way; its far
    // end stays as given, which changes nothing (no geometry lies outside the box) and saves
    // three divisions.
    double t0 = ray.tnear, t1 = ray.tfar;
    const bool starts_inside = query.org.x >= query_box_.lower.x && query.org.x <= query_box_.upper.x &&
                               query.org.y >= query_box_.lower.y && query.org.y <= query_box_.upper.y &&
                               query.org.z >= query_box_.lower.z && query.org.z <= query_box_.upper.z;
    for (int axis = 0; axis < 3 && !starts_inside; ++axis) {
        const double o = query.org[axis], d = query.dir[axis];
        const double lo = query_box_.lower[axis], hi = query_box_.upper[axis];
        if (d == 0) {
            if (o < lo || o > hi) return false;
            continue;
        }
        // A reciprocal rounds t by an ulp more than a division; the box's padding covers that.
        const double inv_d = 1.0 / d;
        double ta = (lo - o) * inv_d, tb = (hi - o) * inv_d;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    if (!(t0 <= t1)) return false;

    query.t_shift = t0;
    if (bvh_empty_) return true; // Embree is not called: no float ray
    rtcInitIntersectContext(&query.embree);
    const Vec3 start = query.org + query.dir * t0 - frame_.center;
    const Vec3 unit = query.dir * (query.dir_length * query.inv_dir_length2); // 1/|d| = |d|/|d|^2
    embree_ray.org_x = static_cast<float>(start.x);
    embree_ray.org_y = static_cast<float>(start.y);
    embree_ray.org_z = static_cast<float>(start.z);
    embree_ray.dir_x = static_cast<float>(unit.x);
    embree_ray.dir_y = static_cast<float>(unit.y);
    embree_ray.dir_z = static_cast<float>(unit.z);
    embree_ray.tnear = 0.0f;
    embree_ray.tfar = query.embree_tfar(t1);
    embree_ray.time = 0.0f;
    embree_ray.mask = ray_mask(ray, hints); // masks are enabled in Debian's Embree build
    embree_ray.id = kSingleRayId;
    embree_ray.flags = 0;
    return true;
}

bool Scene::start_intersect(const ppm_ray &ray, const RayHints &hints, RayQuery &query, RTCRayHit &rayhit) const {
    if (!start_query(ray, false, hints, query, rayhit.ray)) return false;
    rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    // The big spheres first: a hit there shortens the ray Embree traverses.
    const int nearest = direct_spheres_.intersect(query);
    if (nearest >= 0) {
        query.hit.geom_id = direct_sphere_ids_[nearest];
        if (!bvh_empty_) rayhit.ray.tfar = std::min(rayhit.ray.tfar, query.embree_tfar(query.hit.t));
    }
    return true;
}

void Scene::intersect(const ppm_ray &ray, ppm_hit &hit, bool surface_uv, const RayHints &hints) const {
    RayQuery query;
    RTCRayHit rayhit;
    if (!start_intersect(ray, hints, query, rayhit)) return write_miss(hit);
    if (!bvh_empty_) rtcIntersect1(rtc_scene_, &query.embree, &rayhit);
    finish_intersect(query, hit, surface_uv);
}

void Scene::intersect_stream(const ppm_ray *rays, const RayHints *hints, size_t count, ppm_hit *hits,
                             bool surface_uv) const {
    RayQuery queries[max_stream];
    RTCRayHit rayhits[max_stream];
    bool started[max_stream];
    count = std::min(count, max_stream);
    for (size_t i = 0; i < count; ++i) {
        started[i] = start_intersect(rays[i], hints ? hints[i] : RayHints{}, queries[i], rayhits[i]);
        if (bvh_empty_) continue;
        rayhits[i].ray.id = static_cast<unsigned>(i);
        // A ray that misses the scene's box is not set up: Embree skips rays with tnear > tfar.
        if (!started[i]) {
            RTCRay &r = rayhits[i].ray;
            r.org_x = r.org_y = r.org_z = r.dir_x = r.dir_y = r.time = 0.0f;
            r.dir_z = 1.0f;
            r.tnear = 1.0f;
            r.tfar = 0.0f;
            r.mask = 0;
            r.flags = 0;
        }
    }
    if (!bvh_empty_) {
        StreamContext context;
        rtcInitIntersectContext(&context.embree);
        context.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        context.queries = queries;
        rtcIntersect1M(rtc_scene_, &context.embree, rayhits, static_cast<unsigned>(count), sizeof(RTCRayHit));
    }
    for (size_t i = 0; i < count; ++i) {
        if (started[i])
            finish_intersect(queries[i], hits[i], surface_uv);
        else
            write_miss(hits[i]);
    }
}

void Scene::finish_intersect(const RayQuery &query, ppm_hit &hit, bool surface_uv) const {
    if (!query.found) return write_miss(hit);
    // Every field is set below (describe_hit writes p, p_error, ng and ns).
    const Geometry &g = *geometries_[query.hit.geom_id];
    hit.reserved = 0;
    hit.t = query.hit.t;
    hit.u = query.hit.u;
    hit.v = query.hit.v;
    hit.geom_id = query.hit.geom_id;
    hit.prim_id = query.hit.prim_id;
    hit.material = g.material;
    g.describe_hit(query, frame_.tolerance, hit);
    if (g.flip_normals)
        for (int k = 0; k < 3; ++k) {
            hit.ng[k] = -hit.ng[k];
            hit.ns[k] = -hit.ns[k];
        }
    if (surface_uv) g.compute_uv(hit);
}

bool Scene::occluded(const ppm_ray &ray, const RayHints &hints) const {
    RayQuery query;
    RTCRay embree_ray;
    if (!start_query(ray, true, hints, query, embree_ray)) return false;
    if (direct_spheres_.occluded(query)) return true;
    if (bvh_empty_) return false;
    rtcOccluded1(rtc_scene_, &query.embree, &embree_ray);
    return query.found;
}

void Scene::intersect(const ppm_ray *rays, size_t count, ppm_hit *hits) const {
    require_committed("ppm_scene_intersect");
    for (size_t i = 0; i < count; ++i) validate_ray(rays[i], i);
    if (count < parallel_batch_threshold) {
        for (size_t i = 0; i < count; ++i) intersect(rays[i], hits[i]);
        return;
    }
    context_->run([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, count, rays_per_task),
                          [&](const tbb::blocked_range<size_t> &range) {
                              for (size_t i = range.begin(); i != range.end(); ++i) intersect(rays[i], hits[i]);
                          });
    });
}

void Scene::occluded(const ppm_ray *rays, size_t count, uint8_t *result) const {
    require_committed("ppm_scene_occluded");
    for (size_t i = 0; i < count; ++i) validate_ray(rays[i], i);
    if (count < parallel_batch_threshold) {
        for (size_t i = 0; i < count; ++i) result[i] = occluded(rays[i]) ? 1 : 0;
        return;
    }
    context_->run([&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, count, rays_per_task),
                          [&](const tbb::blocked_range<size_t> &range) {
                              for (size_t i = range.begin(); i != range.end(); ++i)
                                  result[i] = occluded(rays[i]) ? 1 : 0;
                          });
    });
}

} // namespace ppm
