// SPDX-License-Identifier: Apache-2.0
#include "api/api_params.h"

#include "core/error.h"
#include "core/suggest.h"
#include "math/limits.h"

#include <cmath>
#include <cstring>
#include <type_traits>

namespace ppm::api {

namespace {

const char *type_name(ppm_param_type type) {
    switch (type) {
    case PPM_PARAM_NUMBERS: return "numbers";
    case PPM_PARAM_STRING: return "a string";
    case PPM_PARAM_MATERIAL: return "a material id";
    case PPM_PARAM_TEXTURE: return "a texture id";
    }
    return "an unknown kind";
}

} // namespace

Params::Params(std::string what, const ppm_param *params, std::size_t count)
    : what_(std::move(what)), params_(params), count_(count), used_(count, false) {
    if (count > 0 && !params) invalid_argument(what_ + ": params is NULL but param_count is " + std::to_string(count));
    for (std::size_t i = 0; i < count; ++i) {
        if (!params[i].name) invalid_argument(what_ + ": parameter " + std::to_string(i) + " has no name (NULL)");
        // A caller's bad value is not one of the enumerators, and loading it as the enum type
        // would be undefined in C++: read its bytes as the underlying integer.
        std::underlying_type_t<ppm_param_type> raw = 0;
        std::memcpy(&raw, &params[i].type, sizeof raw);
        if (raw != PPM_PARAM_NUMBERS && raw != PPM_PARAM_STRING && raw != PPM_PARAM_MATERIAL &&
            raw != PPM_PARAM_TEXTURE)
            fail(params[i].name, "has an unknown type " + std::to_string(static_cast<long long>(raw)));
        const ppm_param_type t = params[i].type;
        if (t == PPM_PARAM_NUMBERS && params[i].count > 0 && !params[i].numbers)
            fail(params[i].name, "has numbers NULL and count " + std::to_string(params[i].count));
        if (t == PPM_PARAM_STRING && !params[i].string) fail(params[i].name, "is a string, but NULL");
        for (std::size_t j = 0; j < i; ++j)
            if (std::strcmp(params[j].name, params[i].name) == 0) fail(params[i].name, "is given twice");
    }
}

void Params::fail(const char *name, const std::string &message) const {
    invalid_argument(what_ + ": parameter '" + name + "' " + message);
}

const ppm_param *Params::find(const char *name) {
    asked_.emplace_back(name);
    for (std::size_t i = 0; i < count_; ++i)
        if (std::strcmp(params_[i].name, name) == 0) {
            used_[i] = true;
            return &params_[i];
        }
    return nullptr;
}

bool Params::has(const char *name) const {
    for (std::size_t i = 0; i < count_; ++i)
        if (std::strcmp(params_[i].name, name) == 0) return true;
    return false;
}

bool Params::is_texture(const char *name) const {
    for (std::size_t i = 0; i < count_; ++i)
        if (std::strcmp(params_[i].name, name) == 0) return params_[i].type == PPM_PARAM_TEXTURE;
    return false;
}

const ppm_param &Params::take(const char *name, ppm_param_type type, const char *expected) {
    const ppm_param *p = find(name);
    if (!p) fail(name, std::string("is required (") + expected + ")");
    if (p->type != type) fail(name, std::string("must be ") + expected + ", not " + type_name(p->type));
    return *p;
}

const double *Params::numbers(const char *name, std::size_t count_wanted, const char *expected) {
    const ppm_param &p = take(name, PPM_PARAM_NUMBERS, expected);
    if (p.count != count_wanted)
        fail(name, std::string("must be ") + expected + ", not " + std::to_string(p.count) + " numbers");
    for (std::size_t i = 0; i < p.count; ++i)
        if (!std::isfinite(p.numbers[i])) fail(name, "must be finite, not " + format_number(p.numbers[i]));
    return p.numbers;
}

std::vector<double> Params::number_list(const char *name) {
    const ppm_param &p = take(name, PPM_PARAM_NUMBERS, "numbers");
    if (p.count == 0) fail(name, "must hold at least one number");
    for (std::size_t i = 0; i < p.count; ++i)
        if (!std::isfinite(p.numbers[i])) fail(name, "must be finite, not " + format_number(p.numbers[i]));
    return std::vector<double>(p.numbers, p.numbers + p.count);
}

double Params::number(const char *name, double fallback) {
    if (!has(name)) {
        find(name);
        return fallback;
    }
    return numbers(name, 1, "a number")[0];
}

double Params::positive(const char *name, double fallback) {
    const double v = number(name, fallback);
    if (!(v > 0)) fail(name, "must be > 0, not " + format_number(v));
    return v;
}

double Params::number_in(const char *name, double lo, double hi, double fallback) {
    const double v = number(name, fallback);
    if (!(v >= lo && v <= hi))
        fail(name, "must lie in [" + format_number(lo) + ", " + format_number(hi) + "], not " + format_number(v));
    return v;
}

bool Params::boolean(const char *name, bool fallback) {
    const double v = number(name, fallback ? 1 : 0);
    if (v != 0 && v != 1) fail(name, "is a boolean: 0 or 1, not " + format_number(v));
    return v == 1;
}

Rgb Params::color(const char *name, const Rgb &fallback) {
    if (!has(name)) {
        find(name);
        return fallback;
    }
    const ppm_param *p = find(name);
    if (p->type != PPM_PARAM_NUMBERS || (p->count != 1 && p->count != 3))
        fail(name, std::string("must be a colour (1 or 3 numbers), not ") +
                       (p->type == PPM_PARAM_NUMBERS ? std::to_string(p->count) + " numbers" : type_name(p->type)));
    const double *v = numbers(name, p->count, "a colour (1 or 3 numbers)");
    const Rgb c = p->count == 1 ? Rgb(v[0]) : Rgb{v[0], v[1], v[2]};
    if (c.min() < 0) fail(name, "must be >= 0 in every channel");
    return c;
}

Rgb Params::reflectance(const char *name, const Rgb &fallback) {
    const Rgb c = color(name, fallback);
    if (c.max() > 1) fail(name, "must be at most 1 in every channel (energy conservation)");
    return c;
}

Vec3 Params::vec3(const char *name, const Vec3 &fallback) {
    if (!has(name)) {
        find(name);
        return fallback;
    }
    return Vec3::from(numbers(name, 3, "3 numbers"));
}

Affine Params::transform(const char *name, const Affine &fallback) {
    if (!has(name)) {
        find(name);
        return fallback;
    }
    const double *m = numbers(name, 16, "a 4x4 matrix (16 numbers, row-major)");
    if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1)
        fail(name, "must be affine: its last row must be 0 0 0 1");
    Affine a;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) a.m[r][c] = m[4 * r + c];
    return a;
}

std::string Params::string(const char *name, const std::string &fallback) {
    if (!has(name)) {
        find(name);
        return fallback;
    }
    return take(name, PPM_PARAM_STRING, "a string").string;
}

std::string Params::choice(const char *name, std::initializer_list<const char *> choices, const char *fallback) {
    const std::string v = string(name, fallback);
    std::vector<std::string> names(choices.begin(), choices.end());
    for (const std::string &c : names)
        if (c == v) return v;
    std::string list;
    for (const std::string &c : names) list += (list.empty() ? "" : ", ") + c;
    fail(name, "must be one of " + list + ", not '" + v + "'" + did_you_mean(v, names));
}

uint32_t Params::material(const char *name) { return take(name, PPM_PARAM_MATERIAL, "a material id").id; }

uint32_t Params::texture(const char *name) { return take(name, PPM_PARAM_TEXTURE, "a texture id").id; }

void Params::finish() const {
    for (std::size_t i = 0; i < count_; ++i)
        if (!used_[i])
            invalid_argument(what_ + " has no parameter '" + params_[i].name + "'" +
                             did_you_mean(params_[i].name, asked_));
}

void unknown_type(const char *kind, const char *type, const std::vector<std::string> &known) {
    std::string list;
    for (const std::string &n : known) list += (list.empty() ? "" : ", ") + n;
    invalid_argument("unknown " + std::string(kind) + " type '" + type + "'" + did_you_mean(type, known) +
                     " (known: " + list + ")");
}

} // namespace ppm::api
