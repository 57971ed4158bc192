// Internal error reporting: code below the C ABI throws ppm::Error; lib/api turns it into a
// ppm_status and the per-thread message. Nothing else crosses the boundary.
#pragma once

#include <ppm/ppm.h>

#include <stdexcept>
#include <string>

namespace ppm {

class Error : public std::runtime_error {
public:
    Error(ppm_status status, const std::string &message)
        : std::runtime_error(message), status_(status) {}
    ppm_status status() const { return status_; }

private:
    ppm_status status_;
};

[[noreturn]] inline void fail(ppm_status status, const std::string &message) {
    throw Error(status, message);
}
[[noreturn]] inline void invalid_argument(const std::string &message) {
    throw Error(PPM_ERROR_INVALID_ARGUMENT, message);
}

// Shortest round-trip text of a double, for messages.
std::string format_number(double value);

} // namespace ppm
