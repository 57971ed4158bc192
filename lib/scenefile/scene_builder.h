// SPDX-License-Identifier: Apache-2.0
// Builds the scene part of a scene file (bsdfs, emitters, shapes) through the C API.
#pragma once

#include <ppm/ppm.h>

#include "scenefile/json_node.h"
#include "scenefile/scene_params.h"

#include <map>
#include <string>

namespace ppm {

class SceneBuilder {
public:
    // `folder`: the scene file's folder, for relative file names ("" or ending in '/').
    SceneBuilder(ppm_scene scene, std::string folder) : scene_(scene), folder_(std::move(folder)) {}

    void add_bsdfs(const JsonNode &bsdfs);
    void add_emitters(const JsonNode &emitters);
    void add_shapes(const JsonNode &shapes);

private:
    std::uint32_t add_bsdf(const JsonNode &bsdf);
    // A member naming a bsdf of `bsdfs` or holding one.
    std::uint32_t nested_material(const JsonNode &bsdf);
    std::uint32_t add_texture(const JsonNode &texture);
    SceneParams params_of(const JsonNode &object, std::initializer_list<const char *> skip = {});
    std::uint32_t shape_material(const JsonNode &shape);
    void add_shape(const JsonNode &shape);
    void add_emitter(const JsonNode &emitter);
    // A file name as given, resolved against the folder; fails (IO) if the file is missing.
    std::string existing_file(const JsonNode &filename) const;
    // Throws ppm::Error with the API's status and message, located at `node`.
    void check(const JsonNode &node, ppm_status status) const;

    ppm_scene scene_;
    std::string folder_;
    std::map<std::string, std::uint32_t> named_bsdfs_;
    bool has_default_material_ = false;
    std::uint32_t default_material_ = 0;
};

} // namespace ppm
