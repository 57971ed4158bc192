// SPDX-License-Identifier: Apache-2.0
// ppm_type_count and ppm_type_name: the rows of the type tables, and the render modes.
#include <ppm/ppm.h>

#include "api/api_support.h"
#include "api/api_type_tables.h"
#include "settings/render_modes.h"

#include <cstring>
#include <string>
#include <vector>

namespace {

std::vector<const char *> mode_names() {
    std::vector<const char *> names;
    for (const ppm::ModeTraits &m : ppm::render_modes()) names.push_back(m.name);
    return names;
}

// Each kind and where its names come from, in the order messages list them.
struct Kind {
    const char *name;
    std::vector<const char *> (*names)();
};
const Kind kKinds[] = {
    {"material", ppm::api::material_type_names},
    {"texture", ppm::api::texture_type_names},
    {"light", ppm::api::light_type_names},
    {"shape", ppm::api::shape_type_names},
    {"mode", mode_names},
};

std::vector<const char *> names_of(const char *kind) {
    if (!kind) ppm::invalid_argument("kind is NULL");
    std::string list;
    for (const Kind &k : kKinds) {
        if (std::strcmp(k.name, kind) == 0) return k.names();
        list += (list.empty() ? "" : ", ") + std::string(k.name);
    }
    ppm::invalid_argument("unknown kind '" + std::string(kind) + "' (kinds: " + list + ")");
}

} // namespace

extern "C" ppm_status ppm_type_count(const char *kind, size_t *out_count) {
    return ppm::api::guarded(nullptr, [&] {
        ppm::api::require(out_count, "out_count");
        *out_count = names_of(kind).size();
    });
}

extern "C" ppm_status ppm_type_name(const char *kind, size_t index, const char **out_name) {
    return ppm::api::guarded(nullptr, [&] {
        ppm::api::require(out_name, "out_name");
        const std::vector<const char *> names = names_of(kind);
        if (index >= names.size())
            ppm::invalid_argument("index " + std::to_string(index) + " is not below the " +
                                  std::to_string(names.size()) + " " + kind + " types");
        *out_name = names[index];
    });
}
