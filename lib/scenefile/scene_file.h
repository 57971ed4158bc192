// A scene file (docs/scene-format.md) read into a committed scene, a camera and render
// settings. The builder goes through the public C API, so a scene file can express exactly
// what a program can, and every check of the API also guards files; its messages get the
// file's location in front.
#pragma once

#include <ppm/ppm.h>

#include "core/ref_counted.h"
#include "render/render_settings.h"

#include <string>

namespace ppm {

class SceneFile : public RefCounted {
public:
    // Throws ppm::Error: IO for a missing file (the scene or one it names), PARSE for
    // anything wrong inside it, with "file:line:column: key.path: what".
    SceneFile(ppm_context context, const std::string &path);
    ~SceneFile() override;

    ppm_scene scene() const { return scene_; }
    const ppm_camera &camera() const { return camera_; }
    const RenderSettings &settings() const { return settings_; }
    std::int64_t passes() const { return passes_; }
    double time_budget() const { return time_; }

private:
    ppm_scene scene_ = nullptr; // keeps the context alive
    ppm_camera camera_{};
    RenderSettings settings_;
    std::int64_t passes_ = 0;
    double time_ = 0;
};

} // namespace ppm
