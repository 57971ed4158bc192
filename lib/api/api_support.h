// SPDX-License-Identifier: Apache-2.0
// What the files of the C ABI share: the handle types and the wrapper that turns every
// exception into a ppm_status plus the per-thread message.
#pragma once

#include <ppm/ppm.h>

#include "core/context.h"
#include "core/error.h"
#include "math/limits.h"
#include "math/vec3.h"
#include "scene/scene.h"
#include "shading/scene_shading.h"

#include <new>
#include <string>

struct ppm_context_t : ppm::Context {};
// The scene handle: the geometry (scene layer) and what the renderer adds to it.
struct ppm_scene_t : ppm::Scene {
    using Scene::Scene;
    ppm::SceneShading shading;
};

namespace ppm::api {

// The message of the calling thread's last failed call (ppm_last_error_message).
std::string &last_error();

// Runs `body`, mapping exceptions to a status; reports failures to the context's callback.
// How deep the calling thread is in guarded calls: a call made by another call of the API (a
// table row building through a typed function) leaves the report to the outermost one.
inline int &guarded_depth() {
    thread_local int depth = 0;
    return depth;
}

template <class Body> ppm_status guarded(const ppm::Context *context, Body &&body) noexcept {
    ppm_status status = PPM_OK;
    struct Depth {
        Depth() { ++guarded_depth(); }
        ~Depth() { --guarded_depth(); }
    } depth;
    try {
        body();
        last_error().clear();
        return PPM_OK;
    } catch (const ppm::Error &e) {
        status = e.status();
        last_error() = e.what();
    } catch (const std::bad_alloc &) {
        status = PPM_ERROR_OUT_OF_MEMORY;
        last_error() = "out of memory";
    } catch (const std::exception &e) {
        status = PPM_ERROR_INTERNAL;
        last_error() = std::string("internal error: ") + e.what();
    } catch (...) {
        status = PPM_ERROR_INTERNAL;
        last_error() = "internal error: unknown exception";
    }
    if (context && guarded_depth() == 1) context->report_error(status, last_error().c_str());
    return status;
}

template <class T> void require(const T *pointer, const char *name) {
    if (!pointer) ppm::invalid_argument(std::string(name) + " is NULL");
}

inline void require_key(const char *key) { require(key, "key"); }

// A point or vector of the scene: finite and within the coordinate limit (math/limits.h).
inline ppm::Vec3 finite_point(const double *p, const char *name) {
    require(p, name);
    const ppm::Vec3 v = ppm::Vec3::from(p);
    if (!ppm::is_finite(v)) ppm::invalid_argument(std::string(name) + " has a NaN or infinite coordinate");
    if (!ppm::within_coordinate_limit(v))
        ppm::invalid_argument(std::string(name) + " has a coordinate beyond +-" +
                              ppm::format_number(ppm::kCoordinateLimit) + " (the limit of scene coordinates)");
    return v;
}

template <class Body> ppm_status scene_call(ppm_scene scene, Body &&body) noexcept {
    if (!scene) return guarded(nullptr, [] { ppm::invalid_argument("scene is NULL"); });
    return guarded(&scene->context(), [&] { body(*scene); });
}

inline void write_id(uint32_t *out, uint32_t id) {
    if (out) *out = id;
}

} // namespace ppm::api
