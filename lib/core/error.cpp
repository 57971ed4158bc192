#include "core/error.h"

#include <cstdio>
#include <cstdlib>

namespace ppm {

std::string format_number(double value) {
    char text[32];
    for (int digits = 15; digits <= 17; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, value);
        if (std::strtod(text, nullptr) == value || !(value == value)) break;
    }
    return text;
}

} // namespace ppm
