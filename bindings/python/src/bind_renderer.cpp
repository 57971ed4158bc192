// SPDX-License-Identifier: Apache-2.0
// The progressive photon-mapping renderer.
#include "arrays.h"
#include "camera.h"
#include "objects.h"

#include <nanobind/stl/string.h>

#include <string>

namespace nb = nanobind;

namespace ppm_py {

void bind_renderer(nb::module_ &m) {
    nb::class_<Renderer> cls(m, "Renderer");
    cls.def("__init__", [](Renderer *self, Scene &scene, const CameraTuple &camera) {
        const ppm_camera_v2 c = to_camera(camera);
        ppm_renderer renderer = nullptr;
        check(ppm_renderer_create_v2(scene.get(), &c, &renderer));
        new (self) Renderer(renderer, "Renderer");
    });
    def_close(cls);

    cls.def("set_int", [](Renderer &r, const std::string &key, int64_t value) {
        check(ppm_renderer_set_int(r.get(), key.c_str(), value));
    });
    cls.def("set_double", [](Renderer &r, const std::string &key, double value) {
        check(ppm_renderer_set_double(r.get(), key.c_str(), value));
    });
    cls.def("set_string", [](Renderer &r, const std::string &key, const std::string &value) {
        check(ppm_renderer_set_string(r.get(), key.c_str(), value.c_str()));
    });
    cls.def("get_int", [](Renderer &r, const std::string &key) {
        int64_t value = 0;
        check(ppm_renderer_get_int(r.get(), key.c_str(), &value));
        return value;
    });
    cls.def("get_double", [](Renderer &r, const std::string &key) {
        double value = 0;
        check(ppm_renderer_get_double(r.get(), key.c_str(), &value));
        return value;
    });
    cls.def("get_string", [](Renderer &r, const std::string &key) {
        size_t length = 0;
        check(ppm_renderer_get_string(r.get(), key.c_str(), nullptr, 0, &length));
        std::string value(length + 1, '\0');
        check(ppm_renderer_get_string(r.get(), key.c_str(), value.data(), value.size(), nullptr));
        value.resize(length);
        return value;
    });

    // Without the GIL, so that another Python thread can cancel() or read the image meanwhile.
    cls.def("render_pass", [](Renderer &r) {
        auto renderer = r.borrow();
        nb::gil_scoped_release unlocked;
        check(ppm_renderer_render_pass(renderer.get()));
    });
    cls.def("cancel", [](Renderer &r) { check(ppm_renderer_cancel(r.get())); });
    cls.def("get_layer", [](Renderer &r, const std::string &layer, OutFloats out) {
        auto renderer = r.borrow();
        nb::gil_scoped_release unlocked;
        check(ppm_renderer_get_layer(renderer.get(), layer.c_str(), out.data(), out.size()));
    });

    cls.def("save_checkpoint", [](Renderer &r, const std::string &path) {
        auto renderer = r.borrow();
        nb::gil_scoped_release unlocked;
        check(ppm_renderer_save_checkpoint(renderer.get(), path.c_str()));
    });
    cls.def("load_checkpoint", [](Renderer &r, const std::string &path) {
        auto renderer = r.borrow();
        nb::gil_scoped_release unlocked;
        check(ppm_renderer_load_checkpoint(renderer.get(), path.c_str()));
    });
}

} // namespace ppm_py
