// SPDX-License-Identifier: Apache-2.0
// The typed settings of contexts, scenes and scene files (ppm.h, "Typed settings"): one table
// of keys and types per object, so that all of them answer an unknown key, a key of another
// type and a fractional value for an integer key alike.
#pragma once

#include <cstddef>
#include <cstdint>

namespace ppm::api {

enum class KeyType { Int, Double };

struct Key {
    const char *name;
    KeyType type;
};

// A table of keys; `what` names its entries in messages ("scene setting").
struct KeyTable {
    const char *what;
    const Key *keys;
    std::size_t count;

    template <std::size_t N> constexpr KeyTable(const char *what_, const Key (&keys_)[N])
        : what(what_), keys(keys_), count(N) {}

    // The type of `key`. Throws INVALID_ARGUMENT naming the key and listing the table when the
    // key is NULL or unknown.
    KeyType find(const char *key) const;

    // For get_int: throws INVALID_ARGUMENT unless `key` is an integer key, since a double
    // returned as an integer would be silently rounded.
    void require_int(const char *key) const;

    // For set_double on an integer key: `value` as an integer. Throws INVALID_ARGUMENT naming
    // the key when it is not finite, not whole or beyond the range of int64_t.
    std::int64_t whole_number(const char *key, double value) const;
};

} // namespace ppm::api
