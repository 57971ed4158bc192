// SPDX-License-Identifier: Apache-2.0
#include "scenefile/scene_params.h"

#include "core/error.h"
#include "scenefile/transform.h"

#include <algorithm>

namespace ppm {

namespace {

bool is_colour_object(const JsonNode &node) {
    return node.is_object() && node.has("type") && node.at("type").is_string() &&
           (node.at("type").string() == "rgb" || node.at("type").string() == "spectrum");
}

bool names_material(const std::string &key) { return key.compare(0, 4, "bsdf") == 0; }

// The numbers of an array, nested arrays flattened in order ([[x, y, z], ...] control points).
void append_numbers(const JsonNode &array, std::vector<double> &out) {
    for (std::size_t i = 0; i < array.size(); ++i) {
        const JsonNode element = array[i];
        if (element.is_array())
            append_numbers(element, out);
        else
            out.push_back(element.number());
    }
}

} // namespace

SceneParams::SceneParams(const JsonNode &object, const std::string &folder, const NestedMaterial &material,
                         const NestedTexture &texture, std::initializer_list<const char *> skip)
    : object_(object) {
    object.require_object();
    for (const std::string &key : object.keys()) {
        if (key == "type") continue;
        if (std::any_of(skip.begin(), skip.end(), [&](const char *name) { return key == name; })) continue;
        const JsonNode member = object.at(key.c_str());
        const Json::Value &v = member.value();
        if (key == "to_world" || key == "to_uv") {
            const std::array<double, 16> m = matrix16(parse_transform(member));
            add_numbers(key, std::vector<double>(m.begin(), m.end()));
        } else if (names_material(key) && (member.is_object() || member.is_string())) {
            names_.push_back(key);
            params_.push_back({names_.back().c_str(), PPM_PARAM_MATERIAL, nullptr, 0, nullptr, material(member)});
        } else if (v.isBool()) {
            add_numbers(key, {v.asBool() ? 1.0 : 0.0});
        } else if (member.is_number()) {
            add_numbers(key, {member.number()});
        } else if (member.is_array()) {
            std::vector<double> values;
            append_numbers(member, values);
            add_numbers(key, std::move(values));
        } else if (is_colour_object(member)) {
            const std::array<double, 3> c = member.color(false);
            add_numbers(key, {c[0], c[1], c[2]});
        } else if (member.is_string()) {
            std::string s = member.string();
            if (key == "filename" && !s.empty() && s[0] != '/') s = folder + s;
            names_.push_back(key);
            strings_.push_back(std::move(s));
            params_.push_back({names_.back().c_str(), PPM_PARAM_STRING, nullptr, 0, strings_.back().c_str(), 0});
        } else if (member.is_object()) {
            const std::uint32_t id = texture(member);
            if (id == PPM_INVALID_ID) continue;
            names_.push_back(key);
            params_.push_back({names_.back().c_str(), PPM_PARAM_TEXTURE, nullptr, 0, nullptr, id});
        } else {
            member.fail("expected a number, an array of numbers, a string or an object");
        }
    }
}

void SceneParams::add_material(const std::string &name, std::uint32_t id) {
    names_.push_back(name);
    params_.push_back({names_.back().c_str(), PPM_PARAM_MATERIAL, nullptr, 0, nullptr, id});
}

void SceneParams::add_numbers(const std::string &name, std::vector<double> values) {
    names_.push_back(name);
    numbers_.push_back(std::move(values));
    params_.push_back(
        {names_.back().c_str(), PPM_PARAM_NUMBERS, numbers_.back().data(), numbers_.back().size(), nullptr, 0});
}

void SceneParams::check(ppm_status status) const {
    if (status == PPM_OK) return;
    const std::string message = ppm_last_error_message();
    // A value the API refuses is, in a scene file, an error of the file (as the builder's own
    // checks of values are), as is an unknown type; a refusal that names neither (degenerate
    // geometry the typed calls refuse) stays the API's.
    const bool of_the_file = message.find("parameter '") != std::string::npos || message.compare(0, 8, "unknown ") == 0;
    if (status == PPM_ERROR_INVALID_ARGUMENT && of_the_file) status = PPM_ERROR_PARSE;
    if (message.compare(0, 8, "unknown ") == 0 && object_.has("type"))
        fail(status, object_.at("type").where() + ": " + message);
    for (const std::string &name : names_)
        if (message.find("parameter '" + name + "'") != std::string::npos)
            fail(status, object_.at(name.c_str()).where() + ": " + message);
    // A file that cannot be read or parsed is the error of the member that names it.
    if ((status == PPM_ERROR_IO || status == PPM_ERROR_PARSE) && object_.has("filename"))
        fail(status, object_.at("filename").where() + ": " + message);
    fail(status, object_.where() + ": " + message);
}

} // namespace ppm
