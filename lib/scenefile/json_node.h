// SPDX-License-Identifier: Apache-2.0
// Strict, located reading of a JSON document (through jsoncpp): every value knows its key
// path and its line and column in the file, so that every error can say exactly where it is
// ("scene.json:14:9: bsdfs.glass.int_ior: expected a number > 0").
#pragma once

#include "scenefile/source_files.h"

#include <json/value.h>

#include <array>
#include <initializer_list>
#include <string>
#include <vector>

namespace ppm {

// A parsed JSON file, or a scene structure another reader built (Mitsuba XML), with the map
// from its values to lines and columns in the files it came from.
class JsonDocument {
public:
    // Reads and parses `path`: comments allowed; duplicate keys, trailing garbage, NUL bytes,
    // nesting deeper than 64 levels and non-finite numbers rejected. Throws ppm::Error: IO (unreadable file), PARSE (syntax;
    // the message is "path:line:column: what").
    explicit JsonDocument(const std::string &path);
    // Parses `text` as the content of a file named `path` (which need not exist), as above.
    JsonDocument(const std::string &path, std::string text);
    // A structure built by another reader: the offsets of its values are positions in
    // `sources` (0: none).
    JsonDocument(Json::Value root, SourceFiles sources);

    // The (first) file's path.
    const std::string &path() const { return sources_.path(0); }
    const Json::Value &root() const { return root_; }
    // "path:line:column" of a value (the file alone if it has no position).
    std::string location(const Json::Value &value) const;

private:
    void parse();

    SourceFiles sources_;
    bool parsed_here_ = true; // offsets count from the start of the one JSON text (else: positions)
    std::size_t base_ = 0;    // the JSON text's first position in sources_
    Json::Value root_;
};

// A value inside a document with its key path ("shapes[2].radius"). Errors thrown by its
// methods are ppm::Error(PARSE) located at the value.
class JsonNode {
public:
    JsonNode(const JsonDocument &document, const Json::Value &value, std::string key_path)
        : document_(&document), value_(&value), key_path_(std::move(key_path)) {}

    const Json::Value &value() const { return *value_; }
    const std::string &key_path() const { return key_path_; }
    const JsonDocument &document() const { return *document_; }
    // "file:line:column: key.path" for messages.
    std::string where() const;
    [[noreturn]] void fail(const std::string &message) const;

    bool is_object() const { return value_->isObject(); }
    bool is_array() const { return value_->isArray(); }
    bool is_string() const { return value_->isString(); }
    bool is_number() const { return value_->isNumeric() && !value_->isBool(); }

    // Objects: a member (its key path extended), presence, and the check that no key outside
    // `allowed` is there (names the first unknown key and lists the allowed ones).
    void require_object() const;
    void allow_only(std::initializer_list<const char *> allowed) const;
    bool has(const char *key) const;
    JsonNode at(const char *key) const;    // fails if missing
    std::vector<std::string> keys() const; // sorted (jsoncpp keeps no file order)
    // Arrays.
    void require_array() const;
    std::size_t size() const { return value_->size(); }
    JsonNode operator[](std::size_t index) const;

    // Scalars, each failing with "expected ..." when the type or range is wrong.
    double number() const;
    double number_in(double low, double high, bool low_open, bool high_open) const;
    double positive() const;     // > 0
    double non_negative() const; // >= 0
    std::int64_t integer(std::int64_t low, std::int64_t high) const;
    bool boolean() const;
    std::string string() const;
    std::string one_of(std::initializer_list<const char *> choices) const;
    std::array<double, 3> vec3() const;                  // [x, y, z]
    std::array<double, 3> color(bool reflectance) const; // number, [r, g, b] or {"type": "rgb", "value": ...}

    // Member shortcut with a default.
    std::array<double, 3> vec3_or(const char *key, std::array<double, 3> fallback) const {
        return has(key) ? at(key).vec3() : fallback;
    }

private:
    const JsonDocument *document_;
    const Json::Value *value_;
    std::string key_path_;
};

// Joins a key path and a member name ("" + "sensor" = "sensor", "sensor" + "fov" = "sensor.fov").
std::string join_key_path(const std::string &parent, const std::string &key);

} // namespace ppm
