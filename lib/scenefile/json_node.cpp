// SPDX-License-Identifier: Apache-2.0
#include "scenefile/json_node.h"

#include "core/error.h"
#include "core/suggest.h"
#include "io/text_file.h"

#include <json/reader.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>

namespace ppm {

namespace {

[[noreturn]] void parse_error(const std::string &message) { fail(PPM_ERROR_PARSE, message); }

// jsoncpp's messages look like "* Line 3, Column 5\n  Missing ',' or '}' in object declaration\n";
// this turns the first one into "path:3:5: Missing ',' or '}' in object declaration".
std::string first_jsoncpp_error(const std::string &path, const std::string &errors) {
    int line = 0, column = 0, consumed = 0;
    if (std::sscanf(errors.c_str(), "* Line %d, Column %d%n", &line, &column, &consumed) == 2) {
        const std::size_t start = errors.find_first_not_of(" \n", static_cast<std::size_t>(consumed));
        const std::size_t end = start == std::string::npos ? start : errors.find('\n', start);
        const std::string message = start == std::string::npos ? "syntax error" : errors.substr(start, end - start);
        return path + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message;
    }
    return path + ": " + errors;
}

// Scene files nest a few levels deep; anything deeper is refused before jsoncpp recurses into
// it (its own stack limit throws an exception that carries no position).
constexpr int kMaxNesting = 64;

// The offset of the first NUL byte anywhere, or else of the bracket that opens level
// kMaxNesting + 1 outside strings and comments; npos if there is none. `what` says which.
std::size_t first_unreadable_byte(const std::string &text, std::string &what) {
    const std::size_t nul = text.find('\0');
    if (nul != std::string::npos) {
        what = "NUL byte in the file";
        return nul;
    }
    int depth = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '"') {
            for (++i; i < text.size() && text[i] != '"'; ++i)
                if (text[i] == '\\') ++i;
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
            i = text.find('\n', i);
            if (i == std::string::npos) break;
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
            i = text.find("*/", i + 2);
            if (i == std::string::npos) break;
            ++i;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxNesting) {
                what = "arrays and objects nested more than " + std::to_string(kMaxNesting) + " levels deep";
                return i;
            }
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return std::string::npos;
}

std::vector<std::string> names_of(std::initializer_list<const char *> names) {
    return std::vector<std::string>(names.begin(), names.end());
}

std::string describe_allowed(std::initializer_list<const char *> allowed) {
    std::string list;
    for (const char *key : allowed) list += (list.empty() ? "" : ", ") + std::string(key);
    return list;
}

} // namespace

std::string join_key_path(const std::string &parent, const std::string &key) {
    return parent.empty() ? key : parent + "." + key;
}

JsonDocument::JsonDocument(const std::string &path) : JsonDocument(path, read_text_file(path)) {}

JsonDocument::JsonDocument(const std::string &path, std::string text) {
    base_ = sources_.add(path, std::move(text));
    parse();
}

JsonDocument::JsonDocument(Json::Value root, SourceFiles sources)
    : sources_(std::move(sources)), parsed_here_(false), root_(std::move(root)) {
    if (sources_.count() == 0) sources_.add("<scene>", std::string());
}

void JsonDocument::parse() {
    const std::string &text = sources_.text(0);
    Json::CharReaderBuilder builder;
    builder["allowComments"] = true;
    builder["strictRoot"] = true;
    builder["allowDroppedNullPlaceholders"] = false;
    builder["allowNumericKeys"] = false;
    builder["allowSingleQuotes"] = false;
    builder["failIfExtra"] = true;
    builder["allowTrailingCommas"] = false;
    builder["rejectDupKeys"] = true;
    builder["allowSpecialFloats"] = false;
    builder["stackLimit"] = 200;
    std::string unreadable;
    const std::size_t bad = first_unreadable_byte(text, unreadable);
    if (bad != std::string::npos) parse_error(sources_.location(base_ + bad) + ": " + unreadable);
    const std::unique_ptr<Json::CharReader> reader(builder.newCharReader());
    std::string errors;
    bool parsed = false;
    try {
        parsed = reader->parse(text.data(), text.data() + text.size(), &root_, &errors);
    } catch (const std::exception &e) {
        parse_error(path() + ": " + e.what());
    }
    if (!parsed) parse_error(first_jsoncpp_error(path(), errors));
    if (!root_.isObject()) parse_error(location(root_) + ": the scene must be a JSON object { ... }");
}

std::string JsonDocument::location(const Json::Value &value) const {
    const std::ptrdiff_t offset = value.getOffsetStart();
    if (!parsed_here_) return sources_.location(offset < 0 ? 0 : static_cast<std::size_t>(offset));
    if (offset < 0 || static_cast<std::size_t>(offset) > sources_.text(0).size()) return path();
    return sources_.location(base_ + static_cast<std::size_t>(offset));
}

std::string JsonNode::where() const {
    const std::string location = document_->location(*value_);
    return key_path_.empty() ? location : location + ": " + key_path_;
}

void JsonNode::fail(const std::string &message) const { parse_error(where() + ": " + message); }

void JsonNode::require_object() const {
    if (!value_->isObject()) fail("expected an object { ... }");
}

void JsonNode::allow_only(std::initializer_list<const char *> allowed) const {
    require_object();
    for (const std::string &key : value_->getMemberNames()) {
        const bool known = std::any_of(allowed.begin(), allowed.end(), [&](const char *a) { return key == a; });
        if (!known)
            JsonNode(*document_, (*value_)[key], join_key_path(key_path_, key))
                .fail("unknown key" + did_you_mean(key, names_of(allowed)) +
                      " (allowed here: " + describe_allowed(allowed) + ")");
    }
}

bool JsonNode::has(const char *key) const { return value_->isObject() && value_->isMember(key); }

JsonNode JsonNode::at(const char *key) const {
    require_object();
    const Json::Value *member = value_->find(key, key + std::char_traits<char>::length(key));
    if (!member) fail(std::string("missing key '") + key + "'");
    return JsonNode(*document_, *member, join_key_path(key_path_, key));
}

std::vector<std::string> JsonNode::keys() const {
    require_object();
    std::vector<std::string> names = value_->getMemberNames();
    std::sort(names.begin(), names.end());
    return names;
}

void JsonNode::require_array() const {
    if (!value_->isArray()) fail("expected an array [ ... ]");
}

JsonNode JsonNode::operator[](std::size_t index) const {
    return JsonNode(*document_, (*value_)[static_cast<Json::ArrayIndex>(index)],
                    key_path_ + "[" + std::to_string(index) + "]");
}

double JsonNode::number() const {
    if (!is_number()) fail("expected a number");
    const double v = value_->asDouble();
    if (!std::isfinite(v)) fail("expected a finite number");
    return v;
}

double JsonNode::number_in(double low, double high, bool low_open, bool high_open) const {
    const double v = is_number() ? value_->asDouble() : std::numeric_limits<double>::quiet_NaN();
    const bool above = low_open ? v > low : v >= low;
    const bool below = high_open ? v < high : v <= high;
    if (!(above && below && std::isfinite(v))) {
        std::ostringstream range;
        range << "expected a number in " << (low_open ? "(" : "[") << format_number(low) << ", " << format_number(high)
              << (high_open ? ")" : "]");
        fail(range.str());
    }
    return v;
}

double JsonNode::positive() const {
    const double v = is_number() ? value_->asDouble() : 0;
    if (!(v > 0 && std::isfinite(v))) fail("expected a number > 0");
    return v;
}

double JsonNode::non_negative() const {
    const double v = is_number() ? value_->asDouble() : -1;
    if (!(v >= 0 && std::isfinite(v))) fail("expected a number >= 0");
    return v;
}

std::int64_t JsonNode::integer(std::int64_t low, std::int64_t high) const {
    const std::string range = "expected a whole number in [" + std::to_string(low) + ", " + std::to_string(high) + "]";
    if (!is_number()) fail(range);
    const double v = value_->asDouble();
    if (!(std::floor(v) == v && v >= static_cast<double>(low) && v <= static_cast<double>(high))) fail(range);
    return static_cast<std::int64_t>(v); // whole and in range: exact (the ranges used stay below 2^53)
}

bool JsonNode::boolean() const {
    if (!value_->isBool()) fail("expected true or false");
    return value_->asBool();
}

std::string JsonNode::string() const {
    if (!value_->isString()) fail("expected a string");
    std::string s = value_->asString();
    // A C string (a file name, a key) would end at the NUL and name something else.
    if (s.find('\0') != std::string::npos) fail("a string must not contain a NUL character (\\u0000)");
    return s;
}

std::string JsonNode::one_of(std::initializer_list<const char *> choices) const {
    const std::string expected = "expected one of: " + describe_allowed(choices);
    if (!value_->isString()) fail(expected);
    const std::string s = value_->asString();
    for (const char *choice : choices)
        if (s == choice) return s;
    fail("'" + s + "' is not known" + did_you_mean(s, names_of(choices)) + "; " + expected);
}

std::array<double, 3> JsonNode::vec3() const {
    if (!value_->isArray() || value_->size() != 3) fail("expected an array of 3 numbers [x, y, z]");
    return {(*this)[0].number(), (*this)[1].number(), (*this)[2].number()};
}

std::array<double, 3> JsonNode::color(bool reflectance) const {
    std::array<double, 3> c{};
    if (is_number()) {
        const double v = number();
        c = {v, v, v};
    } else if (value_->isArray()) {
        if (value_->size() != 3) fail("expected a colour: a number, [r, g, b] or {\"type\": \"rgb\", \"value\": ...}");
        c = vec3();
    } else if (value_->isObject()) {
        allow_only({"type", "value"});
        if (at("type").one_of({"rgb"}) != "rgb") fail("expected type 'rgb'");
        return at("value").color(reflectance);
    } else {
        fail("expected a colour: a number, [r, g, b] or {\"type\": \"rgb\", \"value\": ...}");
    }
    for (double v : c) {
        if (v < 0) fail("colour channels must be >= 0");
        if (reflectance && v > 1) fail("a reflectance must lie in [0, 1] in every channel (energy conservation)");
    }
    return c;
}

} // namespace ppm
