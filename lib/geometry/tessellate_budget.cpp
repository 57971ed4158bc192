// SPDX-License-Identifier: Apache-2.0
#include "geometry/tessellate_budget.h"

#include "core/error.h"
#include "geometry/tessellate.h"

#include <cmath>

namespace ppm {
namespace tess {

[[noreturn]] void over_budget(double triangles) {
    invalid_argument("the tessellation would need about " + format_number(std::round(triangles)) +
                     " triangles, more than the limit of " + format_number(max_tessellation_triangles) +
                     ": use a larger tolerance or grid");
}

} // namespace tess
} // namespace ppm
