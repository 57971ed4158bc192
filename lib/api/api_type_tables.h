// SPDX-License-Identifier: Apache-2.0
// The names of the rows of the API's type tables (api_*_types.cpp), in table order: what
// ppm_type_count / ppm_type_name report, and so what the scene file readers know.
#pragma once

#include <vector>

namespace ppm::api {

std::vector<const char *> material_type_names();
std::vector<const char *> texture_type_names();
std::vector<const char *> light_type_names();
std::vector<const char *> shape_type_names();

// The names of a table's rows (rows with a `name` member).
template <class Row, std::size_t N> std::vector<const char *> type_names(const Row (&rows)[N]) {
    std::vector<const char *> names;
    for (const Row &row : rows) names.push_back(row.name);
    return names;
}

} // namespace ppm::api
