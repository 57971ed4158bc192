// SPDX-License-Identifier: Apache-2.0
// The C ABI of contexts, scenes, ray queries and tessellation (api_render.cpp has materials,
// lights and the renderer). Only lib/api sees handles: it checks arguments, calls the C++
// objects and turns every exception into a ppm_status plus the per-thread message.
#include <ppm/ppm.h>

#include "api/api_keys.h"
#include "api/api_support.h"
#include "core/context.h"
#include "core/error.h"
#include "core/ref_counted.h"
#include "geometry/tessellate.h"
#include "io/bpt_reader.h"
#include "io/obj_reader.h"
#include "io/ply_reader.h"
#include "io/serialized_reader.h"
#include "scene/cylinder_geometry.h"
#include "scene/disk_geometry.h"
#include "scene/mesh_geometry.h"
#include "scene/patch_geometry.h"
#include "scene/quad_geometry.h"
#include "scene/scene.h"
#include "scene/spawn.h"
#include "scene/sphere_geometry.h"

#include <cstring>
#include <new>
#include <string>

namespace {

using namespace ppm::api;
using ppm::invalid_argument;

// A mesh read from a file. One without normals gets Mitsuba's computed vertex normals (its
// mesh plugins do so unless face_normals is set), so a file shades as in Mitsuba.
std::unique_ptr<ppm::MeshGeometry> mesh_from_file(ppm::MeshData mesh) {
    auto geometry = std::make_unique<ppm::MeshGeometry>(std::move(mesh));
    geometry->compute_vertex_normals();
    return geometry;
}

// The patches of `control_points` (ppm_scene_add_bezier_patches' layout), checked.
std::vector<ppm::BezierPatch> read_patches(const double *control_points, size_t patch_count) {
    require(control_points, "control_points");
    if (patch_count == 0) invalid_argument("patch_count is 0");
    if (patch_count > ppm::max_bpt_patches)
        invalid_argument("patch_count " + std::to_string(patch_count) + " exceeds the limit of " +
                         std::to_string(ppm::max_bpt_patches));
    std::vector<ppm::BezierPatch> patches;
    ppm::allocate_or_fail(std::to_string(patch_count) + " Bezier patches", patch_count * sizeof(ppm::BezierPatch),
                          [&] { patches.resize(patch_count); });
    for (size_t p = 0; p < patch_count; ++p)
        for (int k = 0; k < 16; ++k) {
            patches[p].p[k] = ppm::Vec3::from(control_points + (p * 16 + k) * 3);
            if (!ppm::is_finite(patches[p].p[k]))
                invalid_argument("patch " + std::to_string(p) + " control point " + std::to_string(k) +
                                 " has a NaN or infinite coordinate");
        }
    return patches;
}

// `make` validates its input and returns the new geometry (or throws).
// Throws INVALID_ARGUMENT unless the geometry's box under `transform` lies within the
// coordinate limit (math/limits.h), so that commit never meets an overflowing box.
void check_world_box(const ppm::Geometry &geometry, const ppm::Affine &transform) {
    const ppm::Box3 box = geometry.world_bounds(transform);
    for (const double v : {box.lower.x, box.lower.y, box.lower.z, box.upper.x, box.upper.y, box.upper.z})
        if (!ppm::within(v, ppm::kCoordinateLimit))
            invalid_argument(std::string("the bounding box of the ") + geometry.kind() + " reaches the coordinate " +
                             ppm::format_number(v) + ", beyond +-" + ppm::format_number(ppm::kCoordinateLimit) +
                             " (the limit of scene coordinates)");
}

template <class Make> ppm_status add_geometry(ppm_scene scene, uint32_t *out_geom_id, Make &&make) {
    return scene_call(scene, [&](ppm::Scene &s) {
        std::unique_ptr<ppm::Geometry> geometry = make();
        check_world_box(*geometry, geometry->transform);
        write_id(out_geom_id, s.add(std::move(geometry)));
    });
}

constexpr Key kContextKeyList[] = {{"threads", KeyType::Int}};
constexpr KeyTable kContextKeys("context setting", kContextKeyList);

constexpr Key kSceneKeyList[] = {{"tolerance", KeyType::Double}, {"patch_presplit", KeyType::Int}};
constexpr KeyTable kSceneKeys("scene setting", kSceneKeyList);

void set_context_int(ppm_context context, const char *key, int64_t value) {
    kContextKeys.find(key); // "threads" is the only key
    if (value < 0 || value > 1024)
        invalid_argument("threads must be 0 (all hardware threads) or 1..1024, not " + std::to_string(value));
    context->set_threads(static_cast<int>(value));
}

bool is_key(const char *key, const char *name) { return std::strcmp(key, name) == 0; }

} // namespace

std::string &ppm::api::last_error() {
    thread_local std::string message;
    return message;
}

extern "C" {

uint32_t ppm_version(void) { return PPM_VERSION; }
const char *ppm_version_string(void) { return PPM_VERSION_STRING; }

const char *ppm_status_string(ppm_status status) {
    switch (status) {
    case PPM_OK: return "ok";
    case PPM_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case PPM_ERROR_INVALID_OPERATION: return "invalid operation";
    case PPM_ERROR_OUT_OF_MEMORY: return "out of memory";
    case PPM_ERROR_IO: return "input/output error";
    case PPM_ERROR_PARSE: return "parse error";
    case PPM_ERROR_UNSUPPORTED: return "unsupported";
    case PPM_ERROR_CANCELLED: return "cancelled";
    case PPM_ERROR_INTERNAL: return "internal error";
    }
    return "unknown status";
}

const char *ppm_last_error_message(void) { return last_error().c_str(); }

/* Context ----------------------------------------------------------------------------- */

ppm_status ppm_context_create(ppm_context *out_context) {
    return guarded(nullptr, [&] {
        require(out_context, "out_context");
        *out_context = new ppm_context_t();
    });
}

ppm_status ppm_context_retain(ppm_context context) {
    return guarded(nullptr, [&] {
        require(context, "context");
        context->retain();
    });
}

void ppm_context_release(ppm_context context) {
    if (context) context->release();
}

ppm_status ppm_context_set_int(ppm_context context, const char *key, int64_t value) {
    return guarded(context, [&] {
        require(context, "context");
        set_context_int(context, key, value);
    });
}

ppm_status ppm_context_set_double(ppm_context context, const char *key, double value) {
    return guarded(context, [&] {
        require(context, "context");
        kContextKeys.find(key);
        set_context_int(context, key, kContextKeys.whole_number(key, value));
    });
}

ppm_status ppm_context_get_int(ppm_context context, const char *key, int64_t *out_value) {
    return guarded(context, [&] {
        require(context, "context");
        kContextKeys.require_int(key);
        require(out_value, "out_value");
        *out_value = context->threads();
    });
}

ppm_status ppm_context_get_double(ppm_context context, const char *key, double *out_value) {
    return guarded(context, [&] {
        require(context, "context");
        kContextKeys.find(key);
        require(out_value, "out_value");
        *out_value = context->threads();
    });
}

ppm_status ppm_context_set_error_callback(ppm_context context, ppm_error_callback callback, void *user_data) {
    return guarded(nullptr, [&] {
        require(context, "context");
        context->set_error_callback(callback, user_data);
    });
}

ppm_status ppm_context_set_warning_callback(ppm_context context, ppm_warning_callback callback, void *user_data) {
    return guarded(nullptr, [&] {
        require(context, "context");
        context->set_warning_callback(callback, user_data);
    });
}

/* Scene ------------------------------------------------------------------------------- */

ppm_status ppm_scene_create(ppm_context context, ppm_scene *out_scene) {
    return guarded(context, [&] {
        require(context, "context");
        require(out_scene, "out_scene");
        *out_scene = new ppm_scene_t(*context);
    });
}

ppm_status ppm_scene_retain(ppm_scene scene) {
    return scene_call(scene, [](ppm::Scene &s) { s.retain(); });
}

void ppm_scene_release(ppm_scene scene) {
    if (scene) scene->release();
}

ppm_status ppm_scene_set_int(ppm_scene scene, const char *key, int64_t value) {
    return scene_call(scene, [&](ppm::Scene &s) {
        kSceneKeys.find(key);
        if (is_key(key, "tolerance"))
            s.set_tolerance(static_cast<double>(value));
        else
            s.set_patch_presplit(static_cast<double>(value));
    });
}

ppm_status ppm_scene_get_int(ppm_scene scene, const char *key, int64_t *out_value) {
    return scene_call(scene, [&](ppm::Scene &s) {
        kSceneKeys.require_int(key); // "patch_presplit" is the only integer key
        require(out_value, "out_value");
        *out_value = s.patch_presplit();
    });
}

// patch_presplit keeps its own check of a fractional double, whose message names its range.
ppm_status ppm_scene_set_double(ppm_scene scene, const char *key, double value) {
    return scene_call(scene, [&](ppm::Scene &s) {
        kSceneKeys.find(key);
        if (is_key(key, "tolerance"))
            s.set_tolerance(value);
        else
            s.set_patch_presplit(value);
    });
}

ppm_status ppm_scene_get_double(ppm_scene scene, const char *key, double *out_value) {
    return scene_call(scene, [&](ppm::Scene &s) {
        kSceneKeys.find(key);
        require(out_value, "out_value");
        *out_value = is_key(key, "tolerance") ? s.tolerance() : s.patch_presplit();
    });
}

ppm_status ppm_scene_add_bezier_patches(ppm_scene scene, const double *control_points, size_t patch_count,
                                        uint32_t *out_geom_id) {
    return add_geometry(scene, out_geom_id, [&] {
        std::vector<ppm::BezierPatch> patches = read_patches(control_points, patch_count);
        return std::make_unique<ppm::PatchGeometry>(std::move(patches));
    });
}

ppm_status ppm_scene_load_bpt(ppm_scene scene, const char *path, uint32_t *out_geom_id) {
    return add_geometry(scene, out_geom_id, [&] {
        require(path, "path");
        return std::make_unique<ppm::PatchGeometry>(ppm::read_bpt_file(path));
    });
}

ppm_status ppm_scene_add_sphere(ppm_scene scene, const double center[3], double radius, uint32_t *out_geom_id) {
    return add_geometry(scene, out_geom_id, [&] {
        const ppm::Vec3 c = finite_point(center, "center");
        if (!(radius > 0) || !(radius <= ppm::kCoordinateLimit))
            invalid_argument("sphere radius must lie in (0, " + ppm::format_number(ppm::kCoordinateLimit) + "], not " +
                             ppm::format_number(radius));
        return std::make_unique<ppm::SphereGeometry>(c, radius);
    });
}

ppm_status ppm_scene_add_disk(ppm_scene scene, const double center[3], const double axis_u[3], const double axis_v[3],
                              uint32_t *out_geom_id) {
    return add_geometry(scene, out_geom_id, [&] {
        const ppm::Vec3 c = finite_point(center, "center");
        const ppm::Vec3 au = finite_point(axis_u, "axis_u");
        const ppm::Vec3 av = finite_point(axis_v, "axis_v");
        const double area = ppm::length(ppm::cross(au, av));
        if (!(area > 1e-12 * ppm::length(au) * ppm::length(av)) || !std::isfinite(area))
            invalid_argument("disk axes are zero or parallel: the disk has no area");
        return std::make_unique<ppm::DiskGeometry>(c, au, av);
    });
}

ppm_status ppm_scene_add_cylinder(ppm_scene scene, const double p0[3], const double p1[3], double radius,
                                  uint32_t *out_geom_id) {
    return add_geometry(scene, out_geom_id, [&] {
        const ppm::Vec3 a = finite_point(p0, "p0"), b = finite_point(p1, "p1");
        if (!(radius > 0) || !(radius <= ppm::kCoordinateLimit))
            invalid_argument("cylinder radius must lie in (0, " + ppm::format_number(ppm::kCoordinateLimit) +
                             "], not " + ppm::format_number(radius));
        if (!(ppm::length(b - a) > 1e-12 * std::max(ppm::max_abs_component(a), ppm::max_abs_component(b))) ||
            ppm::length(b - a) == 0)
            invalid_argument("cylinder p0 and p1 are equal: the cylinder has no length");
        return std::make_unique<ppm::CylinderGeometry>(a, b, radius);
    });
}

ppm_status ppm_scene_set_geometry_flip_normals(ppm_scene scene, uint32_t geom_id, int flip) {
    return scene_call(scene, [&](ppm::Scene &s) {
        ppm::Geometry &g = s.geometry(geom_id);
        if (dynamic_cast<ppm::SphereGeometry *>(&g) || dynamic_cast<ppm::PatchGeometry *>(&g))
            invalid_argument("geometry " + std::to_string(geom_id) + " is a " + g.kind() +
                             "; flip_normals is supported on triangle meshes, quads, disks and cylinders");
        if (g.flip_normals != (flip != 0)) s.mark_modified();
        g.flip_normals = flip != 0;
    });
}

ppm_status ppm_scene_set_mesh_face_normals(ppm_scene scene, uint32_t geom_id, int face_normals) {
    return scene_call(scene, [&](ppm::Scene &s) {
        ppm::Geometry &g = s.geometry(geom_id);
        auto *mesh = dynamic_cast<ppm::MeshGeometry *>(&g);
        if (!mesh)
            invalid_argument("geometry " + std::to_string(geom_id) + " is a " + g.kind() +
                             "; face_normals applies to triangle meshes");
        if (face_normals && mesh->has_vertex_normals()) {
            mesh->drop_vertex_normals();
            s.mark_modified();
        }
    });
}

ppm_status ppm_scene_add_quad(ppm_scene scene, const double origin[3], const double edge_u[3], const double edge_v[3],
                              uint32_t *out_geom_id) {
    return add_geometry(scene, out_geom_id, [&] {
        const ppm::Vec3 o = finite_point(origin, "origin");
        const ppm::Vec3 eu = finite_point(edge_u, "edge_u");
        const ppm::Vec3 ev = finite_point(edge_v, "edge_v");
        const double area = ppm::length(ppm::cross(eu, ev));
        if (!(area > 1e-12 * ppm::length(eu) * ppm::length(ev)) || !std::isfinite(area))
            invalid_argument("quad edges are zero or parallel: the quad has no area");
        return std::make_unique<ppm::QuadGeometry>(o, eu, ev);
    });
}

ppm_status ppm_scene_add_triangle_mesh(ppm_scene scene, const double *positions, size_t vertex_count,
                                       const uint32_t *indices, size_t triangle_count, const double *normals,
                                       const double *uvs, uint32_t *out_geom_id) {
    return add_geometry(scene, out_geom_id, [&] {
        require(positions, "positions");
        require(indices, "indices");
        if (vertex_count == 0 || triangle_count == 0) invalid_argument("mesh has no vertices or no triangles");
        if (vertex_count >= PPM_INVALID_ID || triangle_count >= PPM_INVALID_ID / 3)
            invalid_argument("mesh is too large (at most 2^32 - 1 vertices and 2^32 / 3 triangles)");
        ppm::MeshData mesh;
        const std::uint64_t vertex_bytes = sizeof(ppm::Vec3) * (normals ? 2 : 1) + (uvs ? 2 * sizeof(double) : 0);
        const std::uint64_t mesh_bytes = vertex_count * vertex_bytes + triangle_count * 3 * sizeof(uint32_t);
        ppm::allocate_or_fail("a mesh of " + std::to_string(vertex_count) + " vertices and " +
                                  std::to_string(triangle_count) + " triangles",
                              mesh_bytes, [&] {
                                  mesh.positions.resize(vertex_count);
                                  mesh.indices.reserve(3 * triangle_count);
                                  if (normals) mesh.normals.reserve(vertex_count);
                                  if (uvs) mesh.uvs.reserve(2 * vertex_count);
                              });
        for (size_t k = 0; k < vertex_count; ++k) {
            mesh.positions[k] = ppm::Vec3::from(positions + 3 * k);
            if (!ppm::is_finite(mesh.positions[k]))
                invalid_argument("vertex " + std::to_string(k) + " has a NaN or infinite coordinate");
        }
        mesh.indices.assign(indices, indices + 3 * triangle_count);
        for (size_t k = 0; k < mesh.indices.size(); ++k)
            if (mesh.indices[k] >= vertex_count)
                invalid_argument("triangle " + std::to_string(k / 3) + " uses vertex " +
                                 std::to_string(mesh.indices[k]) + " of " + std::to_string(vertex_count));
        if (normals) {
            mesh.normals.resize(vertex_count);
            for (size_t k = 0; k < vertex_count; ++k) {
                mesh.normals[k] = ppm::Vec3::from(normals + 3 * k);
                if (!ppm::is_finite(mesh.normals[k]))
                    invalid_argument("normal " + std::to_string(k) + " has a NaN or infinite coordinate");
            }
        }
        if (uvs) {
            mesh.uvs.assign(uvs, uvs + 2 * vertex_count);
            for (size_t k = 0; k < mesh.uvs.size(); ++k)
                if (!std::isfinite(mesh.uvs[k]))
                    invalid_argument("uv " + std::to_string(k / 2) + " is NaN or infinite");
        }
        return std::make_unique<ppm::MeshGeometry>(std::move(mesh));
    });
}

ppm_status ppm_scene_load_obj(ppm_scene scene, const char *path, uint32_t *out_geom_id) {
    return add_geometry(scene, out_geom_id, [&] {
        require(path, "path");
        return mesh_from_file(ppm::read_obj_file(path));
    });
}

ppm_status ppm_scene_load_ply(ppm_scene scene, const char *path, uint32_t *out_geom_id) {
    return add_geometry(scene, out_geom_id, [&] {
        require(path, "path");
        ppm::PlyMesh ply = ppm::read_ply_file(path);
        for (const std::string &warning : ply.warnings) scene->context().warn(warning);
        return mesh_from_file(std::move(ply.mesh));
    });
}

ppm_status ppm_scene_load_serialized(ppm_scene scene, const char *path, uint32_t shape_index, uint32_t *out_geom_id) {
    return add_geometry(scene, out_geom_id, [&] {
        require(path, "path");
        ppm::SerializedMesh serialized = ppm::read_serialized_file(path, shape_index);
        if (serialized.had_colours)
            scene->context().warn(std::string(path) + ": mesh " + std::to_string(shape_index) +
                                  ": vertex colours are ignored");
        std::unique_ptr<ppm::MeshGeometry> mesh = mesh_from_file(std::move(serialized.mesh));
        if (serialized.face_normals) mesh->drop_vertex_normals();
        return mesh;
    });
}

ppm_status ppm_scene_set_geometry_transform(ppm_scene scene, uint32_t geom_id, const double matrix[16]) {
    return scene_call(scene, [&](ppm::Scene &s) {
        ppm::Geometry &g = s.geometry(geom_id);
        require(matrix, "matrix");
        ppm::Affine transform;
        for (int k = 0; k < 16; ++k)
            if (!std::isfinite(matrix[k])) invalid_argument("matrix element " + std::to_string(k) + " is not finite");
        if (matrix[12] != 0 || matrix[13] != 0 || matrix[14] != 0 || matrix[15] != 1)
            invalid_argument(
                "the last row of the matrix must be (0, 0, 0, 1): projective transforms are not supported");
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) transform.m[r][c] = matrix[4 * r + c];
        const double det = transform.determinant();
        double scale = 0;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) scale = std::max(scale, std::fabs(transform.m[r][c]));
        if (!(std::fabs(det) > 1e-12 * scale * scale * scale)) invalid_argument("the matrix's upper 3x3 is singular");
        try {
            g.check_transform(transform);
            check_world_box(g, transform);
        } catch (const ppm::Error &e) {
            invalid_argument("geometry " + std::to_string(geom_id) + " (" + g.kind() + "): " + e.what());
        }
        g.transform = transform;
        s.mark_modified();
    });
}

ppm_status ppm_scene_set_geometry_material(ppm_scene scene, uint32_t geom_id, uint32_t material_id) {
    return scene_call(scene, [&](ppm::Scene &s) {
        s.geometry(geom_id).material = material_id;
        s.mark_modified();
    });
}

ppm_status ppm_scene_get_primitive_count(ppm_scene scene, uint32_t geom_id, size_t *out_count) {
    return scene_call(scene, [&](ppm::Scene &s) {
        const ppm::Geometry &g = s.geometry(geom_id);
        require(out_count, "out_count");
        *out_count = g.primitive_count();
    });
}

ppm_status ppm_scene_get_geometry_count(ppm_scene scene, size_t *out_count) {
    return scene_call(scene, [&](ppm::Scene &s) {
        require(out_count, "out_count");
        *out_count = s.geometry_count();
    });
}

ppm_status ppm_scene_get_bezier_patches(ppm_scene scene, uint32_t geom_id, double *out, size_t capacity) {
    return scene_call(scene, [&](ppm::Scene &s) {
        const auto *patches = dynamic_cast<const ppm::PatchGeometry *>(&s.geometry(geom_id));
        if (!patches) invalid_argument("geometry " + std::to_string(geom_id) + " is not a patch set");
        if (!s.committed()) ppm::fail(PPM_ERROR_INVALID_OPERATION, "the scene is not committed");
        require(out, "out");
        const std::vector<ppm::BezierPatch> &world = patches->world_patches();
        if (capacity < world.size() * 48)
            invalid_argument("out holds " + std::to_string(capacity) + " doubles; " + std::to_string(world.size()) +
                             " patches need " + std::to_string(world.size() * 48));
        for (const ppm::BezierPatch &patch : world)
            for (const ppm::Vec3 &p : patch.p) *out++ = p.x, *out++ = p.y, *out++ = p.z;
    });
}

ppm_status ppm_scene_commit(ppm_scene scene) {
    return scene_call(scene, [](ppm::Scene &s) { s.commit(); });
}

ppm_status ppm_scene_get_bounds(ppm_scene scene, double out_lower[3], double out_upper[3]) {
    return scene_call(scene, [&](ppm::Scene &s) {
        require(out_lower, "out_lower");
        require(out_upper, "out_upper");
        if (!s.committed()) ppm::fail(PPM_ERROR_INVALID_OPERATION, "ppm_scene_get_bounds: the scene is not committed");
        s.bounds().lower.store(out_lower);
        s.bounds().upper.store(out_upper);
    });
}

ppm_status ppm_scene_intersect(ppm_scene scene, const ppm_ray *rays, size_t count, ppm_hit *hits) {
    return scene_call(scene, [&](ppm::Scene &s) {
        if (count == 0) return;
        require(rays, "rays");
        require(hits, "hits");
        s.intersect(rays, count, hits);
    });
}

ppm_status ppm_scene_occluded(ppm_scene scene, const ppm_ray *rays, size_t count, uint8_t *occluded) {
    return scene_call(scene, [&](ppm::Scene &s) {
        if (count == 0) return;
        require(rays, "rays");
        require(occluded, "occluded");
        s.occluded(rays, count, occluded);
    });
}

ppm_status ppm_hit_spawn_ray(const ppm_hit *hit, const double dir[3], ppm_ray *out_ray) {
    return guarded(nullptr, [&] {
        require(hit, "hit");
        require(out_ray, "out_ray");
        const ppm::Vec3 d = finite_point(dir, "dir");
        if (!(ppm::length2(d) > 0)) invalid_argument("dir is zero");
        if (hit->geom_id == PPM_INVALID_ID) invalid_argument("hit is a miss: there is no surface to leave");
        const ppm::Vec3 p = ppm::Vec3::from(hit->p), n = ppm::Vec3::from(hit->ng);
        if (!ppm::is_finite(p) || !ppm::is_finite(n) || !std::isfinite(hit->p_error) || hit->p_error < 0)
            invalid_argument("hit has a NaN or infinite point, normal or p_error");
        *out_ray = ppm::spawn_ray(*hit, d);
    });
}

} // extern "C"

/* Tessellation ------------------------------------------------------------------------ */

struct ppm_mesh_t : ppm::RefCounted {
    ppm_mesh_t(ppm::PatchMesh m, double t) : mesh(std::move(m)), tolerance(t) {}
    const ppm::PatchMesh mesh;
    const double tolerance;
};

namespace {

constexpr uint32_t max_tessellation_grid = 4096;

template <class Body> ppm_status mesh_call(ppm_mesh mesh, Body &&body) noexcept {
    return guarded(nullptr, [&] {
        require(mesh, "mesh");
        body(mesh->mesh);
    });
}

template <class T> void write_out(T *out, T value) {
    if (out) *out = value;
}

} // namespace

extern "C" {

ppm_status ppm_tessellate_patches(const double *control_points, size_t patch_count, double tolerance, uint32_t grid,
                                  ppm_mesh *out_mesh) {
    return guarded(nullptr, [&] {
        require(out_mesh, "out_mesh");
        const std::vector<ppm::BezierPatch> patches = read_patches(control_points, patch_count);
        if (grid > max_tessellation_grid)
            invalid_argument("grid " + std::to_string(grid) + " exceeds the limit of " +
                             std::to_string(max_tessellation_grid));
        if (grid == 0 && (!(tolerance > 0) || !std::isfinite(tolerance)))
            invalid_argument("tolerance must be finite and > 0 for an adaptive tessellation (grid 0), not " +
                             ppm::format_number(tolerance));
        ppm::PatchMesh mesh =
            grid > 0 ? ppm::tessellate_uniform(patches, grid) : ppm::tessellate_adaptive(patches, tolerance);
        *out_mesh = new ppm_mesh_t(std::move(mesh), grid > 0 ? 0.0 : tolerance);
    });
}

ppm_status ppm_mesh_retain(ppm_mesh mesh) {
    return guarded(nullptr, [&] {
        require(mesh, "mesh");
        mesh->retain();
    });
}

void ppm_mesh_release(ppm_mesh mesh) {
    if (mesh) mesh->release();
}

ppm_status ppm_mesh_get_vertices(ppm_mesh mesh, const double **out_positions, const double **out_normals,
                                 const double **out_uvs, size_t *out_vertex_count) {
    return mesh_call(mesh, [&](const ppm::PatchMesh &m) {
        write_out(out_positions, m.positions.data());
        write_out(out_normals, m.normals.data());
        write_out(out_uvs, m.uvs.data());
        write_out(out_vertex_count, m.vertex_count());
    });
}

ppm_status ppm_mesh_get_triangles(ppm_mesh mesh, const uint32_t **out_indices, size_t *out_triangle_count) {
    return mesh_call(mesh, [&](const ppm::PatchMesh &m) {
        write_out(out_indices, m.indices.data());
        write_out(out_triangle_count, m.triangle_count());
    });
}

ppm_status ppm_mesh_get_triangle_patches(ppm_mesh mesh, const uint32_t **out_patch_ids) {
    return mesh_call(mesh, [&](const ppm::PatchMesh &m) {
        require(out_patch_ids, "out_patch_ids");
        *out_patch_ids = m.triangle_patch.data();
    });
}

ppm_status ppm_mesh_get_welded_vertices(ppm_mesh mesh, const uint32_t **out_welded_ids, size_t *out_welded_count) {
    return mesh_call(mesh, [&](const ppm::PatchMesh &m) {
        write_out(out_welded_ids, m.welded.data());
        write_out(out_welded_count, size_t(m.welded_count));
    });
}

ppm_status ppm_mesh_get_double(ppm_mesh mesh, const char *key, double *out_value) {
    return guarded(nullptr, [&] {
        require(mesh, "mesh");
        require_key(key);
        require(out_value, "out_value");
        if (std::strcmp(key, "max_deviation") == 0)
            *out_value = mesh->mesh.max_deviation;
        else if (std::strcmp(key, "tolerance") == 0)
            *out_value = mesh->tolerance;
        else
            invalid_argument(std::string("unknown mesh property '") + key + "' (known: max_deviation, tolerance)");
    });
}

} // extern "C"
