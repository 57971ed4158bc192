// SPDX-License-Identifier: Apache-2.0
// Turning ppm_status codes into Python exceptions.
//
// Every wrapper calls check() right after its C call, on the same thread, so that
// ppm_last_error_message() (per thread, valid until the next ppm_* call) is still the message
// of that call. The C++ exception carries the message to nanobind's exception translator,
// which raises the matching class of libppm._errors with the GIL held.
#pragma once

#include <ppm/ppm.h>

#include <nanobind/nanobind.h>

#include <stdexcept>
#include <string>

namespace ppm_py {

// A failed C call: its status and the library's message.
class StatusError : public std::runtime_error {
public:
    StatusError(ppm_status status, const std::string &message) : std::runtime_error(message), status_(status) {}
    ppm_status status() const { return status_; }

private:
    ppm_status status_;
};

// A method called on a handle after close().
class ClosedError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws StatusError for anything but PPM_OK.
inline void check(ppm_status status) {
    if (status == PPM_OK) return;
    std::string message = ppm_last_error_message();
    if (message.empty()) message = ppm_status_string(status);
    throw StatusError(status, message);
}

// Registers the translator; libppm._errors must be importable (libppm/__init__.py imports it first).
void register_errors(nanobind::module_ &m);

} // namespace ppm_py
