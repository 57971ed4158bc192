// The C ABI of scene files.
#include <ppm/ppm.h>

#include "api/api_camera.h"
#include "api/api_keys.h"
#include "api/api_renderer.h"
#include "scenefile/scene_file.h"

#include <cstring>

struct ppm_scene_file_t : ppm::SceneFile {
    using SceneFile::SceneFile;
};

namespace {

using namespace ppm::api;

constexpr Key kFileKeyList[] = {{"passes", KeyType::Int}, {"time", KeyType::Double}};
constexpr KeyTable kFileKeys("scene file value", kFileKeyList);

template <class Body> ppm_status file_call(ppm_scene_file file, Body &&body) noexcept {
    if (!file) return guarded(nullptr, [] { ppm::invalid_argument("scene file is NULL"); });
    return guarded(&file->scene()->context(), [&] { body(*file); });
}

} // namespace

extern "C" {

ppm_status ppm_scene_file_load(ppm_context context, const char *path, ppm_scene_file *out_file) {
    return guarded(context, [&] {
        require(context, "context");
        require(path, "path");
        require(out_file, "out_file");
        *out_file = new ppm_scene_file_t(context, path);
    });
}

ppm_status ppm_scene_file_retain(ppm_scene_file file) {
    return file_call(file, [](ppm::SceneFile &f) { f.retain(); });
}

void ppm_scene_file_release(ppm_scene_file file) {
    if (file) file->release();
}

ppm_status ppm_scene_file_get_scene(ppm_scene_file file, ppm_scene *out_scene) {
    return file_call(file, [&](ppm::SceneFile &f) {
        require(out_scene, "out_scene");
        f.scene()->retain();
        *out_scene = f.scene();
    });
}

ppm_status ppm_scene_file_get_camera(ppm_scene_file file, ppm_camera *out_camera) {
    return file_call(file, [&](ppm::SceneFile &f) {
        require(out_camera, "out_camera");
        *out_camera = f.camera();
    });
}

ppm_status ppm_scene_file_get_camera_v2(ppm_scene_file file, ppm_camera_v2 *out_camera) {
    return file_call(file, [&](ppm::SceneFile &f) { write_camera(camera_settings(&f.camera()), out_camera); });
}

ppm_status ppm_scene_file_create_renderer(ppm_scene_file file, ppm_renderer *out_renderer) {
    return file_call(file, [&](ppm::SceneFile &f) {
        require(out_renderer, "out_renderer");
        ppm_renderer renderer = nullptr;
        if (const ppm_status status = ppm_renderer_create(f.scene(), &f.camera(), &renderer); status != PPM_OK)
            ppm::fail(status, ppm_last_error_message());
        renderer->settings() = f.settings();
        *out_renderer = renderer;
    });
}

ppm_status ppm_scene_file_get_int(ppm_scene_file file, const char *key, int64_t *out_value) {
    return file_call(file, [&](ppm::SceneFile &f) {
        kFileKeys.require_int(key); // "passes" is the only integer key
        require(out_value, "out_value");
        *out_value = f.passes();
    });
}

ppm_status ppm_scene_file_get_double(ppm_scene_file file, const char *key, double *out_value) {
    return file_call(file, [&](ppm::SceneFile &f) {
        kFileKeys.find(key);
        require(out_value, "out_value");
        *out_value = std::strcmp(key, "time") == 0 ? f.time_budget() : static_cast<double>(f.passes());
    });
}

} // extern "C"
