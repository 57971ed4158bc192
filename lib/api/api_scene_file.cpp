// SPDX-License-Identifier: Apache-2.0
// The C ABI of scene files.
#include <ppm/ppm.h>

#include "api/api_camera.h"
#include "api/api_keys.h"
#include "api/api_renderer.h"
#include "scenefile/load_error.h"
#include "scenefile/scene_file.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>

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

// The size of the first ppm_scene_file_options (it ends with `reserved`), and one no version
// will reach: larger is taken for an uninitialised struct.
constexpr size_t kFirstOptionsSize =
    offsetof(ppm_scene_file_options, reserved) + sizeof(ppm_scene_file_options{}.reserved);
constexpr size_t kMaxOptionsSize = 4096;

// The options of the caller's struct, which holds `options->size` bytes.
ppm::SceneFileSource source_with_options(const ppm_scene_file_options *options) {
    ppm::SceneFileSource source;
    if (!options) return source;
    const size_t size = options->size;
    if (size < kFirstOptionsSize || size > kMaxOptionsSize)
        ppm::invalid_argument("options->size is " + std::to_string(size) +
                              ", expected sizeof(ppm_scene_file_options) (" +
                              std::to_string(sizeof(ppm_scene_file_options)) +
                              " in this libppm): initialise the struct with ppm_scene_file_options_init");
    const auto *bytes = reinterpret_cast<const unsigned char *>(options);
    for (size_t i = sizeof(ppm_scene_file_options); i < size; ++i)
        if (bytes[i] != 0)
            ppm::fail(PPM_ERROR_UNSUPPORTED, "options byte " + std::to_string(i) + " of " + std::to_string(size) +
                                                 " is set, but this libppm knows only the first " +
                                                 std::to_string(sizeof(ppm_scene_file_options)) + " bytes");
    ppm_scene_file_options known;
    std::memset(&known, 0, sizeof known);
    std::memcpy(&known, options, std::min(size, sizeof known));
    for (const uint64_t word : known.reserved)
        if (word != 0) ppm::invalid_argument("options->reserved must be 0");

    if (known.format) {
        const std::string format = known.format;
        if (format == "json")
            source.format = ppm::SceneFileSource::Format::Json;
        else if (format == "xml")
            source.format = ppm::SceneFileSource::Format::Xml;
        else
            ppm::invalid_argument("options->format is '" + format + "', expected \"json\", \"xml\" or NULL");
    }
    if (known.define_count > 0) {
        require(known.define_names, "options->define_names");
        require(known.define_values, "options->define_values");
    }
    for (size_t i = 0; i < known.define_count; ++i) {
        const std::string index = "[" + std::to_string(i) + "]";
        require(known.define_names[i], ("options->define_names" + index).c_str());
        require(known.define_values[i], ("options->define_values" + index).c_str());
        if (!*known.define_names[i]) ppm::invalid_argument("options->define_names" + index + " is empty");
        source.defines[known.define_names[i]] = known.define_values[i];
    }
    source.lenient = known.lenient != 0;
    return source;
}

// The warnings of a file that fails to load are given too: they often explain the error.
ppm_scene_file load(ppm_context context, const ppm::SceneFileSource &source) {
    ppm_scene_file_t *file = nullptr;
    try {
        file = new ppm_scene_file_t(context, source);
    } catch (const ppm::LoadError &e) {
        for (const std::string &warning : e.warnings()) context->warn(warning);
        throw;
    }
    for (const std::string &warning : file->warnings()) context->warn(warning);
    return file;
}

} // namespace

extern "C" {

ppm_status ppm_scene_file_load(ppm_context context, const char *path, ppm_scene_file *out_file) {
    return ppm_scene_file_load_v2(context, path, nullptr, out_file);
}

ppm_status ppm_scene_file_load_v2(ppm_context context, const char *path, const ppm_scene_file_options *options,
                                  ppm_scene_file *out_file) {
    return guarded(context, [&] {
        require(context, "context");
        require(path, "path");
        require(out_file, "out_file");
        ppm::SceneFileSource source = source_with_options(options);
        source.path = path;
        *out_file = load(context, source);
    });
}

ppm_status ppm_scene_file_load_memory(ppm_context context, const char *text, size_t size, const char *name,
                                      const char *folder, const ppm_scene_file_options *options,
                                      ppm_scene_file *out_file) {
    return guarded(context, [&] {
        require(context, "context");
        if (size > 0) require(text, "text");
        require(out_file, "out_file");
        ppm::SceneFileSource source = source_with_options(options);
        source.folder = folder && *folder ? std::string(folder) : std::string();
        if (!source.folder.empty() && source.folder.back() != '/') source.folder += '/';
        const std::string path = name ? name : "<scene text>";
        const std::string content(text ? text : "", size);
        source.path = path;
        source.text = &content;
        *out_file = load(context, source);
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

// The first camera struct has no principal point offset: a file's camera with one is refused
// there rather than returned centred.
ppm_status ppm_scene_file_get_camera(ppm_scene_file file, ppm_camera *out_camera) {
    return file_call(file, [&](ppm::SceneFile &f) {
        require(out_camera, "out_camera");
        const ppm_camera_v2 &c = f.camera();
        if (c.principal_point_offset_x != 0 || c.principal_point_offset_y != 0)
            ppm::fail(PPM_ERROR_UNSUPPORTED, "the scene's camera has a principal point offset, which ppm_camera "
                                             "cannot hold: use ppm_scene_file_get_camera_v2");
        ppm_camera camera{};
        for (int i = 0; i < 3; ++i) {
            camera.origin[i] = c.origin[i];
            camera.target[i] = c.target[i];
            camera.up[i] = c.up[i];
        }
        camera.fov = c.fov;
        camera.width = c.width;
        camera.height = c.height;
        camera.aperture_radius = c.aperture_radius;
        camera.focus_distance = c.focus_distance;
        camera.near_clip = c.near_clip;
        *out_camera = camera;
    });
}

ppm_status ppm_scene_file_get_camera_v2(ppm_scene_file file, ppm_camera_v2 *out_camera) {
    return file_call(file, [&](ppm::SceneFile &f) { write_camera(camera_settings(&f.camera()), out_camera); });
}

ppm_status ppm_scene_file_create_renderer(ppm_scene_file file, ppm_renderer *out_renderer) {
    return file_call(file, [&](ppm::SceneFile &f) {
        require(out_renderer, "out_renderer");
        ppm_renderer renderer = nullptr;
        if (const ppm_status status = ppm_renderer_create_v2(f.scene(), &f.camera(), &renderer); status != PPM_OK)
            ppm::fail(status, ppm_last_error_message());
        renderer->settings() = f.settings();
        *out_renderer = renderer;
    });
}

ppm_status ppm_scene_file_create_renderer_v2(ppm_scene_file file, const ppm_camera_v2 *camera,
                                             ppm_renderer *out_renderer) {
    if (!camera) return ppm_scene_file_create_renderer(file, out_renderer);
    return file_call(file, [&](ppm::SceneFile &f) {
        require(out_renderer, "out_renderer");
        ppm_renderer renderer = nullptr;
        if (const ppm_status status = ppm_renderer_create_v2(f.scene(), camera, &renderer); status != PPM_OK)
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
