// SPDX-License-Identifier: Apache-2.0
// Partial renders of the pass-independent mode, the renderer calls that make and take them,
// and the image writer.
#include "arrays.h"
#include "objects.h"

#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <string>
#include <utility>
#include <vector>

namespace nb = nanobind;

namespace ppm_py {

using InFloats = nb::ndarray<const float, nb::c_contig, nb::device::cpu>;

void bind_partial(nb::module_ &m) {
    nb::class_<Partial> cls(m, "Partial");
    def_close(cls);
    cls.def_static("load", [](const std::string &path) {
        ppm_partial p = nullptr;
        {
            nb::gil_scoped_release unlocked;
            check(ppm_partial_load(path.c_str(), &p));
        }
        return new Partial(p, "Partial");
    });
    cls.def_static("from_bytes", [](nb::bytes data) {
        ppm_partial p = nullptr;
        check(ppm_partial_load_memory(data.c_str(), data.size(), &p));
        return new Partial(p, "Partial");
    });
    cls.def("to_bytes", [](Partial &p) {
        const void *data = nullptr;
        size_t size = 0;
        check(ppm_partial_serialize(p.get(), &data, &size));
        return nb::bytes(static_cast<const char *>(data), size);
    });
    cls.def("save", [](Partial &p, const std::string &path) {
        auto partial = p.borrow();
        nb::gil_scoped_release unlocked;
        check(ppm_partial_save(partial.get(), path.c_str()));
    });
    cls.def("merge", [](Partial &p, Partial &other) { check(ppm_partial_merge(p.get(), other.get())); });
    cls.def("get_int", [](Partial &p, const std::string &key) {
        int64_t value = 0;
        check(ppm_partial_get_int(p.get(), key.c_str(), &value));
        return value;
    });
    cls.def("set_int", [](Partial &p, const std::string &key, int64_t value) {
        check(ppm_partial_set_int(p.get(), key.c_str(), value));
    });
    cls.def("passes", [](Partial &p) {
        size_t count = 0;
        check(ppm_partial_get_passes(p.get(), nullptr, 0, &count));
        std::vector<uint64_t> flat(2 * count);
        check(ppm_partial_get_passes(p.get(), flat.data(), flat.size(), &count));
        std::vector<std::pair<uint64_t, uint64_t>> ranges;
        for (size_t k = 0; k < count; ++k) ranges.emplace_back(flat[2 * k], flat[2 * k + 1]);
        return ranges;
    });
    cls.def("get_layer", [](Partial &p, const std::string &layer, OutFloats out) {
        check(ppm_partial_get_layer(p.get(), layer.c_str(), out.data(), out.size()));
    });

    m.def("render_pass_index", [](Renderer &r, uint64_t index) {
        auto renderer = r.borrow();
        nb::gil_scoped_release unlocked;
        check(ppm_renderer_render_pass_index(renderer.get(), index));
    });
    m.def("renderer_partial", [](Renderer &r) {
        ppm_partial p = nullptr;
        check(ppm_renderer_get_partial(r.get(), &p));
        return new Partial(p, "Partial");
    });
    m.def("renderer_merge_partial",
          [](Renderer &r, Partial &p) { check(ppm_renderer_merge_partial(r.get(), p.get())); });

    m.def("image_check_path", [](const std::string &path) { check(ppm_image_check_path(path.c_str())); });
    m.def("image_write",
          [](const std::string &path, InFloats radiance, uint32_t width, uint32_t height,
             const std::vector<std::string> &names, const std::vector<InFloats> &layers, double exposure) {
              if (radiance.size() != size_t(width) * height * 3)
                  throw nb::value_error("radiance: size is not width x height x 3");
              if (names.size() != layers.size()) throw nb::value_error("one name per layer");
              std::vector<ppm_image_layer> list;
              for (size_t i = 0; i < layers.size(); ++i) {
                  if (layers[i].size() != size_t(width) * height)
                      throw nb::value_error("a layer's size is not width x height");
                  list.push_back(ppm_image_layer{names[i].c_str(), layers[i].data()});
              }
              nb::gil_scoped_release unlocked;
              check(ppm_image_write(path.c_str(), radiance.data(), width, height, list.data(), list.size(), exposure));
          });
}

} // namespace ppm_py
