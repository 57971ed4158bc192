// SPDX-License-Identifier: Apache-2.0
// Scene building: geometry, transforms, materials, textures, lights, commit, bounds.
#include "arrays.h"
#include "objects.h"

#include <nanobind/stl/array.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <array>
#include <optional>
#include <tuple>
#include <vector>

namespace nb = nanobind;

namespace ppm_py {

namespace {

using Vec2 = std::array<double, 2>;
using Vec3 = std::array<double, 3>;

// Runs an add call that reports a new id through its last argument.
template <typename F> uint32_t new_id(F &&call) {
    uint32_t id = PPM_INVALID_ID;
    check(call(&id));
    return id;
}

// One named parameter of ppm_scene_add_material / _texture / _light, as the Python layer
// passes it: (name, kind, numbers, string, id) with kind a ppm_param_type value.
using Param = std::tuple<std::string, int, std::vector<double>, std::string, uint32_t>;

using AddWithParams = ppm_status (*)(ppm_scene, const char *, const ppm_param *, size_t, uint32_t *);

uint32_t add_with_params(Scene &s, AddWithParams add, const std::string &type, const std::vector<Param> &given) {
    std::vector<ppm_param> params;
    params.reserve(given.size());
    for (const Param &p : given) {
        ppm_param c{};
        c.name = std::get<0>(p).c_str();
        c.type = static_cast<ppm_param_type>(std::get<1>(p));
        c.numbers = std::get<2>(p).data();
        c.count = std::get<2>(p).size();
        c.string = std::get<3>(p).c_str();
        c.id = std::get<4>(p);
        params.push_back(c);
    }
    return new_id([&](uint32_t *id) { return add(s.get(), type.c_str(), params.data(), params.size(), id); });
}

} // namespace

void bind_scene(nb::module_ &m) {
    nb::class_<Scene> cls(m, "Scene");
    cls.def("__init__", [](Scene *self, Context &context) {
        ppm_scene scene = nullptr;
        check(ppm_scene_create(context.get(), &scene));
        new (self) Scene(scene, "Scene");
    });
    def_close(cls);

    cls.def("set_int", [](Scene &s, const std::string &key, int64_t value) {
        check(ppm_scene_set_int(s.get(), key.c_str(), value));
    });
    cls.def("get_int", [](Scene &s, const std::string &key) {
        int64_t value = 0;
        check(ppm_scene_get_int(s.get(), key.c_str(), &value));
        return value;
    });
    cls.def("set_double", [](Scene &s, const std::string &key, double value) {
        check(ppm_scene_set_double(s.get(), key.c_str(), value));
    });
    cls.def("get_double", [](Scene &s, const std::string &key) {
        double value = 0;
        check(ppm_scene_get_double(s.get(), key.c_str(), &value));
        return value;
    });

    // Geometry.
    cls.def("add_bezier_patches", [](Scene &s, const Doubles &points) {
        const size_t count = groups_of(points, 48, "control_points");
        return new_id([&](uint32_t *id) { return ppm_scene_add_bezier_patches(s.get(), points.data(), count, id); });
    });
    cls.def("load_bpt", [](Scene &s, const std::string &path) {
        return new_id([&](uint32_t *id) { return ppm_scene_load_bpt(s.get(), path.c_str(), id); });
    });
    cls.def("add_sphere", [](Scene &s, const Vec3 &center, double radius) {
        return new_id([&](uint32_t *id) { return ppm_scene_add_sphere(s.get(), center.data(), radius, id); });
    });
    cls.def("add_quad", [](Scene &s, const Vec3 &origin, const Vec3 &edge_u, const Vec3 &edge_v) {
        return new_id(
            [&](uint32_t *id) { return ppm_scene_add_quad(s.get(), origin.data(), edge_u.data(), edge_v.data(), id); });
    });
    cls.def("add_disk", [](Scene &s, const Vec3 &center, const Vec3 &axis_u, const Vec3 &axis_v) {
        return new_id(
            [&](uint32_t *id) { return ppm_scene_add_disk(s.get(), center.data(), axis_u.data(), axis_v.data(), id); });
    });
    cls.def("add_cylinder", [](Scene &s, const Vec3 &p0, const Vec3 &p1, double radius) {
        return new_id([&](uint32_t *id) { return ppm_scene_add_cylinder(s.get(), p0.data(), p1.data(), radius, id); });
    });
    cls.def("set_geometry_flip_normals", [](Scene &s, uint32_t geom_id, bool flip) {
        check(ppm_scene_set_geometry_flip_normals(s.get(), geom_id, flip ? 1 : 0));
    });
    cls.def("set_mesh_face_normals", [](Scene &s, uint32_t geom_id, bool face_normals) {
        check(ppm_scene_set_mesh_face_normals(s.get(), geom_id, face_normals ? 1 : 0));
    });
    cls.def(
        "add_triangle_mesh",
        [](Scene &s, const Doubles &positions, const Indices &indices, std::optional<Doubles> normals,
           std::optional<Doubles> uvs) {
            const size_t vertices = groups_of(positions, 3, "positions");
            const size_t triangles = groups_of(indices, 3, "indices");
            if (normals && normals->size() != 3 * vertices) throw nb::value_error("normals: need 3 numbers per vertex");
            if (uvs && uvs->size() != 2 * vertices) throw nb::value_error("uvs: need 2 numbers per vertex");
            return new_id([&](uint32_t *id) {
                return ppm_scene_add_triangle_mesh(s.get(), positions.data(), vertices, indices.data(), triangles,
                                                   normals ? normals->data() : nullptr, uvs ? uvs->data() : nullptr,
                                                   id);
            });
        },
        nb::arg("positions"), nb::arg("indices"), nb::arg("normals").none(), nb::arg("uvs").none());
    cls.def("load_obj", [](Scene &s, const std::string &path) {
        return new_id([&](uint32_t *id) { return ppm_scene_load_obj(s.get(), path.c_str(), id); });
    });
    cls.def("set_geometry_transform", [](Scene &s, uint32_t geom_id, const Doubles &matrix) {
        if (matrix.size() != 16) throw nb::value_error("matrix: need 16 numbers");
        check(ppm_scene_set_geometry_transform(s.get(), geom_id, matrix.data()));
    });
    cls.def("set_geometry_material", [](Scene &s, uint32_t geom_id, uint32_t material) {
        check(ppm_scene_set_geometry_material(s.get(), geom_id, material));
    });
    cls.def("get_primitive_count", [](Scene &s, uint32_t geom_id) {
        size_t count = 0;
        check(ppm_scene_get_primitive_count(s.get(), geom_id, &count));
        return count;
    });
    cls.def("get_geometry_count", [](Scene &s) {
        size_t count = 0;
        check(ppm_scene_get_geometry_count(s.get(), &count));
        return count;
    });
    cls.def("get_bezier_patches", [](Scene &s, uint32_t geom_id, OutDoubles out) {
        check(ppm_scene_get_bezier_patches(s.get(), geom_id, out.data(), out.size()));
    });
    // Building the acceleration structure of a large scene takes a while: no GIL.
    cls.def("commit", [](Scene &s) {
        auto scene = s.borrow();
        nb::gil_scoped_release unlocked;
        check(ppm_scene_commit(scene.get()));
    });
    cls.def("get_bounds", [](Scene &s) {
        Vec3 lower{}, upper{};
        check(ppm_scene_get_bounds(s.get(), lower.data(), upper.data()));
        return std::make_pair(lower, upper);
    });

    // Materials, textures, lights.
    cls.def("add_diffuse_material", [](Scene &s, const Vec3 &reflectance) {
        return new_id([&](uint32_t *id) { return ppm_scene_add_diffuse_material(s.get(), reflectance.data(), id); });
    });
    cls.def("add_mirror_material", [](Scene &s, const Vec3 &reflectance) {
        return new_id([&](uint32_t *id) { return ppm_scene_add_mirror_material(s.get(), reflectance.data(), id); });
    });
    cls.def("add_dielectric_material", [](Scene &s, double int_ior, double ext_ior) {
        return new_id([&](uint32_t *id) { return ppm_scene_add_dielectric_material(s.get(), int_ior, ext_ior, id); });
    });
    cls.def("add_coated_material", [](Scene &s, const Vec3 &reflectance, double int_ior, double ext_ior) {
        return new_id([&](uint32_t *id) {
            return ppm_scene_add_coated_material(s.get(), reflectance.data(), int_ior, ext_ior, id);
        });
    });
    cls.def(
        "set_material_texture",
        [](Scene &s, uint32_t material, const std::string &path, std::optional<Vec2> scale,
           std::optional<Vec2> offset) {
            check(ppm_scene_set_material_texture(s.get(), material, path.c_str(), scale ? scale->data() : nullptr,
                                                 offset ? offset->data() : nullptr));
        },
        nb::arg("material"), nb::arg("path"), nb::arg("scale").none(), nb::arg("offset").none());
    cls.def("set_patch_uv_rects", [](Scene &s, uint32_t geom_id, const Doubles &rects) {
        size_t patches = 0;
        check(ppm_scene_get_primitive_count(s.get(), geom_id, &patches));
        // The C call reads 4 numbers per patch of the geometry: never let it read past `rects`.
        if (rects.size() != 4 * patches)
            throw nb::value_error(("rects: geometry " + std::to_string(geom_id) + " has " + std::to_string(patches) +
                                   " primitives, need 4 numbers for each")
                                      .c_str());
        check(ppm_scene_set_patch_uv_rects(s.get(), geom_id, rects.data()));
    });
    cls.def("add_material", [](Scene &s, const std::string &type, const std::vector<Param> &params) {
        return add_with_params(s, ppm_scene_add_material, type, params);
    });
    cls.def("add_texture", [](Scene &s, const std::string &type, const std::vector<Param> &params) {
        return add_with_params(s, ppm_scene_add_texture, type, params);
    });
    cls.def("add_light", [](Scene &s, const std::string &type, const std::vector<Param> &params) {
        return add_with_params(s, ppm_scene_add_light, type, params);
    });
    cls.def("add_shape", [](Scene &s, const std::string &type, const std::vector<Param> &params) {
        return add_with_params(s, ppm_scene_add_shape, type, params);
    });
    cls.def("add_point_light", [](Scene &s, const Vec3 &position, const Vec3 &intensity) {
        return new_id(
            [&](uint32_t *id) { return ppm_scene_add_point_light(s.get(), position.data(), intensity.data(), id); });
    });
    cls.def("add_spot_light", [](Scene &s, const Vec3 &position, const Vec3 &target, const Vec3 &intensity,
                                 double cutoff_angle, double beam_width) {
        return new_id([&](uint32_t *id) {
            return ppm_scene_add_spot_light(s.get(), position.data(), target.data(), intensity.data(), cutoff_angle,
                                            beam_width, id);
        });
    });
    cls.def("set_geometry_emission", [](Scene &s, uint32_t geom_id, const Vec3 &radiance) {
        check(ppm_scene_set_geometry_emission(s.get(), geom_id, radiance.data()));
    });

    bind_queries(m, cls);
}

} // namespace ppm_py
