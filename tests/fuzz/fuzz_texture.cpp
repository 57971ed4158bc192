// SPDX-License-Identifier: Apache-2.0
// Image textures through ppm_scene_set_material_texture (OpenImageIO underneath). The file
// gets the extension its leading bytes suggest (PNG, OpenEXR, PFM, Radiance HDR, JPEG; .png
// otherwise), as a user's file would. A texture either loads, and a textured floor and sphere
// then render one finite pass, or is refused with IO, INVALID_ARGUMENT or PARSE naming the file.
#include "fuzz_support.h"

#include <cstring>

namespace {

const char *extension_for(const uint8_t *data, size_t size) {
    const auto starts = [&](const char *magic) {
        const size_t n = std::strlen(magic);
        return size >= n && std::memcmp(data, magic, n) == 0;
    };
    if (starts("v/1\x01")) return "exr";
    if (starts("PF") || starts("Pf")) return "pfm";
    if (starts("#?")) return "hdr";
    if (starts("\xff\xd8\xff")) return "jpg";
    return "png";
}

void check(ppm_status status, const char *call) {
    if (status != PPM_OK) fuzz::die(call);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const std::string name = std::string("texture.") + extension_for(data, size);
    const std::string path = fuzz::write_temp_file(name, data, size);
    ppm_scene scene = nullptr;
    check(ppm_scene_create(fuzz::context(), &scene), "ppm_scene_create");
    const double grey[3] = {0.8, 0.8, 0.8};
    uint32_t material = 0;
    check(ppm_scene_add_diffuse_material(scene, grey, &material), "ppm_scene_add_diffuse_material");
    const double scale[2] = {2, 2}, offset[2] = {0.25, 0};
    const ppm_status status = ppm_scene_set_material_texture(scene, material, path.c_str(), scale, offset);
    if (status != PPM_OK) {
        // PARSE: a header claiming more pixels than the file's bytes can hold.
        fuzz::expect_located_error(status, {PPM_ERROR_IO, PPM_ERROR_INVALID_ARGUMENT, PPM_ERROR_PARSE}, name,
                                   "ppm_scene_set_material_texture");
        ppm_scene_release(scene);
        return 0;
    }
    const double floor_origin[3] = {-2, 0, -2}, edge_u[3] = {0, 0, 4}, edge_v[3] = {4, 0, 0};
    const double center[3] = {0, 0.5, 0}, light[3] = {0, 2, 2}, intensity[3] = {4, 4, 4};
    uint32_t floor_id = 0, sphere_id = 0;
    check(ppm_scene_add_quad(scene, floor_origin, edge_u, edge_v, &floor_id), "ppm_scene_add_quad");
    check(ppm_scene_add_sphere(scene, center, 0.5, &sphere_id), "ppm_scene_add_sphere");
    check(ppm_scene_add_point_light(scene, light, intensity, nullptr), "ppm_scene_add_point_light");
    check(ppm_scene_commit(scene), "ppm_scene_commit");
    ppm_camera camera{};
    camera.origin[1] = 1.5, camera.origin[2] = 3;
    camera.target[1] = 0.3;
    camera.up[1] = 1;
    camera.fov = 50;
    camera.width = camera.height = fuzz::kFilmSize;
    ppm_renderer renderer = nullptr;
    check(ppm_renderer_create(scene, &camera, &renderer), "ppm_renderer_create with a texture that loaded");
    fuzz::limit_renderer(renderer);
    fuzz::render_one_pass(renderer);
    ppm_renderer_release(renderer);
    ppm_scene_release(scene);
    return 0;
}
