// SPDX-License-Identifier: Apache-2.0
#include "scenefile/scene_builder.h"

#include "core/error.h"
#include "scenefile/scene_params.h"

#include <sys/stat.h>

#include <array>
#include <initializer_list>

namespace ppm {

namespace {

// A colour given as {"type": "bitmap", ...} rather than a number, [r, g, b] or {"type": "rgb"}.
bool is_bitmap(const JsonNode &color) {
    return color.is_object() && color.has("type") && color.at("type").is_string() &&
           color.at("type").string() == "bitmap";
}

// A texture the generic path reads (ppm_scene_add_texture): any texture object but a bitmap
// with only the keys of libppm's older form (filename, scale, offset).
bool is_generic_texture(const JsonNode &color) {
    if (!color.is_object() || !color.has("type") || !color.at("type").is_string()) return false;
    const std::string type = color.at("type").string();
    if (type == "rgb" || type == "spectrum") return false;
    if (type != "bitmap") return true;
    for (const std::string &key : color.keys())
        if (key != "type" && key != "filename" && key != "scale" && key != "offset") return true;
    return false;
}

} // namespace

bool SceneBuilder::substituted(const JsonNode &node, const Error &e, const std::string &instead) {
    if (!lenient_ || (e.status() != PPM_ERROR_PARSE && e.status() != PPM_ERROR_INVALID_ARGUMENT)) return false;
    lenient_->warnings.push_back(std::string(e.what()) + ": " + instead);
    lenient_->locations.push_back(node.where());
    return true;
}

std::uint32_t SceneBuilder::grey_material(const JsonNode &at) {
    const double grey[3] = {0.5, 0.5, 0.5};
    std::uint32_t id = 0;
    check(at, ppm_scene_add_diffuse_material(scene_, grey, &id));
    return id;
}

void SceneBuilder::check(const JsonNode &node, ppm_status status) const {
    if (status != PPM_OK) fail(status, node.where() + ": " + ppm_last_error_message());
}

std::string SceneBuilder::existing_file(const JsonNode &filename) const {
    const std::string name = filename.string();
    if (name.empty()) filename.fail("expected a file name");
    const std::string path = name[0] == '/' ? name : folder_ + name;
    struct stat info {};
    if (stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode))
        fail(PPM_ERROR_IO, filename.where() + ": file not found: " + path);
    return path;
}

// ---------------------------------------------------------------------------------------------
// bsdfs

void SceneBuilder::add_bsdfs(const JsonNode &bsdfs) {
    bsdfs.require_object();
    for (const std::string &name : bsdfs.keys()) named_bsdfs_[name] = add_bsdf(bsdfs.at(name.c_str()));
}

std::uint32_t SceneBuilder::add_bsdf(const JsonNode &bsdf) {
    try {
        return add_bsdf_as_given(bsdf);
    } catch (const Error &e) {
        if (!substituted(bsdf, e, "diffuse grey 0.5 instead")) throw;
        return grey_material(bsdf);
    }
}

std::uint32_t SceneBuilder::add_bsdf_as_given(const JsonNode &bsdf) {
    bsdf.require_object();
    const std::string type = bsdf.at("type").string();
    // libppm's older bitmap form of a colour goes around the texture table: the material
    // without that colour, then its image through ppm_scene_set_material_texture.
    const char *legacy_key = nullptr;
    for (const char *key : {"reflectance", "specular_reflectance", "diffuse_reflectance"})
        if (bsdf.has(key) && is_bitmap(bsdf.at(key)) && !is_generic_texture(bsdf.at(key))) legacy_key = key;
    const SceneParams params = params_of(bsdf, legacy_key ? std::initializer_list<const char *>{legacy_key}
                                                          : std::initializer_list<const char *>{});
    std::uint32_t id = 0;
    params.check(ppm_scene_add_material(scene_, type.c_str(), params.data(), params.size(), &id));
    if (!legacy_key) return id;

    const JsonNode texture = bsdf.at(legacy_key);
    texture.allow_only({"type", "filename", "scale", "offset"});
    const std::string path = existing_file(texture.at("filename"));
    std::array<double, 2> scale{1, 1}, offset{0, 0};
    if (texture.has("scale")) {
        const JsonNode s = texture.at("scale");
        if (s.is_number()) {
            scale = {s.number(), s.number()};
        } else {
            if (!s.is_array() || s.size() != 2) s.fail("expected a number or [su, sv]");
            scale = {s[0].number(), s[1].number()};
        }
        if (scale[0] == 0 || scale[1] == 0) s.fail("a texture scale must not be zero");
    }
    if (texture.has("offset")) {
        const JsonNode o = texture.at("offset");
        if (!o.is_array() || o.size() != 2) o.fail("expected [ou, ov]");
        offset = {o[0].number(), o[1].number()};
    }
    check(texture, ppm_scene_set_material_texture(scene_, id, path.c_str(), scale.data(), offset.data()));
    return id;
}

SceneParams SceneBuilder::params_of(const JsonNode &object, std::initializer_list<const char *> skip) {
    return SceneParams(
        object, folder_, [this](const JsonNode &nested) { return nested_material(nested); },
        [this](const JsonNode &nested) { return add_texture(nested); }, skip);
}

std::uint32_t SceneBuilder::nested_material(const JsonNode &bsdf) {
    if (bsdf.is_object()) return add_bsdf(bsdf);
    const std::string name = bsdf.string();
    const auto found = named_bsdfs_.find(name);
    if (found == named_bsdfs_.end()) bsdf.fail("no bsdf named '" + name + "' in bsdfs");
    return found->second;
}

std::uint32_t SceneBuilder::add_texture(const JsonNode &texture) {
    try {
        return add_texture_as_given(texture);
    } catch (const Error &e) {
        if (!substituted(texture, e, "left out, the parameter keeps its default")) throw;
        return PPM_INVALID_ID;
    }
}

std::uint32_t SceneBuilder::add_texture_as_given(const JsonNode &texture) {
    texture.require_object();
    const std::string type = texture.at("type").string();
    const SceneParams params = params_of(texture);
    std::uint32_t id = 0;
    params.check(ppm_scene_add_texture(scene_, type.c_str(), params.data(), params.size(), &id));
    return id;
}

// ---------------------------------------------------------------------------------------------
// emitters

void SceneBuilder::add_emitters(const JsonNode &emitters) {
    emitters.require_array();
    for (std::size_t i = 0; i < emitters.size(); ++i) add_emitter(emitters[i]);
}

void SceneBuilder::add_emitter(const JsonNode &emitter) {
    try {
        emitter.require_object();
        const std::string type = emitter.at("type").string();
        const SceneParams params = params_of(emitter);
        params.check(ppm_scene_add_light(scene_, type.c_str(), params.data(), params.size(), nullptr));
    } catch (const Error &e) {
        if (!substituted(emitter, e, "skipped")) throw;
    }
}

// ---------------------------------------------------------------------------------------------
// shapes

void SceneBuilder::add_shapes(const JsonNode &shapes) {
    shapes.require_array();
    if (shapes.size() == 0) shapes.fail("a scene needs at least one shape");
    for (std::size_t i = 0; i < shapes.size(); ++i) add_shape(shapes[i]);
}

std::uint32_t SceneBuilder::shape_material(const JsonNode &shape) {
    if (shape.has("bsdf")) return nested_material(shape.at("bsdf"));
    if (!has_default_material_) {
        const double grey[3] = {0.5, 0.5, 0.5};
        check(shape, ppm_scene_add_diffuse_material(scene_, grey, &default_material_));
        has_default_material_ = true;
    }
    return default_material_;
}

void SceneBuilder::add_shape(const JsonNode &shape) {
    try {
        add_shape_as_given(shape);
    } catch (const Error &e) {
        if (!substituted(shape, e, "skipped")) throw;
    }
}

void SceneBuilder::add_shape_as_given(const JsonNode &shape) {
    shape.require_object();
    const std::string type = shape.at("type").string();
    // A missing file is the scene file's error, located at its name.
    if (shape.has("filename")) existing_file(shape.at("filename"));
    const std::uint32_t material = shape_material(shape);
    SceneParams params = params_of(shape, {"bsdf", "emitter"});
    params.add_material("bsdf", material);
    std::uint32_t geom = 0;
    params.check(ppm_scene_add_shape(scene_, type.c_str(), params.data(), params.size(), &geom));
    if (!shape.has("emitter")) return;
    const JsonNode emitter = shape.at("emitter");
    try {
        emitter.allow_only({"type", "radiance"});
        emitter.at("type").one_of({"area"});
        const std::array<double, 3> radiance =
            emitter.has("radiance") ? emitter.at("radiance").color(false) : std::array<double, 3>{1, 1, 1};
        check(emitter, ppm_scene_set_geometry_emission(scene_, geom, radiance.data()));
    } catch (const Error &e) {
        // The shape is in the scene already: it stays, without emission.
        if (!substituted(emitter, e, "the shape is kept without emission")) throw;
    }
}

} // namespace ppm
