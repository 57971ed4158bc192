// SPDX-License-Identifier: Apache-2.0
// Scene files (docs/scene-format.md: JSON or Mitsuba 3 XML).
#include "camera.h"
#include "objects.h"

#include <nanobind/stl/map.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace nb = nanobind;

namespace ppm_py {

namespace {

struct SceneFile : Handle<ppm_scene_file, ppm_scene_file_retain, ppm_scene_file_release> {
    using Handle::Handle;
};

} // namespace

void bind_scene_file(nb::module_ &m) {
    nb::class_<SceneFile> cls(m, "SceneFile");
    // Loading builds and commits the scene and reads textures: no GIL. With `text`, the
    // scene is that text, named `path` in messages, its file names relative to `folder`.
    cls.def("__init__", [](SceneFile *self, Context &context, const std::string &path, std::optional<std::string> text,
                           std::optional<std::string> folder, std::optional<std::string> format,
                           const std::map<std::string, std::string> &defines, bool lenient) {
        std::vector<const char *> names, values;
        for (const auto &define : defines) {
            names.push_back(define.first.c_str());
            values.push_back(define.second.c_str());
        }
        ppm_scene_file_options options;
        ppm_scene_file_options_init(&options);
        options.format = format ? format->c_str() : nullptr;
        options.define_names = names.data();
        options.define_values = values.data();
        options.define_count = names.size();
        options.lenient = lenient ? 1 : 0;
        ppm_scene_file file = nullptr;
        {
            auto c = context.borrow();
            nb::gil_scoped_release unlocked;
            if (text)
                check(ppm_scene_file_load_memory(c.get(), text->data(), text->size(), path.c_str(),
                                                 folder ? folder->c_str() : nullptr, &options, &file));
            else
                check(ppm_scene_file_load_v2(c.get(), path.c_str(), &options, &file));
        }
        new (self) SceneFile(file, "SceneFile");
    });
    def_close(cls);
    cls.def("get_scene", [](SceneFile &f) {
        ppm_scene scene = nullptr;
        check(ppm_scene_file_get_scene(f.get(), &scene));
        return new Scene(scene, "Scene");
    });
    cls.def("get_camera", [](SceneFile &f) {
        ppm_camera_v2 camera;
        ppm_camera_v2_init(&camera);
        check(ppm_scene_file_get_camera_v2(f.get(), &camera));
        return from_camera(camera);
    });
    // With a camera: the file's settings seen through it (another size, a crop window).
    cls.def(
        "create_renderer",
        [](SceneFile &f, std::optional<CameraTuple> camera) {
            ppm_renderer renderer = nullptr;
            if (camera) {
                const ppm_camera_v2 c = to_camera(*camera);
                check(ppm_scene_file_create_renderer_v2(f.get(), &c, &renderer));
            } else {
                check(ppm_scene_file_create_renderer(f.get(), &renderer));
            }
            return new Renderer(renderer, "Renderer");
        },
        nb::arg("camera") = nb::none());
    cls.def("get_int", [](SceneFile &f, const std::string &key) {
        int64_t value = 0;
        check(ppm_scene_file_get_int(f.get(), key.c_str(), &value));
        return value;
    });
    cls.def("get_double", [](SceneFile &f, const std::string &key) {
        double value = 0;
        check(ppm_scene_file_get_double(f.get(), key.c_str(), &value));
        return value;
    });
}

} // namespace ppm_py
