// SPDX-License-Identifier: Apache-2.0
// ppm_scene_add_texture: one function per texture type, each reading its parameters with
// Mitsuba 3's names and defaults (src/textures/*.cpp). A new type is a function and a row of
// kTextureTypes.
#include <ppm/ppm.h>

#include "api/api_params.h"
#include "api/api_support.h"

#include <string>

namespace {

using ppm::api::Params;

// Mitsuba's `to_uv` as libppm's mapping, which scales and offsets u and v: rotation and
// shear are refused.
ppm::TextureMapping read_to_uv(Params &p) {
    const ppm::Affine m = p.transform("to_uv", ppm::Affine{});
    if (m.m[0][1] != 0 || m.m[1][0] != 0)
        p.fail("to_uv", "may only scale and translate u and v (no rotation or shear)");
    if (m.m[0][0] == 0 || m.m[1][1] == 0) p.fail("to_uv", "must not scale u or v by zero");
    ppm::TextureMapping mapping;
    mapping.scale_u = m.m[0][0];
    mapping.scale_v = m.m[1][1];
    mapping.offset_u = m.m[0][3];
    mapping.offset_v = m.m[1][3];
    return mapping;
}

uint32_t add_bitmap(ppm_scene_t &scene, Params &p) {
    const std::string filename = p.string("filename", "");
    if (filename.empty()) p.fail("filename", "is required (the image file)");
    const ppm::TextureMapping mapping = read_to_uv(p);
    p.finish();
    return scene.shading.add_texture({ppm::Texture::load(filename), mapping});
}

struct TextureType {
    const char *name;
    uint32_t (*add)(ppm_scene_t &, Params &);
};

const TextureType kTextureTypes[] = {
    {"bitmap", add_bitmap},
};

} // namespace

extern "C" ppm_status ppm_scene_add_texture(ppm_scene scene, const char *type, const ppm_param *params,
                                            size_t param_count, uint32_t *out_texture_id) {
    return ppm::api::scene_call(scene, [&](ppm_scene_t &s) {
        const TextureType &t = ppm::api::find_type(kTextureTypes, "texture", type);
        Params p(std::string(t.name) + " texture", params, param_count);
        ppm::api::write_id(out_texture_id, t.add(s, p));
    });
}
