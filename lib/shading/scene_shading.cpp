// SPDX-License-Identifier: Apache-2.0
#include "shading/scene_shading.h"

#include "core/error.h"

#include <string>

namespace ppm {

uint32_t SceneShading::add_material(Material material) {
    if (materials_.size() >= PPM_INVALID_ID - 1) invalid_argument("too many materials in a scene");
    materials_.push_back(std::move(material));
    return static_cast<uint32_t>(materials_.size() - 1);
}

Material &SceneShading::material(uint32_t material_id) {
    if (material_id >= materials_.size())
        invalid_argument("material id " + std::to_string(material_id) + " does not exist (the scene has " +
                         std::to_string(materials_.size()) + " materials)");
    return materials_[material_id];
}

uint32_t SceneShading::add_texture(TextureRef texture) {
    if (textures_.size() >= PPM_INVALID_ID - 1) invalid_argument("too many textures in a scene");
    textures_.push_back(std::move(texture));
    return static_cast<uint32_t>(textures_.size() - 1);
}

const TextureRef &SceneShading::texture(uint32_t texture_id) const {
    if (texture_id >= textures_.size())
        invalid_argument("texture id " + std::to_string(texture_id) + " does not exist (the scene has " +
                         std::to_string(textures_.size()) + " textures)");
    return textures_[texture_id];
}

uint32_t SceneShading::add_light(Light light) {
    if (lights_.size() >= PPM_INVALID_ID - 1) invalid_argument("too many lights in a scene");
    lights_.push_back(light);
    return static_cast<uint32_t>(lights_.size() - 1);
}

void SceneShading::set_emission(uint32_t geom_id, const Rgb &radiance) {
    if (geom_id >= emission_.size()) emission_.resize(std::size_t(geom_id) + 1);
    emission_[geom_id] = radiance;
}

Rgb SceneShading::emission(uint32_t geom_id) const { return geom_id < emission_.size() ? emission_[geom_id] : Rgb(); }

} // namespace ppm
