// SPDX-License-Identifier: Apache-2.0
// Pass orchestration: the mode's integrator renders a pass into the film; the renderer keeps
// one pass at a time, cancellation and the timings.
#include "renderer/renderer.h"

#include "core/error.h"
#include "renderer/integrator_registry.h"
#include "scene/scene.h"

#include <cmath>

namespace ppm {

Renderer::Renderer(Scene &scene, const SceneShading &shading, const CameraSettings &camera)
    : scene_(&scene), geometry_count_(scene.geometry_count()), render_scene_(scene, shading), camera_settings_(camera),
      camera_(camera), material_count_(shading.materials().size()), point_light_count_(shading.lights().size()),
      film_(camera_.width(), camera_.height()) {
    const std::uint64_t pixels = static_cast<std::uint64_t>(camera_.width()) * camera_.height();
    if (pixels > (std::uint64_t(1) << 28))
        invalid_argument("image of " + std::to_string(camera_.width()) + " x " + std::to_string(camera_.height()) +
                         " pixels exceeds the limit of 2^28 pixels");
    scene_->retain();
}

Renderer::~Renderer() { scene_->release(); }

PassInputs Renderer::pass_inputs() const {
    pass_settings_ = settings_;
    pass_settings_.photons_per_pass = paths_per_pass();
    return PassInputs{scene_->context(), render_scene_, camera_, pass_settings_, cancel_requested_, flux_scale()};
}

Integrator &Renderer::integrator() {
    if (!integrator_ || integrator_mode_ != settings_.mode) {
        integrator_ = make_integrator(settings_.mode);
        integrator_mode_ = settings_.mode;
    }
    return *integrator_;
}

double Renderer::flux_scale() const {
    // Without any light (or only black ones) no photon is traced and the image is black; the
    // accumulator still needs a valid scale.
    const double power = render_scene_.total_power().max();
    return power > 0 ? power : 1.0;
}

void Renderer::render_pass() {
    std::unique_lock<std::mutex> one_pass(pass_mutex_, std::try_to_lock);
    if (!one_pass.owns_lock()) fail(PPM_ERROR_INVALID_OPERATION, "another pass of this renderer is running");
    run_pass(mode_traits(settings_.mode).pass_independent ? film_.lowest_missing_pass() : film_.passes());
}

void Renderer::render_pass_index(std::uint64_t index) {
    std::unique_lock<std::mutex> one_pass(pass_mutex_, std::try_to_lock);
    if (!one_pass.owns_lock()) fail(PPM_ERROR_INVALID_OPERATION, "another pass of this renderer is running");
    require_mode(&ModeTraits::pass_independent, "rendering a pass by its index");
    if (index >= kPassIndexLimit) invalid_argument("pass index " + std::to_string(index) + " is not below 2^32");
    if (film_.holds_pass(index))
        fail(PPM_ERROR_INVALID_OPERATION, "pass " + std::to_string(index) + " is rendered already");
    run_pass(index);
}

void Renderer::require_mode(bool ModeTraits::*trait, const char *what) const {
    if (!(mode_traits(settings_.mode).*trait))
        fail(PPM_ERROR_INVALID_OPERATION, std::string(what) + " needs a pass-independent mode (" + mode_names(trait) +
                                              "), not \"" + settings_.get_string("mode") + "\"");
}

void Renderer::run_pass(std::uint64_t index) {
    if (!scene_->committed())
        fail(PPM_ERROR_INVALID_OPERATION, "the scene was changed after the renderer was created and is not committed");
    // The renderer's materials, emission and lights are one per geometry of the scene it was
    // made from: a geometry added since has none of them.
    if (scene_->geometry_count() != geometry_count_)
        fail(PPM_ERROR_INVALID_OPERATION, "the scene has " + std::to_string(scene_->geometry_count()) +
                                              " geometries, not the " + std::to_string(geometry_count_) +
                                              " it had when the renderer was created: create a new renderer");
    const auto check_cancel = [this] {
        if (cancel_requested_.exchange(false)) fail(PPM_ERROR_CANCELLED, "render pass cancelled");
    };
    check_cancel();
    if (index >= kPassIndexLimit) fail(PPM_ERROR_INVALID_OPERATION, "the render has 2^32 passes, its limit");
    const std::uint32_t pass = static_cast<std::uint32_t>(index);
    Integrator &mode = integrator();
    if (!started()) film_.set_pass_independent(mode_traits(settings_.mode).pass_independent);
    const PassInputs in = pass_inputs();
    const bool first = !started();
    PassTimes times;
    if (!mode.render_pass(in, pass, film_, times)) {
        // A cancelled first pass leaves no slots: they may be incomplete, and the next pass
        // makes them again.
        if (first) film_.clear_slots();
        cancel_requested_.store(false);
        fail(PPM_ERROR_CANCELLED, "render pass cancelled");
    }
    last_eye_seconds_ = times.eye_seconds;
    last_search_build_seconds_ = times.search_build_seconds;
    last_photon_seconds_ = times.photon_seconds;
}

} // namespace ppm
