// SPDX-License-Identifier: Apache-2.0
// Mitsuba serialized meshes through ppm_scene_load_serialized, as mesh 0 and as mesh 1 (found
// through the index at the file's end): each load either succeeds, commits and renders
// finitely, or is refused with IO or PARSE naming the file.
#include "fuzz_support.h"

namespace {

void ignore_warning(void *, const char *) {}

void load(const std::string &path, uint32_t shape_index) {
    ppm_scene scene = nullptr;
    if (ppm_scene_create(fuzz::context(), &scene) != PPM_OK) fuzz::die("ppm_scene_create");
    const ppm_status status = ppm_scene_load_serialized(scene, path.c_str(), shape_index, nullptr);
    if (status == PPM_OK) {
        const ppm_status committed = ppm_scene_commit(scene);
        if (committed == PPM_OK)
            fuzz::check_geometry_scene(scene);
        else if (committed != PPM_ERROR_INVALID_ARGUMENT)
            fuzz::die("ppm_scene_commit of a serialized mesh that loaded");
    } else {
        fuzz::expect_located_error(status, {PPM_ERROR_IO, PPM_ERROR_PARSE}, "input.serialized",
                                   "ppm_scene_load_serialized");
    }
    ppm_scene_release(scene);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const std::string path = fuzz::write_temp_file("input.serialized", data, size);
    ppm_context_set_warning_callback(fuzz::context(), ignore_warning, nullptr);
    load(path, 0);
    load(path, 1);
    return 0;
}
