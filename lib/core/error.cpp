#include "core/error.h"

#include <cstdio>

namespace ppm {

std::string format_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

} // namespace ppm
