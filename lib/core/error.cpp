#include "core/error.h"

#include <cstdio>

namespace ppm {

std::string out_of_memory_message(const std::string &what, std::uint64_t bytes) {
    char size[32];
    std::snprintf(size, sizeof size, "%.1f GiB", static_cast<double>(bytes) / (1024.0 * 1024.0 * 1024.0));
    return "out of memory for " + what + ": " + std::to_string(bytes) + " bytes (" + size + ")";
}

std::string format_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

} // namespace ppm
