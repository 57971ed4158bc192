// SPDX-License-Identifier: Apache-2.0
// Internal error reporting: code below the C ABI throws ppm::Error; lib/api turns it into a
// ppm_status and the per-thread message. Nothing else crosses the boundary.
#pragma once

#include <ppm/ppm.h>

#include <cstdint>
#include <new>
#include <stdexcept>
#include <string>

namespace ppm {

class Error : public std::runtime_error {
public:
    Error(ppm_status status, const std::string &message) : std::runtime_error(message), status_(status) {}
    ppm_status status() const { return status_; }

private:
    ppm_status status_;
};

[[noreturn]] inline void fail(ppm_status status, const std::string &message) { throw Error(status, message); }
[[noreturn]] inline void invalid_argument(const std::string &message) {
    throw Error(PPM_ERROR_INVALID_ARGUMENT, message);
}

// "out of memory for WHAT: N bytes (X GiB)".
std::string out_of_memory_message(const std::string &what, std::uint64_t bytes);

// Runs `allocate`, whose allocations are sized by input (a film, a file's arrays), and turns
// their failure (std::bad_alloc, or the std::length_error of a size no container can hold)
// into OUT_OF_MEMORY naming the object and its size, which a bare "out of memory" from the API
// boundary cannot.
template <class Allocate> void allocate_or_fail(const std::string &what, std::uint64_t bytes, Allocate &&allocate) {
    try {
        allocate();
    } catch (const std::bad_alloc &) {
        fail(PPM_ERROR_OUT_OF_MEMORY, out_of_memory_message(what, bytes));
    } catch (const std::length_error &) {
        fail(PPM_ERROR_OUT_OF_MEMORY, out_of_memory_message(what, bytes));
    }
}

// Shortest round-trip text of a double, for messages.
std::string format_number(double value);

} // namespace ppm
