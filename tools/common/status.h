// SPDX-License-Identifier: Apache-2.0
// The tools' one check of a libppm status: a failed call throws ApiError, whose message is
// what the tool was doing followed by libppm's message for the call. The message is read at
// once, since the next libppm call on the thread replaces it. Each tool's main() reports any
// std::exception as "TOOL: message" with exit status 2 (kExitRuntime in command_line.h).
#pragma once

#include <ppm/ppm.h>

#include <stdexcept>
#include <string>

namespace ppm_tools {

// A failed libppm call; the tools' own runtime errors are plain std::runtime_error.
struct ApiError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// How a tool's messages read: "what: libppm's message" (ppm-render, ppm-merge), or with the
// status named, "what: parse error: libppm's message" (ppm-tess, ppm-bench).
enum class StatusName { omitted, included };

// check(status, what) throws ApiError when `status` is not PPM_OK; `what` (may be empty) says
// what was being done.
struct StatusCheck {
    StatusName name;

    void operator()(ppm_status status, const std::string &what = {}) const {
        if (status == PPM_OK) return;
        std::string message = what.empty() ? std::string() : what + ": ";
        if (name == StatusName::included) message += std::string(ppm_status_string(status)) + ": ";
        throw ApiError(message + ppm_last_error_message());
    }
};

inline constexpr StatusCheck check{StatusName::omitted};
inline constexpr StatusCheck check_with_status{StatusName::included};

} // namespace ppm_tools
