// SPDX-License-Identifier: Apache-2.0
#include "core/error.h"

#include <cstdio>
#include <cstdlib>

namespace ppm {

std::string out_of_memory_message(const std::string &what, std::uint64_t bytes) {
    char size[32];
    std::snprintf(size, sizeof size, "%.1f GiB", static_cast<double>(bytes) / (1024.0 * 1024.0 * 1024.0));
    return "out of memory for " + what + ": " + std::to_string(bytes) + " bytes (" + size + ")";
}

std::string format_number(double value) {
    char text[32];
    for (int digits = 15; digits <= 17; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, value);
        if (std::strtod(text, nullptr) == value || !(value == value)) break;
    }
    return text;
}

} // namespace ppm
