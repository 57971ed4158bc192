// .bpt patch files through ppm_scene_load_bpt: a file either loads, commits and renders
// finitely, or is refused with IO or PARSE naming the file.
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const std::string path = fuzz::write_temp_file("input.bpt", data, size);
    ppm_scene scene = nullptr;
    if (ppm_scene_create(fuzz::context(), &scene) != PPM_OK) fuzz::die("ppm_scene_create");
    const ppm_status status = ppm_scene_load_bpt(scene, path.c_str(), nullptr);
    if (status == PPM_OK) {
        if (ppm_scene_commit(scene) != PPM_OK) fuzz::die("ppm_scene_commit of a .bpt file that loaded");
        fuzz::check_geometry_scene(scene);
    } else {
        fuzz::expect_located_error(status, {PPM_ERROR_IO, PPM_ERROR_PARSE}, "input.bpt", "ppm_scene_load_bpt");
    }
    ppm_scene_release(scene);
    return 0;
}
