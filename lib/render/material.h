// SPDX-License-Identifier: Apache-2.0
// A material as the renderer uses it: a BSDF whose colour may come from an image texture.
#pragma once

#include "render/bsdf.h"
#include "render/texture.h"

#include <algorithm>
#include <memory>

namespace ppm {

// Texture coordinates (s, t) of a surface become (s * scale_u + offset_u, t * scale_v +
// offset_v) before the lookup, and the texture repeats: a scale of 4 tiles it 4 times.
struct TextureMapping {
    double scale_u = 1, scale_v = 1;
    double offset_u = 0, offset_v = 0;
};

// A texture of the scene (ppm_scene_add_texture): an image and how surface coordinates map
// onto it. Materials that use it copy it.
struct TextureRef {
    std::shared_ptr<const Texture> texture;
    TextureMapping mapping;
};

struct Material {
    Bsdf bsdf;
    // Replaces the BSDF's reflectance (diffuse colour, coat base or mirror tint) when set;
    // values above 1 are clamped so the material stays energy conserving.
    std::shared_ptr<const Texture> texture;
    TextureMapping mapping;

    // The BSDF at a surface point with texture coordinates (s, t).
    Bsdf at(double s, double t) const {
        if (!texture) return bsdf;
        const Rgb c = texture->lookup(s * mapping.scale_u + mapping.offset_u, t * mapping.scale_v + mapping.offset_v);
        return bsdf.with_reflectance({std::min(c.r, 1.0), std::min(c.g, 1.0), std::min(c.b, 1.0)});
    }
};

} // namespace ppm
