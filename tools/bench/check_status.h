// SPDX-License-Identifier: Apache-2.0
// Turns a failed libppm call into an exception naming the call and libppm's message.
#pragma once

#include <ppm/ppm.h>

#include <stdexcept>
#include <string>

namespace bench {

inline void check(ppm_status status, const char *call) {
    if (status != PPM_OK)
        throw std::runtime_error(std::string(call) + ": " + ppm_status_string(status) + ": " +
                                 ppm_last_error_message());
}

} // namespace bench
