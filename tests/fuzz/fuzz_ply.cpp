// SPDX-License-Identifier: Apache-2.0
// PLY meshes through ppm_scene_load_ply: a file either loads, commits and renders finitely
// (or, when it is all degenerate, commit refuses it as documented), or is refused with IO or
// PARSE naming the file. Warnings (skipped colours and elements) are collected and dropped.
#include "fuzz_support.h"

namespace {

void ignore_warning(void *, const char *) {}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const std::string path = fuzz::write_temp_file("input.ply", data, size);
    ppm_context_set_warning_callback(fuzz::context(), ignore_warning, nullptr);
    ppm_scene scene = nullptr;
    if (ppm_scene_create(fuzz::context(), &scene) != PPM_OK) fuzz::die("ppm_scene_create");
    const ppm_status status = ppm_scene_load_ply(scene, path.c_str(), nullptr);
    if (status == PPM_OK) {
        const ppm_status committed = ppm_scene_commit(scene);
        if (committed == PPM_OK)
            fuzz::check_geometry_scene(scene);
        else if (committed != PPM_ERROR_INVALID_ARGUMENT)
            fuzz::die("ppm_scene_commit of a PLY file that loaded");
    } else {
        fuzz::expect_located_error(status, {PPM_ERROR_IO, PPM_ERROR_PARSE}, "input.ply", "ppm_scene_load_ply");
    }
    ppm_scene_release(scene);
    return 0;
}
