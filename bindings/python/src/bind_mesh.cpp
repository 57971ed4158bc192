// SPDX-License-Identifier: Apache-2.0
// Tessellation. The mesh's arrays go to numpy without a copy: each array is a read-only view
// of the mesh's own memory, and its owner capsule holds a reference to the mesh, so the
// arrays stay valid after close() (the C getters' pointers live as long as any reference).
#include "arrays.h"
#include "objects.h"

#include <nanobind/stl/string.h>

#include <initializer_list>

namespace nb = nanobind;

namespace ppm_py {

namespace {

nb::capsule mesh_reference(ppm_mesh mesh) {
    check(ppm_mesh_retain(mesh));
    return nb::capsule(mesh, [](void *p) noexcept { ppm_mesh_release(static_cast<ppm_mesh>(p)); });
}

template <typename T> nb::object view(ppm_mesh mesh, const T *data, std::initializer_list<size_t> shape) {
    return nb::cast(nb::ndarray<nb::numpy, const T>(data, shape, mesh_reference(mesh)));
}

} // namespace

void bind_mesh(nb::module_ &m) {
    nb::class_<Mesh> cls(m, "Mesh");
    def_close(cls);
    cls.def("arrays", [](Mesh &self) -> nb::typed<nb::dict, nb::str, nb::any> {
        ppm_mesh mesh = self.get();
        const double *positions = nullptr, *normals = nullptr, *uvs = nullptr;
        const uint32_t *indices = nullptr, *patches = nullptr, *welded = nullptr;
        size_t vertices = 0, triangles = 0, welded_count = 0;
        check(ppm_mesh_get_vertices(mesh, &positions, &normals, &uvs, &vertices));
        check(ppm_mesh_get_triangles(mesh, &indices, &triangles));
        check(ppm_mesh_get_triangle_patches(mesh, &patches));
        check(ppm_mesh_get_welded_vertices(mesh, &welded, &welded_count));
        nb::dict d;
        d["vertices"] = view(mesh, positions, {vertices, 3});
        d["normals"] = view(mesh, normals, {vertices, 3});
        d["uvs"] = view(mesh, uvs, {vertices, 2});
        d["triangles"] = view(mesh, indices, {triangles, 3});
        d["triangle_patches"] = view(mesh, patches, {triangles});
        d["welded_ids"] = view(mesh, welded, {vertices});
        d["welded_count"] = welded_count;
        return d;
    });
    cls.def("get_double", [](Mesh &self, const std::string &key) {
        double value = 0;
        check(ppm_mesh_get_double(self.get(), key.c_str(), &value));
        return value;
    });

    // Adaptive tessellation of many patches takes seconds: no GIL.
    m.def("tessellate", [](const Doubles &points, double tolerance, uint32_t grid) {
        const size_t count = groups_of(points, 48, "control_points");
        ppm_mesh mesh = nullptr;
        {
            nb::gil_scoped_release unlocked;
            check(ppm_tessellate_patches(points.data(), count, tolerance, grid, &mesh));
        }
        return new Mesh(mesh, "Mesh");
    });
}

} // namespace ppm_py
