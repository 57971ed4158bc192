// SPDX-License-Identifier: Apache-2.0
// Array arguments as the C API reads them: C-contiguous, on the CPU. The Python layer has
// already converted and shape-checked them; require_size() guards the pointer arithmetic
// for callers of libppm._core itself.
#pragma once

#include "status.h"

#include <nanobind/ndarray.h>

#include <cstdint>
#include <string>

namespace ppm_py {

using Doubles = nanobind::ndarray<const double, nanobind::c_contig, nanobind::device::cpu>;
using Indices = nanobind::ndarray<const uint32_t, nanobind::c_contig, nanobind::device::cpu>;
using Bytes = nanobind::ndarray<const uint8_t, nanobind::c_contig, nanobind::device::cpu>;
using OutBytes = nanobind::ndarray<uint8_t, nanobind::c_contig, nanobind::device::cpu>;
using OutFloats = nanobind::ndarray<float, nanobind::c_contig, nanobind::device::cpu>;
using OutDoubles = nanobind::ndarray<double, nanobind::c_contig, nanobind::device::cpu>;

// Number of groups of `group` elements in `a`; ValueError unless `a` holds a whole number.
template <typename Array> size_t groups_of(const Array &a, size_t group, const char *name) {
    if (a.size() % group != 0)
        throw nanobind::value_error(
            (std::string(name) + ": element count is not a multiple of " + std::to_string(group)).c_str());
    return a.size() / group;
}

} // namespace ppm_py
