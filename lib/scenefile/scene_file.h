// SPDX-License-Identifier: Apache-2.0
// A scene file (docs/scene-format.md: libppm's JSON, or Mitsuba 3 XML) read into a committed
// scene, a camera and render settings. The builder goes through the public C API, so a scene file can express exactly
// what a program can, and every check of the API also guards files; its messages get the
// file's location in front.
#pragma once

#include <ppm/ppm.h>

#include "core/ref_counted.h"
#include "settings/render_settings.h"

#include <map>
#include <string>
#include <vector>

namespace ppm {

class JsonDocument;
struct LenientLog;

// Where a scene file's text comes from and how to read it.
struct SceneFileSource {
    enum class Format { Detect, Json, Xml };

    std::string path;                           // the file; for `text`, the name messages give it
    const std::string *text = nullptr;          // the content, when not read from `path`
    std::string folder;                         // for `text`: what its file names are relative to
    Format format = Format::Detect;             // Detect: XML for a ".xml" name or text starting with '<'
    std::map<std::string, std::string> defines; // Mitsuba XML parameters (as its -D name=value)
    bool lenient = false;                       // XML: substitute what libppm cannot render, with a warning
};

class SceneFile : public RefCounted {
public:
    // Throws ppm::Error: IO for a missing file (the scene or one it names), PARSE for
    // anything wrong inside it, with "file:line:column: key.path: what", INVALID_ARGUMENT
    // for parameters given for a JSON file. Once the file is read, the error is a LoadError
    // (scenefile/load_error.h) carrying the warnings met before it.
    SceneFile(ppm_context context, const SceneFileSource &source);
    ~SceneFile() override;

    // What the reader skipped or substituted, "file:line:column: what", one per element.
    const std::vector<std::string> &warnings() const { return warnings_; }

    ppm_scene scene() const { return scene_; }
    const ppm_camera_v2 &camera() const { return camera_; }
    const RenderSettings &settings() const { return settings_; }
    std::int64_t passes() const { return passes_; }
    double time_budget() const { return time_; }

private:
    // The scene, camera and settings from the document; `folder`: what its file names are
    // relative to.
    void build(ppm_context context, const std::string &path, const JsonDocument &document, const std::string &folder,
               LenientLog *lenient);

    ppm_scene scene_ = nullptr; // keeps the context alive
    ppm_camera_v2 camera_{};
    RenderSettings settings_;
    std::int64_t passes_ = 0;
    double time_ = 0;
    std::vector<std::string> warnings_;
};

} // namespace ppm
