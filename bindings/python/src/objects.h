// SPDX-License-Identifier: Apache-2.0
// The handle classes of the extension module libppm._core, shared by the bind_*.cpp files.
// They mirror ppm.h one to one; argument checking with readable messages, numpy shapes and
// documentation live in the Python package (libppm/*.py), which is the public API.
#pragma once

#include "handle.h"

#include <nanobind/nanobind.h>

namespace ppm_py {

struct Context : Handle<ppm_context, ppm_context_retain, ppm_context_release> {
    using Handle::Handle;
};

struct Scene : Handle<ppm_scene, ppm_scene_retain, ppm_scene_release> {
    using Handle::Handle;
};

struct Mesh : Handle<ppm_mesh, ppm_mesh_retain, ppm_mesh_release> {
    using Handle::Handle;
};

struct Renderer : Handle<ppm_renderer, ppm_renderer_retain, ppm_renderer_release> {
    using Handle::Handle;
};

struct Partial : Handle<ppm_partial, ppm_partial_retain, ppm_partial_release> {
    using Handle::Handle;
};

// Adds close() and the read-only property `closed` to a bound handle class.
template <typename T> void def_close(nanobind::class_<T> &cls) {
    cls.def("close", [](T &self) { self.close(); }).def_prop_ro("closed", [](const T &self) { return self.closed(); });
}

void bind_context(nanobind::module_ &m);
void bind_scene(nanobind::module_ &m);
void bind_queries(nanobind::module_ &m, nanobind::class_<Scene> &cls);
void bind_mesh(nanobind::module_ &m);
void bind_renderer(nanobind::module_ &m);
void bind_scene_file(nanobind::module_ &m);
void bind_partial(nanobind::module_ &m);

} // namespace ppm_py
