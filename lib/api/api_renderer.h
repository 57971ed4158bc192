// SPDX-License-Identifier: Apache-2.0
// The renderer handle, shared by the renderer's and the scene file's C API.
#pragma once

#include "api/api_support.h"
#include "renderer/renderer.h"

struct ppm_renderer_t : ppm::Renderer {
    ppm_renderer_t(ppm_scene_t &scene, const ppm::CameraSettings &camera_settings)
        : Renderer(scene, scene.shading, camera_settings), camera(camera_settings) {}

    // The camera as given, for ppm_renderer_get_camera_v2; never changes, so it may be read
    // during a pass.
    const ppm::CameraSettings camera;
};

namespace ppm::api {

template <class Body> ppm_status renderer_call(ppm_renderer renderer, Body &&body) noexcept {
    if (!renderer) return guarded(nullptr, [] { ppm::invalid_argument("renderer is NULL"); });
    return guarded(&renderer->context(), [&] { body(*renderer); });
}

} // namespace ppm::api
