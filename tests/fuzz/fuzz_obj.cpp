// SPDX-License-Identifier: Apache-2.0
// Wavefront OBJ meshes through ppm_scene_load_obj: a file either loads, commits and renders
// finitely (or, when it is all degenerate, commit refuses it as documented), or is refused
// with IO or PARSE naming the file.
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const std::string path = fuzz::write_temp_file("input.obj", data, size);
    ppm_scene scene = nullptr;
    if (ppm_scene_create(fuzz::context(), &scene) != PPM_OK) fuzz::die("ppm_scene_create");
    const ppm_status status = ppm_scene_load_obj(scene, path.c_str(), nullptr);
    if (status == PPM_OK) {
        // INVALID_ARGUMENT is documented for a scene whose every geometry is degenerate (a point).
        const ppm_status committed = ppm_scene_commit(scene);
        if (committed == PPM_OK)
            fuzz::check_geometry_scene(scene);
        else if (committed != PPM_ERROR_INVALID_ARGUMENT)
            fuzz::die("ppm_scene_commit of an OBJ file that loaded");
    } else {
        fuzz::expect_located_error(status, {PPM_ERROR_IO, PPM_ERROR_PARSE}, "input.obj", "ppm_scene_load_obj");
    }
    ppm_scene_release(scene);
    return 0;
}
