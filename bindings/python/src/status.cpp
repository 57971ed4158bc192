// SPDX-License-Identifier: Apache-2.0
#include "status.h"

namespace nb = nanobind;

namespace ppm_py {

namespace {

// Looked up on every error rather than cached: errors are rare and this way no Python object
// outlives the interpreter in a static.
void raise(const char *class_name, const char *message, int status) {
    nb::object errors = nb::module_::import_("libppm._errors");
    nb::object cls = status < 0 ? errors.attr(class_name) : errors.attr("_class_for_status")(status, nb::str(message));
    nb::object exc = cls(nb::str(message), status < 0 ? nb::none() : nb::cast(status));
    PyErr_SetObject(cls.ptr(), exc.ptr());
}

} // namespace

void register_errors(nb::module_ &) {
    nb::register_exception_translator([](const std::exception_ptr &p, void *) {
        try {
            std::rethrow_exception(p);
        } catch (const StatusError &e) {
            raise(nullptr, e.what(), static_cast<int>(e.status()));
        } catch (const ClosedError &e) {
            raise("ClosedError", e.what(), -1);
        }
    });
}

} // namespace ppm_py
