#include "objects.h"

#include <nanobind/stl/string.h>

namespace nb = nanobind;

namespace ppm_py {

void bind_context(nb::module_ &m) {
    nb::class_<Context> cls(m, "Context");
    cls.def("__init__", [](Context *self) {
        ppm_context context = nullptr;
        check(ppm_context_create(&context));
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
