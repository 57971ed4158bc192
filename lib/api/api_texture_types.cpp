// SPDX-License-Identifier: Apache-2.0
// ppm_scene_add_texture: one function per texture type, each reading its parameters with
// Mitsuba 3's names and defaults (src/textures/*.cpp). A new type is a function and a row of
// kTextureTypes.
#include <ppm/ppm.h>

#include "api/api_params.h"
#include "api/api_support.h"
#include "api/api_type_tables.h"

#include <string>

namespace {

using ppm::api::Params;

// Mitsuba's `to_uv` (a 4x4, or its default identity) as libppm's mapping: the 2D affine part
// acting on (u, v, 1), i.e. rows 0 and 1, columns 0, 1 and 3 (Mitsuba's
// Transform4f::extract() keeps the same entries as a 3x3). A singular map is refused.
ppm::TextureMapping read_to_uv(Params &p) {
    const ppm::Affine m = p.transform("to_uv", ppm::Affine{});
    ppm::TextureMapping mapping;
    for (int r = 0; r < 2; ++r) {
        mapping.m[r][0] = m.m[r][0];
        mapping.m[r][1] = m.m[r][1];
        mapping.m[r][2] = m.m[r][3];
    }
    if (mapping.m[0][0] * mapping.m[1][1] - mapping.m[0][1] * mapping.m[1][0] == 0)
        p.fail("to_uv", "is singular on (u, v) (it maps the surface to a line or a point)");
    return mapping;
}

uint32_t add_bitmap(ppm_scene_t &scene, Params &p) {
    const std::string filename = p.string("filename", "");
    if (filename.empty()) p.fail("filename", "is required (the image file)");
    const std::string filter = p.choice("filter_type", {"bilinear", "nearest"}, "bilinear");
    const std::string wrap = p.choice("wrap_mode", {"repeat", "mirror", "clamp"}, "repeat");
    const bool raw = p.boolean("raw", false);
    const ppm::TextureMapping mapping = read_to_uv(p);
    p.finish();
    return scene.shading.add_texture(
        ppm::TextureRef::bitmap(ppm::Texture::load(filename, raw), mapping,
                                filter == "nearest" ? ppm::TextureFilter::Nearest : ppm::TextureFilter::Bilinear,
                                wrap == "mirror"  ? ppm::TextureWrap::Mirror
                                : wrap == "clamp" ? ppm::TextureWrap::Clamp
                                                  : ppm::TextureWrap::Repeat));
}

// Mitsuba 3 src/textures/checkerboard.cpp: two colours (defaults 0.4 and 0.2) in cells of
// half a unit of (u, v) after to_uv.
uint32_t add_checkerboard(ppm_scene_t &scene, Params &p) {
    const ppm::Rgb color0 = p.color("color0", ppm::Rgb(0.4)), color1 = p.color("color1", ppm::Rgb(0.2));
    const ppm::TextureMapping mapping = read_to_uv(p);
    p.finish();
    return scene.shading.add_texture(ppm::TextureRef::checkerboard(color0, color1, mapping));
}

struct TextureType {
    const char *name;
    uint32_t (*add)(ppm_scene_t &, Params &);
};

const TextureType kTextureTypes[] = {
    {"bitmap", add_bitmap},
    {"checkerboard", add_checkerboard},
};

} // namespace

namespace ppm::api {

std::vector<const char *> texture_type_names() { return type_names(kTextureTypes); }

} // namespace ppm::api

extern "C" ppm_status ppm_scene_add_texture(ppm_scene scene, const char *type, const ppm_param *params,
                                            size_t param_count, uint32_t *out_texture_id) {
    return ppm::api::scene_call(scene, [&](ppm_scene_t &s) {
        const TextureType &t = ppm::api::find_type(kTextureTypes, "texture", type);
        Params p(std::string(t.name) + " texture", params, param_count);
        ppm::api::write_id(out_texture_id, t.add(s, p));
    });
}
