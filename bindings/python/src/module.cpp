// SPDX-License-Identifier: Apache-2.0
// libppm._core: a thin typed mirror of <ppm/ppm.h>. See objects.h.
#include "objects.h"
#include "status.h"

#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <string>
#include <vector>

namespace nb = nanobind;

NB_MODULE(_core, m) {
    m.doc() = "Low-level bindings of the libppm C API; use the libppm package instead.";
    ppm_py::register_errors(m);
    m.def("version", [] { return ppm_version(); });
    m.def("version_string", [] { return ppm_version_string(); });
    m.def("status_string", [](int status) { return ppm_status_string(static_cast<ppm_status>(status)); });
    m.attr("INVALID_ID") = PPM_INVALID_ID;
    m.def("type_names", [](const std::string &kind) {
        std::size_t count = 0;
        ppm_py::check(ppm_type_count(kind.c_str(), &count));
        std::vector<std::string> names;
        for (std::size_t i = 0; i < count; ++i) {
            const char *name = nullptr;
            ppm_py::check(ppm_type_name(kind.c_str(), i, &name));
            names.emplace_back(name);
        }
        return names;
    });
    ppm_py::bind_context(m);
    ppm_py::bind_scene(m);
    ppm_py::bind_mesh(m);
    ppm_py::bind_renderer(m);
    ppm_py::bind_scene_file(m);
    ppm_py::bind_partial(m);
}
