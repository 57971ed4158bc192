// SPDX-License-Identifier: Apache-2.0
// JSON scene files through ppm_scene_file_load. A file either loads (and then its renderer is
// created and renders one finite pass on a film of at most 64 x 64 pixels) or is refused with
// PARSE, IO or INVALID_ARGUMENT naming the file. The scene's folder holds small files that scenes may refer to:
// texture.png, texture.pfm, mesh.obj and patch.bpt.
#include "fuzz_support.h"

#include <cstring>

namespace {

// 2 x 2 RGB, 8 bits per channel.
const uint8_t kTexturePng[] = {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49,
                               0x48, 0x44, 0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x02,
                               0x00, 0x00, 0x00, 0xfd, 0xd4, 0x9a, 0x73, 0x00, 0x00, 0x00, 0x15, 0x49, 0x44,
                               0x41, 0x54, 0x78, 0xda, 0x63, 0x38, 0x21, 0x27, 0x27, 0x77, 0x42, 0x8e, 0x01,
                               0x48, 0x3c, 0x7b, 0xf6, 0x0c, 0x00, 0x1f, 0xda, 0x05, 0xbf, 0x5d, 0x6d, 0xbb,
                               0xb1, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

// 1 x 1 grey float.
const char kTexturePfm[] = "Pf\n1 1\n-1.0\n\x00\x00\x00\x3f";

const char kMeshObj[] = "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                        "vn 0 1 0\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";

const char kPatchBpt[] = "1\n3 3\n"
                         "0 0 0\n1 0 0\n2 0 0\n3 0 0\n"
                         "0 1 0\n1 1 1\n2 1 1\n3 1 0\n"
                         "0 2 0\n1 2 1\n2 2 1\n3 2 0\n"
                         "0 3 0\n1 3 0\n2 3 0\n3 3 0\n";

void write_companion_files() {
    static bool written = false;
    if (written) return;
    written = true;
    fuzz::write_temp_file("texture.png", kTexturePng, sizeof kTexturePng);
    fuzz::write_temp_file("texture.pfm", reinterpret_cast<const uint8_t *>(kTexturePfm), sizeof kTexturePfm - 1);
    fuzz::write_temp_file("mesh.obj", reinterpret_cast<const uint8_t *>(kMeshObj), std::strlen(kMeshObj));
    fuzz::write_temp_file("patch.bpt", reinterpret_cast<const uint8_t *>(kPatchBpt), std::strlen(kPatchBpt));
}

constexpr uint64_t kMaxFilePixels = 64 * 64;

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    write_companion_files();
    const std::string path = fuzz::write_temp_file("scene.json", data, size);
    ppm_scene_file file = nullptr;
    const ppm_status status = ppm_scene_file_load(fuzz::context(), path.c_str(), &file);
    if (status != PPM_OK) {
        // INVALID_ARGUMENT: a value the scene API itself refuses, passed on with the file's location.
        fuzz::expect_located_error(status, {PPM_ERROR_PARSE, PPM_ERROR_IO, PPM_ERROR_INVALID_ARGUMENT}, "scene.json",
                                   "ppm_scene_file_load");
        return 0;
    }
    ppm_camera camera{};
    if (ppm_scene_file_get_camera(file, &camera) != PPM_OK) fuzz::die("ppm_scene_file_get_camera");
    ppm_renderer renderer = nullptr;
    if (static_cast<uint64_t>(camera.width) * camera.height <= kMaxFilePixels) {
        // The file's own renderer: its integrator settings (radius, mode, seed) are exercised.
        if (ppm_scene_file_create_renderer(file, &renderer) != PPM_OK)
            fuzz::die("ppm_scene_file_create_renderer of a file that loaded");
    } else {
        ppm_scene scene = nullptr;
        if (ppm_scene_file_get_scene(file, &scene) != PPM_OK) fuzz::die("ppm_scene_file_get_scene");
        camera.width = camera.height = fuzz::kFilmSize;
        if (ppm_renderer_create(scene, &camera, &renderer) != PPM_OK)
            fuzz::die("ppm_renderer_create with the camera of a file that loaded");
        ppm_scene_release(scene);
    }
    fuzz::limit_renderer(renderer);
    fuzz::render_one_pass(renderer);
    ppm_renderer_release(renderer);
    ppm_scene_file_release(file);
    return 0;
}
