// SPDX-License-Identifier: Apache-2.0
// What the renderer adds to a scene's geometry: the materials that geometries name by id, and
// the lights: those that are not shapes (point, spot), and the emission that makes a geometry
// an area light.
// Kept beside the Scene (the API's scene handle holds both), so that the scene layer knows no
// material or light.
#pragma once

#include "light/light.h"
#include "material/material.h"

#include <cstdint>
#include <vector>

namespace ppm {

class SceneShading {
public:
    uint32_t add_material(Material material);
    Material &material(uint32_t material_id); // throws INVALID_ARGUMENT for a bad id
    const std::vector<Material> &materials() const { return materials_; }
    uint32_t add_texture(TextureRef texture);
    const TextureRef &texture(uint32_t texture_id) const; // throws INVALID_ARGUMENT for a bad id
    uint32_t add_light(Light light);
    const std::vector<Light> &lights() const { return lights_; }
    // Area light radiance of a geometry by id; black (the default) for one that emits nothing.
    void set_emission(uint32_t geom_id, const Rgb &radiance);
    Rgb emission(uint32_t geom_id) const;

private:
    std::vector<Material> materials_;
    std::vector<TextureRef> textures_;
    std::vector<Light> lights_;
    std::vector<Rgb> emission_; // by geometry id, as far as set
};

} // namespace ppm
