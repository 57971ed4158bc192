// SPDX-License-Identifier: Apache-2.0
#include "api/api_keys.h"

#include "core/error.h"
#include "core/suggest.h"

#include <cmath>
#include <cstring>
#include <string>

namespace ppm::api {

namespace {

const char *type_name(KeyType type) { return type == KeyType::Int ? "an integer" : "a double"; }

} // namespace

KeyType KeyTable::find(const char *key) const {
    if (!key) invalid_argument("key is NULL");
    for (std::size_t i = 0; i < count; ++i)
        if (std::strcmp(keys[i].name, key) == 0) return keys[i].type;
    std::string known;
    std::vector<std::string> names;
    for (std::size_t i = 0; i < count; ++i) {
        known += std::string(i ? ", " : "") + keys[i].name + (keys[i].type == KeyType::Int ? " (int)" : " (double)");
        names.emplace_back(keys[i].name);
    }
    invalid_argument("unknown " + std::string(what) + " '" + key + "'" + did_you_mean(key, names) +
                     " (known: " + known + ")");
}

void KeyTable::require_int(const char *key) const {
    const KeyType type = find(key);
    if (type != KeyType::Int)
        invalid_argument(std::string(what) + " '" + key + "' is " + type_name(type) +
                         ", not an integer: read it as a double");
}

std::int64_t KeyTable::whole_number(const char *key, double value) const {
    // 2^63 is exact in double; every double below it in magnitude converts exactly.
    constexpr double limit = 9223372036854775808.0;
    if (!std::isfinite(value) || value != std::floor(value) || !(value >= -limit && value < limit))
        invalid_argument(std::string(what) + " '" + key + "' is an integer, and " + format_number(value) +
                         " is not a whole number in the range of int64_t");
    return static_cast<std::int64_t>(value);
}

} // namespace ppm::api
