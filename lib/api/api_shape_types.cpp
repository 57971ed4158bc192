// SPDX-License-Identifier: Apache-2.0
// ppm_scene_add_shape: one function per shape type, each reading its parameters with Mitsuba
// 3's names and defaults (src/shapes/*.cpp) and building the geometry through the typed calls
// of ppm.h. A new type is a function and a row of kShapeTypes.
//
// Parameters every type takes: `to_world` (a 4 x 4 row-major transform, default the identity;
// a shape that can hold it in its own parameters takes it there, the others get it as the
// geometry's transform) and `bsdf` (a material id; default: the scene's default material).
// `flip_normals` (0 or 1) on every type but sphere and bezier, whose two sides are alike.
#include <ppm/ppm.h>

#include "api/api_params.h"
#include "api/api_support.h"
#include "api/api_type_tables.h"
#include "geometry/cube_mesh.h"
#include "math/frame.h"
#include "scenefile/transform.h"

#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace {

using ppm::Affine;
using ppm::Vec3;
using ppm::api::Params;

// A typed call's failure, with the message it left, as this call's.
void check(ppm_status status) {
    if (status != PPM_OK) throw ppm::Error(status, ppm::api::last_error());
}

std::array<double, 3> array3(const Vec3 &v) { return {v.x, v.y, v.z}; }

// What the type functions leave for the common tail of ppm_scene_add_shape.
struct Placed {
    uint32_t geom = 0;
    bool transform_geometry = false; // to_world goes to the geometry (it is not in its parameters)
    bool mirrored_normal = false;    // the shape's normal must be flipped to be Mitsuba's
};

uint32_t add_sphere(ppm_scene_t &scene, Params &p, Placed &placed) {
    const std::array<double, 3> center = array3(p.vec3("center", {0, 0, 0}));
    const double radius = p.positive("radius", 1.0);
    p.finish();
    uint32_t geom = 0;
    check(ppm_scene_add_sphere(&scene, center.data(), radius, &geom));
    placed.transform_geometry = true;
    return geom;
}

// A parallelogram placed by to_world, whose normal is Mitsuba's: to_world's inverse transpose
// applied to +z, reversed from edge_u x edge_v by a mirroring to_world.
uint32_t add_parallelogram(ppm_scene_t &scene, Params &p, const Affine &to_world, const Vec3 &origin,
                           const Vec3 &edge_u, const Vec3 &edge_v, bool mitsuba_normal, Placed &placed) {
    p.finish();
    const std::array<double, 3> o = array3(to_world.point(origin)), u = array3(to_world.vector(edge_u)),
                                v = array3(to_world.vector(edge_v));
    uint32_t geom = 0;
    check(ppm_scene_add_quad(&scene, o.data(), u.data(), v.data(), &geom));
    placed.mirrored_normal = mitsuba_normal && to_world.determinant() < 0;
    return geom;
}

// Mitsuba's rectangle: [-1, 1]^2 at z = 0 with normal +z.
uint32_t add_rectangle(ppm_scene_t &scene, Params &p, Placed &placed) {
    return add_parallelogram(scene, p, p.transform("to_world", {}), {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, true, placed);
}

// libppm's parallelogram by its corner and edges (normal edge_u x edge_v).
uint32_t add_quad(ppm_scene_t &scene, Params &p, Placed &placed) {
    for (const char *name : {"origin", "edge_u", "edge_v"})
        if (!p.has(name)) p.fail(name, "must be given");
    const Vec3 origin = p.vec3("origin", {}), edge_u = p.vec3("edge_u", {}), edge_v = p.vec3("edge_v", {});
    return add_parallelogram(scene, p, p.transform("to_world", {}), origin, edge_u, edge_v, false, placed);
}

// Mitsuba's disk: the unit disk at z = 0 with normal +z, placed by to_world; its normal is
// to_world's inverse transpose applied to +z, which is (x axis) x (y axis) / det: reversed by
// a mirroring to_world.
uint32_t add_disk(ppm_scene_t &scene, Params &p, Placed &placed) {
    const Affine to_world = p.transform("to_world", {});
    const std::array<double, 3> c = array3(to_world.point({0, 0, 0})), u = array3(to_world.vector({1, 0, 0})),
                                v = array3(to_world.vector({0, 1, 0}));
    p.finish();
    uint32_t geom = 0;
    check(ppm_scene_add_disk(&scene, c.data(), u.data(), v.data(), &geom));
    placed.mirrored_normal = to_world.determinant() < 0;
    return geom;
}

// Mitsuba's cylinder: p0 (0, 0, 0), p1 (0, 0, 1), radius 1, then to_world; the tube must stay
// circular in the world (to_world may stretch along the axis only).
uint32_t add_cylinder(ppm_scene_t &scene, Params &p, Placed &) {
    const Vec3 p0 = p.vec3("p0", {0, 0, 0}), p1 = p.vec3("p1", {0, 0, 1});
    const double radius = p.positive("radius", 1.0);
    const Affine to_world = p.transform("to_world", {});
    if (!(ppm::length(p1 - p0) > 0))
        p.fail("p1", "must differ from p0: p0 and p1 are equal, so the cylinder has no length");
    Vec3 e1, e2;
    ppm::orthonormal_basis(ppm::normalize(p1 - p0), e1, e2);
    const Vec3 w0 = to_world.point(p0), w1 = to_world.point(p1);
    const Vec3 x = to_world.vector(e1 * radius), y = to_world.vector(e2 * radius), axis = w1 - w0;
    const double lx = ppm::length(x), ly = ppm::length(y), la = ppm::length(axis);
    const double eps = 1e-6;
    if (std::fabs(lx - ly) > eps * lx || std::fabs(ppm::dot(x, y)) > eps * lx * ly ||
        std::fabs(ppm::dot(x, axis)) > eps * lx * la || std::fabs(ppm::dot(y, axis)) > eps * ly * la)
        p.fail("to_world", "must keep a cylinder circular: no shear or non-uniform scaling across its axis");
    const std::array<double, 3> a = array3(w0), b = array3(w1);
    p.finish();
    uint32_t geom = 0;
    check(ppm_scene_add_cylinder(&scene, a.data(), b.data(), lx, &geom));
    return geom;
}

// Mitsuba's cube: [-1, 1]^3, 12 triangles with face normals.
uint32_t add_cube(ppm_scene_t &scene, Params &p, Placed &placed) {
    p.finish();
    const ppm::MeshData cube = ppm::cube_mesh();
    std::vector<double> positions, normals;
    for (std::size_t i = 0; i < cube.positions.size(); ++i)
        for (int axis = 0; axis < 3; ++axis) {
            positions.push_back(cube.positions[i][axis]);
            normals.push_back(cube.normals[i][axis]);
        }
    uint32_t geom = 0;
    check(ppm_scene_add_triangle_mesh(&scene, positions.data(), cube.positions.size(), cube.indices.data(),
                                      cube.indices.size() / 3, normals.data(), cube.uvs.data(), &geom));
    placed.transform_geometry = true;
    return geom;
}

std::string filename(Params &p) {
    if (!p.has("filename")) p.fail("filename", "must be given");
    const std::string name = p.string("filename", "");
    if (name.empty()) p.fail("filename", "must not be empty");
    return name;
}

// A mesh file, read by `load` once every parameter is known; `face_normals` (0 or 1, default
// 0) is Mitsuba's flat shading.
uint32_t add_mesh_file(ppm_scene_t &scene, Params &p, Placed &placed,
                       const std::function<ppm_status(const char *, uint32_t *)> &load) {
    const std::string path = filename(p);
    const bool face_normals = p.boolean("face_normals", false);
    p.finish();
    uint32_t geom = 0;
    check(load(path.c_str(), &geom));
    if (face_normals) check(ppm_scene_set_mesh_face_normals(&scene, geom, 1));
    placed.transform_geometry = true;
    return geom;
}

uint32_t add_obj(ppm_scene_t &scene, Params &p, Placed &placed) {
    return add_mesh_file(scene, p, placed,
                         [&](const char *path, uint32_t *geom) { return ppm_scene_load_obj(&scene, path, geom); });
}

uint32_t add_ply(ppm_scene_t &scene, Params &p, Placed &placed) {
    return add_mesh_file(scene, p, placed,
                         [&](const char *path, uint32_t *geom) { return ppm_scene_load_ply(&scene, path, geom); });
}

uint32_t add_serialized(ppm_scene_t &scene, Params &p, Placed &placed) {
    const double index = p.number_in("shape_index", 0, 4294967295.0, 0);
    if (index != std::floor(index)) p.fail("shape_index", "must be a whole number");
    const uint32_t shape_index = static_cast<uint32_t>(index);
    return add_mesh_file(scene, p, placed, [&](const char *path, uint32_t *geom) {
        return ppm_scene_load_serialized(&scene, path, shape_index, geom);
    });
}

// libppm's bicubic Bezier patches: a .bpt `filename`, or `patches` (48 numbers per patch: 16
// control points, row by row), and optionally `uv_rects` (4 numbers per patch: the (u, v)
// rectangle its texture coordinates span).
uint32_t add_bezier(ppm_scene_t &scene, Params &p, Placed &placed) {
    if (p.has("filename") == p.has("patches"))
        p.fail(p.has("filename") ? "filename" : "patches", "a bezier shape needs either 'filename' or 'patches'");
    const std::string path = p.has("filename") ? filename(p) : "";
    const std::vector<double> points = p.has("patches") ? p.number_list("patches") : std::vector<double>();
    if (points.size() % 48 != 0)
        p.fail("patches",
               "must hold 48 numbers per patch (16 control points), not " + std::to_string(points.size()) + " numbers");
    const std::vector<double> rects = p.has("uv_rects") ? p.number_list("uv_rects") : std::vector<double>();
    p.finish();
    uint32_t geom = 0;
    if (!path.empty())
        check(ppm_scene_load_bpt(&scene, path.c_str(), &geom));
    else
        check(ppm_scene_add_bezier_patches(&scene, points.data(), points.size() / 48, &geom));
    if (!rects.empty()) {
        // Known once the patches are: a mismatch leaves the geometry in the scene (ppm.h).
        std::size_t patch_count = 0;
        check(ppm_scene_get_primitive_count(&scene, geom, &patch_count));
        if (rects.size() != 4 * patch_count)
            p.fail("uv_rects", "must hold one [u0, v0, u1, v1] per patch (" + std::to_string(patch_count) + "), not " +
                                   std::to_string(rects.size()) + " numbers");
        check(ppm_scene_set_patch_uv_rects(&scene, geom, rects.data()));
    }
    placed.transform_geometry = true;
    return geom;
}

struct ShapeType {
    const char *name;
    uint32_t (*add)(ppm_scene_t &, Params &, Placed &);
    bool flips; // takes flip_normals
};

const ShapeType kShapeTypes[] = {
    {"sphere", add_sphere, false},
    {"rectangle", add_rectangle, true},
    {"quad", add_quad, true},
    {"disk", add_disk, true},
    {"cylinder", add_cylinder, true},
    {"cube", add_cube, true},
    {"obj", add_obj, true},
    {"ply", add_ply, true},
    {"serialized", add_serialized, true},
    {"bezier", add_bezier, false},
};

} // namespace

namespace ppm::api {

std::vector<const char *> shape_type_names() { return type_names(kShapeTypes); }

} // namespace ppm::api

extern "C" ppm_status ppm_scene_add_shape(ppm_scene scene, const char *type, const ppm_param *params,
                                          size_t param_count, uint32_t *out_geom_id) {
    return ppm::api::scene_call(scene, [&](ppm_scene_t &s) {
        const ShapeType &t = ppm::api::find_type(kShapeTypes, "shape", type);
        Params p(std::string(t.name) + " shape", params, param_count);
        const bool has_material = p.has("bsdf");
        const uint32_t material = has_material ? p.material("bsdf") : 0;
        if (has_material) s.shading.material(material); // it must exist (throws naming the id)
        const bool flip = t.flips && p.boolean("flip_normals", false);
        const Affine to_world = p.transform("to_world", {});
        Placed placed; // every parameter is read and checked (Params::finish) before the geometry is added
        placed.geom = t.add(s, p, placed);
        if (placed.transform_geometry && !ppm::is_identity(to_world)) {
            const std::array<double, 16> matrix = ppm::matrix16(to_world);
            if (ppm_scene_set_geometry_transform(&s, placed.geom, matrix.data()) != PPM_OK)
                p.fail("to_world", "cannot place the shape: " + ppm::api::last_error());
        }
        if (flip != placed.mirrored_normal) check(ppm_scene_set_geometry_flip_normals(&s, placed.geom, 1));
        if (has_material) check(ppm_scene_set_geometry_material(&s, placed.geom, material));
        ppm::api::write_id(out_geom_id, placed.geom);
    });
}
