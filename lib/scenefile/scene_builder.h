// SPDX-License-Identifier: Apache-2.0
// Builds the scene part of a scene file (bsdfs, emitters, shapes) through the C API.
#pragma once

#include <ppm/ppm.h>

#include "core/error.h"
#include "scenefile/json_node.h"
#include "scenefile/scene_params.h"

#include <map>
#include <string>
#include <vector>

namespace ppm {

// What lenient reading (ppm-render --lenient, for XML files) replaced or left out: each a
// warning, and its location for the summary.
struct LenientLog {
    std::vector<std::string> warnings;
    std::vector<std::string> locations;
};

class SceneBuilder {
public:
    // `folder`: the scene file's folder, for relative file names ("" or ending in '/').
    // `lenient`: when given, a material, texture, light or shape that the library refuses for
    // a value of the file (a parameter or type it does not render) is replaced by diffuse grey
    // 0.5 (a material), left out with its parameter at the default (a texture) or skipped (a
    // light or shape), each logged there; missing files stay errors.
    SceneBuilder(ppm_scene scene, std::string folder, LenientLog *lenient = nullptr)
        : scene_(scene), folder_(std::move(folder)), lenient_(lenient) {}

    void add_bsdfs(const JsonNode &bsdfs);
    void add_emitters(const JsonNode &emitters);
    void add_shapes(const JsonNode &shapes);

private:
    std::uint32_t add_bsdf(const JsonNode &bsdf);
    std::uint32_t add_bsdf_as_given(const JsonNode &bsdf);
    // Lenient reading: true (and logged) when `e` is a refusal of the file's values that may
    // be substituted; false to let it stand.
    bool substituted(const JsonNode &node, const Error &e, const std::string &instead);
    std::uint32_t grey_material(const JsonNode &at);
    // A member naming a bsdf of `bsdfs` or holding one.
    std::uint32_t nested_material(const JsonNode &bsdf);
    std::uint32_t add_texture(const JsonNode &texture);
    std::uint32_t add_texture_as_given(const JsonNode &texture);
    SceneParams params_of(const JsonNode &object, std::initializer_list<const char *> skip = {});
    std::uint32_t shape_material(const JsonNode &shape);
    void add_shape(const JsonNode &shape);
    void add_shape_as_given(const JsonNode &shape);
    void add_emitter(const JsonNode &emitter);
    // A file name as given, resolved against the folder; fails (IO) if the file is missing.
    std::string existing_file(const JsonNode &filename) const;
    // Throws ppm::Error with the API's status and message, located at `node`.
    void check(const JsonNode &node, ppm_status status) const;

    ppm_scene scene_;
    std::string folder_;
    LenientLog *lenient_;
    std::map<std::string, std::uint32_t> named_bsdfs_;
    bool has_default_material_ = false;
    std::uint32_t default_material_ = 0;
};

} // namespace ppm
