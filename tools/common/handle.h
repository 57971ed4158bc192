// SPDX-License-Identifier: Apache-2.0
// One reference to a libppm handle, dropped by its ppm_*_release when the owner goes, on every
// path out of a function (an early return or an exception). Move-only, like std::unique_ptr;
// an empty owner releases nothing (release(NULL) is a no-op anyway).
#pragma once

#include <ppm/ppm.h>

#include <utility>

namespace ppm_tools {

template <typename T, void (*Release)(T)> class Handle {
public:
    Handle() = default;
    // Takes over a reference the caller holds (e.g. one *_create returned).
    explicit Handle(T handle) : handle_(handle) {}
    Handle(Handle &&other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
    Handle &operator=(Handle &&other) noexcept {
        reset(std::exchange(other.handle_, nullptr));
        return *this;
    }
    Handle(const Handle &) = delete;
    Handle &operator=(const Handle &) = delete;
    ~Handle() { Release(handle_); }

    T get() const { return handle_; }
    operator T() const { return handle_; } // passes straight to the C API
    explicit operator bool() const { return handle_ != nullptr; }

    // Releases the reference held, then takes `handle`.
    void reset(T handle = nullptr) { Release(std::exchange(handle_, handle)); }
    // For an out-parameter (ppm_scene_create(context, scene.out())): releases the reference
    // held and gives the slot that the call fills with a new one.
    T *out() {
        reset();
        return &handle_;
    }

private:
    T handle_ = nullptr;
};

using Context = Handle<ppm_context, ppm_context_release>;
using Scene = Handle<ppm_scene, ppm_scene_release>;
using SceneFile = Handle<ppm_scene_file, ppm_scene_file_release>;
using Renderer = Handle<ppm_renderer, ppm_renderer_release>;
using Partial = Handle<ppm_partial, ppm_partial_release>;
using Mesh = Handle<ppm_mesh, ppm_mesh_release>;

} // namespace ppm_tools
