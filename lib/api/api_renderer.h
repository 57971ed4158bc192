// The renderer handle, shared by the renderer's and the scene file's C API.
#pragma once

#include "api/api_support.h"
#include "render/renderer.h"

struct ppm_renderer_t : ppm::Renderer {
    using Renderer::Renderer;
};

namespace ppm::api {

template <class Body> ppm_status renderer_call(ppm_renderer renderer, Body &&body) noexcept {
    if (!renderer) return guarded(nullptr, [] { ppm::invalid_argument("renderer is NULL"); });
    return guarded(&renderer->context(), [&] { body(*renderer); });
}

} // namespace ppm::api
