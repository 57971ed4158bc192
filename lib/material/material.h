// SPDX-License-Identifier: Apache-2.0
// A material as the renderer uses it: a BSDF whose colour may come from a texture (an image
// or a procedural checkerboard).
#pragma once

#include "material/bsdf.h"
#include "material/texture.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace ppm {

// Texture coordinates (s, t) of a surface become (u, v) = M (s, t, 1) before the lookup: the
// 2D affine part of Mitsuba's `to_uv` (rows 0 and 1, columns 0, 1 and 3 of its 4x4).
struct TextureMapping {
    double m[2][3] = {{1, 0, 0}, {0, 1, 0}};

    // u = s * scale_u + offset_u, v = t * scale_v + offset_v (ppm_scene_set_material_texture).
    static TextureMapping scale_offset(double scale_u, double scale_v, double offset_u, double offset_v) {
        TextureMapping t;
        t.m[0][0] = scale_u;
        t.m[0][2] = offset_u;
        t.m[1][1] = scale_v;
        t.m[1][2] = offset_v;
        return t;
    }
    void apply(double s, double t, double *u, double *v) const {
        *u = m[0][0] * s + m[0][1] * t + m[0][2];
        *v = m[1][0] * s + m[1][1] * t + m[1][2];
    }
};

// A texture of the scene (ppm_scene_add_texture), a tagged value: a Mitsuba 3 `bitmap` (an
// image, its filter and wrap mode) or `checkerboard`, and how surface coordinates map onto
// it. Materials that use it copy it; an empty one (kind None) means "no texture".
struct TextureRef {
    enum class Kind : uint8_t { None, Bitmap, Checkerboard };
    Kind kind = Kind::None;
    std::shared_ptr<const Texture> image; // Bitmap
    TextureFilter filter = TextureFilter::Bilinear;
    TextureWrap wrap = TextureWrap::Repeat;
    Rgb color0{0.4}, color1{0.2}; // Checkerboard: Mitsuba's defaults
    TextureMapping mapping;

    static TextureRef bitmap(std::shared_ptr<const Texture> image, const TextureMapping &mapping = {},
                             TextureFilter filter = TextureFilter::Bilinear, TextureWrap wrap = TextureWrap::Repeat) {
        TextureRef t;
        t.kind = Kind::Bitmap;
        t.image = std::move(image);
        t.mapping = mapping;
        t.filter = filter;
        t.wrap = wrap;
        return t;
    }
    static TextureRef checkerboard(const Rgb &color0, const Rgb &color1, const TextureMapping &mapping = {}) {
        TextureRef t;
        t.kind = Kind::Checkerboard;
        t.color0 = color0;
        t.color1 = color1;
        t.mapping = mapping;
        return t;
    }

    explicit operator bool() const { return kind != Kind::None; }

    // The colour at surface texture coordinates (s, t).
    Rgb eval(double s, double t) const {
        double u, v;
        mapping.apply(s, t, &u, &v);
        switch (kind) {
        case Kind::Bitmap: return image->lookup(u, v, filter, wrap);
        case Kind::Checkerboard: {
            // Mitsuba 3 src/textures/checkerboard.cpp (eval): color0 where the fractional parts
            // of u and v are both > 0.5 or both <= 0.5, color1 elsewhere.
            const bool high_u = u - std::floor(u) > 0.5, high_v = v - std::floor(v) > 0.5;
            return high_u == high_v ? color0 : color1;
        }
        case Kind::None:
        default: return Rgb();
        }
    }
    // A scalar (weights, opacities): Mitsuba's eval_1, the luminance of the colour. For a
    // checkerboard Mitsuba 3 keeps its legacy scalar rule, with the cells swapped: color0
    // where exactly one of frac(u), frac(v) is > 0.5 (src/textures/checkerboard.cpp, eval_1).
    double eval_1(double s, double t) const {
        Rgb c;
        if (kind == Kind::Checkerboard) {
            double u, v;
            mapping.apply(s, t, &u, &v);
            const bool high_u = u - std::floor(u) > 0.5, high_v = v - std::floor(v) > 0.5;
            c = high_u != high_v ? color0 : color1;
        } else {
            c = eval(s, t);
        }
        return 0.212671 * c.r + 0.715160 * c.g + 0.072169 * c.b;
    }
};

struct Material {
    Bsdf bsdf;
    // Replaces the BSDF's reflectance (diffuse colour, coat base or mirror tint) when set;
    // values above 1 are clamped so the material stays energy conserving.
    TextureRef texture;

    // Materials made of other materials of the scene (ids into its material list, always
    // of materials made before this one, so there are no cycles). At a hit the renderer
    // picks one component at random with its weight (RenderScene::shade):
    //   Blend (Mitsuba 3 `blendbsdf`): parts[1] with probability w = `weight`, else parts[0],
    //     so the estimate is of (1 - w) f0 + w f1;
    //   Mask (Mitsuba 3 `mask`): parts[0] with probability `weight` (the opacity), else
    //     Bsdf::null() (light passes straight through).
    // `bsdf` and `texture` are unused for them.
    enum class Kind : uint8_t { Single, Blend, Mask };
    Kind kind = Kind::Single;
    uint32_t parts[2] = {0, 0};
    double weight = 0.5;
    TextureRef weight_texture; // replaces `weight` when set (its luminance, clamped to [0, 1])

    static Material blend(uint32_t bsdf_0, uint32_t bsdf_1, double weight, const TextureRef &weight_texture = {}) {
        Material m;
        m.kind = Kind::Blend;
        m.parts[0] = bsdf_0;
        m.parts[1] = bsdf_1;
        m.weight = weight;
        m.weight_texture = weight_texture;
        return m;
    }
    static Material mask(uint32_t bsdf, double opacity, const TextureRef &opacity_texture = {}) {
        Material m;
        m.kind = Kind::Mask;
        m.parts[0] = bsdf;
        m.weight = opacity;
        m.weight_texture = opacity_texture;
        return m;
    }
    bool needs_uv() const { return texture || weight_texture; }
    double weight_at(double s, double t) const {
        return weight_texture ? std::clamp(weight_texture.eval_1(s, t), 0.0, 1.0) : weight;
    }

    // The BSDF at a surface point with texture coordinates (s, t).
    Bsdf at(double s, double t) const {
        if (!texture) return bsdf;
        const Rgb c = texture.eval(s, t);
        return bsdf.with_reflectance({std::min(c.r, 1.0), std::min(c.g, 1.0), std::min(c.b, 1.0)});
    }
};

} // namespace ppm
