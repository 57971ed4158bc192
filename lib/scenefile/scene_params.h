// SPDX-License-Identifier: Apache-2.0
// A JSON object's members as the named parameters of ppm_scene_add_material / _texture /
// _light (ppm.h), so that a type registered in the API's tables is at once readable from JSON
// and Mitsuba XML with its Mitsuba names. The list owns the numbers and strings it points to.
#pragma once

#include <ppm/ppm.h>

#include "scenefile/json_node.h"

#include <deque>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

namespace ppm {

class SceneParams {
public:
    // Resolves a member that names or holds a nested BSDF (keys "bsdf", "bsdf_0", ...) to a
    // material id, and one that holds a nested texture object to a texture id.
    using NestedMaterial = std::function<std::uint32_t(const JsonNode &)>;
    using NestedTexture = std::function<std::uint32_t(const JsonNode &)>;

    // Every member of `object` but "type" and those in `skip`: numbers, booleans (0/1) and
    // arrays of numbers (nested arrays flattened in order) as numbers; {"type": "rgb",
    // "value": ...} as its colour; `to_world`/`to_uv` (any transform form) as 16 numbers;
    // strings as strings; "bsdf*" members as materials; other objects as textures (a texture
    // callback that returns PPM_INVALID_ID leaves the member out: lenient reading). `folder`
    // resolves `filename` members.
    SceneParams(const JsonNode &object, const std::string &folder, const NestedMaterial &material,
                const NestedTexture &texture, std::initializer_list<const char *> skip = {});

    // Adds a material parameter that the file gives in another form (a shape's default).
    void add_material(const std::string &name, std::uint32_t id);

    const ppm_param *data() const { return params_.data(); }
    std::size_t size() const { return params_.size(); }

    // Throws the API's error for a failed call, located at the member its message names
    // ("parameter 'alpha'") or else at the object.
    void check(ppm_status status) const;

private:
    void add_numbers(const std::string &name, std::vector<double> values);

    JsonNode object_;
    std::vector<ppm_param> params_;
    std::deque<std::string> names_, strings_;
    std::deque<std::vector<double>> numbers_;
};

} // namespace ppm
