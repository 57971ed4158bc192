// SPDX-License-Identifier: Apache-2.0
#include "objects.h"

#include <nanobind/stl/string.h>

namespace nb = nanobind;

#include <cstdio>

namespace ppm_py {

namespace {

// libppm's warnings (what an input holds that it skips or substitutes) as Python warnings
// (libppm.Warning), so that the warnings module filters, records or raises them. Called
// from any thread, also while the GIL is released around a load.
void warn_in_python(void *, const char *message) {
    if (!Py_IsInitialized()) {
        std::fprintf(stderr, "libppm: warning: %s\n", message);
        return;
    }
    nb::gil_scoped_acquire locked;
    try {
        nb::module_::import_("libppm._errors").attr("_warn")(nb::str(message));
    } catch (nb::python_error &e) {
        // A filter that turns warnings into errors: the load goes on, the error is reported.
        e.discard_as_unraisable("libppm warning");
    }
}

} // namespace

void bind_context(nb::module_ &m) {
    nb::class_<Context> cls(m, "Context");
    cls.def("__init__", [](Context *self) {
        ppm_context context = nullptr;
        check(ppm_context_create(&context));
        ppm_context_set_warning_callback(context, warn_in_python, nullptr);
        new (self) Context(context, "Context");
    });
    def_close(cls);
    cls.def("set_int", [](Context &c, const std::string &key, int64_t value) {
        check(ppm_context_set_int(c.get(), key.c_str(), value));
    });
    cls.def("get_int", [](Context &c, const std::string &key) {
        int64_t value = 0;
        check(ppm_context_get_int(c.get(), key.c_str(), &value));
        return value;
    });
    cls.def("set_double", [](Context &c, const std::string &key, double value) {
        check(ppm_context_set_double(c.get(), key.c_str(), value));
    });
    cls.def("get_double", [](Context &c, const std::string &key) {
        double value = 0;
        check(ppm_context_get_double(c.get(), key.c_str(), &value));
        return value;
    });
}

} // namespace ppm_py
