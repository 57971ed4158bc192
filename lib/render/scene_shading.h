// What the renderer adds to a scene's geometry: the materials that geometries name by id, and
// the lights that are not shapes (point, spot). Area lights are geometries with an emission.
// Kept beside the Scene (the API's scene handle holds both), so that the scene layer knows no
// material or light.
#pragma once

#include "render/light.h"
#include "render/material.h"

#include <cstdint>
#include <vector>

namespace ppm {

class SceneShading {
public:
    uint32_t add_material(Material material);
    Material &material(uint32_t material_id); // throws INVALID_ARGUMENT for a bad id
    const std::vector<Material> &materials() const { return materials_; }
    uint32_t add_light(Light light);
    const std::vector<Light> &lights() const { return lights_; }

private:
    std::vector<Material> materials_;
    std::vector<Light> lights_;
};

} // namespace ppm
