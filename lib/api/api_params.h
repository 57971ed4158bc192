// SPDX-License-Identifier: Apache-2.0
// Reads the named parameters of ppm_scene_add_material / _texture / _light (ppm.h): each
// getter takes the parameter's Mitsuba name and Mitsuba's default, checks the value and
// throws INVALID_ARGUMENT naming the object and the parameter. finish() refuses every
// parameter that no getter asked for, so a misspelt name is an error, not a silent default.
#pragma once

#include <ppm/ppm.h>

#include "core/error.h"
#include "math/rgb.h"
#include "math/vec3.h"

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace ppm::api {

class Params {
public:
    // `what` names the object in messages, e.g. "roughconductor material".
    Params(std::string what, const ppm_param *params, std::size_t count);

    const std::string &what() const { return what_; }
    bool has(const char *name) const;
    // Whether `name` is given as a texture id (a colour or float that a texture may replace).
    bool is_texture(const char *name) const;

    double number(const char *name, double fallback);
    double positive(const char *name, double fallback); // finite and > 0
    // Finite and within [lo, hi].
    double number_in(const char *name, double lo, double hi, double fallback);
    bool boolean(const char *name, bool fallback); // 0 or 1
    // A colour: 1 number (grey) or 3, finite and >= 0.
    Rgb color(const char *name, const Rgb &fallback);
    // A colour with every channel in [0, 1] (energy conservation).
    Rgb reflectance(const char *name, const Rgb &fallback);
    // One or more finite numbers (a list whose length the caller checks).
    std::vector<double> number_list(const char *name);
    // 3 finite numbers.
    Vec3 vec3(const char *name, const Vec3 &fallback);
    // 16 finite numbers, row-major; the last row must be 0 0 0 1.
    Affine transform(const char *name, const Affine &fallback);
    std::string string(const char *name, const std::string &fallback);
    // One of `choices`, else an error listing them (with a suggestion).
    std::string choice(const char *name, std::initializer_list<const char *> choices, const char *fallback);
    // The id of a material or texture parameter; `name` must be given.
    uint32_t material(const char *name);
    uint32_t texture(const char *name);

    // Throws for any parameter no getter has read (unknown for this type: with a suggestion
    // among the names read) and for a name given twice.
    void finish() const;

    // Throws INVALID_ARGUMENT "<what>: parameter '<name>' <message>".
    [[noreturn]] void fail(const char *name, const std::string &message) const;

private:
    const ppm_param *find(const char *name);
    const ppm_param &take(const char *name, ppm_param_type type, const char *expected);
    const double *numbers(const char *name, std::size_t count_wanted, const char *expected);

    std::string what_;
    const ppm_param *params_;
    std::size_t count_;
    std::vector<bool> used_;
    std::vector<std::string> asked_; // every name a getter asked for: the candidates of suggestions
};

// Throws INVALID_ARGUMENT: "unknown <kind> type '<type>'", a suggestion, and the known names.
[[noreturn]] void unknown_type(const char *kind, const char *type, const std::vector<std::string> &known);

// The row of a type table (rows with a `name` member) whose name is `type`.
template <class Row, std::size_t N> const Row &find_type(const Row (&rows)[N], const char *kind, const char *type) {
    if (!type) invalid_argument(std::string(kind) + " type is NULL");
    std::vector<std::string> known;
    for (const Row &row : rows) {
        if (std::string(row.name) == type) return row;
        known.emplace_back(row.name);
    }
    unknown_type(kind, type, known);
}

} // namespace ppm::api
