// SPDX-License-Identifier: Apache-2.0
// Pass orchestration: the integrator's eye pass, the search build, the photon pass and the
// film's statistics update, with cancellation and timing.
#include "renderer/renderer.h"

#include "core/error.h"
#include "scene/scene.h"

#include <chrono>
#include <cmath>

namespace ppm {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

Renderer::Renderer(Scene &scene, const SceneShading &shading, const CameraSettings &camera)
    : scene_(&scene), render_scene_(scene, shading), camera_settings_(camera), camera_(camera),
      material_count_(shading.materials().size()), point_light_count_(shading.lights().size()),
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
    run_pass(integrator().pass_independent() ? film_.lowest_missing_pass() : film_.passes());
}

void Renderer::render_pass_index(std::uint64_t index) {
    std::unique_lock<std::mutex> one_pass(pass_mutex_, std::try_to_lock);
    if (!one_pass.owns_lock()) fail(PPM_ERROR_INVALID_OPERATION, "another pass of this renderer is running");
    require_pass_independent("rendering a pass by its index");
    if (index >= kPassIndexLimit) invalid_argument("pass index " + std::to_string(index) + " is not below 2^32");
    if (film_.holds_pass(index))
        fail(PPM_ERROR_INVALID_OPERATION, "pass " + std::to_string(index) + " is rendered already");
    run_pass(index);
}

void Renderer::require_pass_independent(const char *what) const {
    if (!RenderSettings::is_pass_independent(settings_.mode))
        fail(PPM_ERROR_INVALID_OPERATION, std::string(what) +
                                              " needs a pass-independent mode (pppm, vcm, bpt, vm), not \"" +
                                              settings_.get_string("mode") + "\"");
}

void Renderer::run_pass(std::uint64_t index) {
    if (!scene_->committed())
        fail(PPM_ERROR_INVALID_OPERATION, "the scene was changed after the renderer was created and is not committed");
    const auto check_cancel = [this] {
        if (cancel_requested_.exchange(false)) fail(PPM_ERROR_CANCELLED, "render pass cancelled");
    };
    check_cancel();
    if (index >= kPassIndexLimit) fail(PPM_ERROR_INVALID_OPERATION, "the render has 2^32 passes, its limit");
    const std::uint32_t pass = static_cast<std::uint32_t>(index);
    Integrator &mode = integrator();
    if (!started()) film_.set_pass_independent(mode.pass_independent());
    const PassInputs in = pass_inputs();
    // A cancelled first pass leaves no slots: they may be incomplete, and the next pass makes them again.
    const bool first = !started();
    const auto discard = [&] {
        if (first) film_.clear_slots();
        check_cancel();
    };

    if (mode.estimates_whole_pass()) {
        const auto start = std::chrono::steady_clock::now();
        PassEstimate estimate;
        mode.estimate_pass(in, pass, estimate);
        if (cancelled()) discard();
        last_eye_seconds_ = seconds_since(start);
        last_photon_seconds_ = 0;
        last_search_build_seconds_ = 0;
        film_.commit_estimated_pass(index, estimate);
        return;
    }

    const auto eye_start = std::chrono::steady_clock::now();
    const std::optional<HitPointBounds> eye_bounds = mode.eye_pass(in, pass, film_, estimator_);
    if (cancelled()) discard();
    const auto build_start = std::chrono::steady_clock::now();
    estimator_.build(scene_->context(), settings_.search, eye_bounds);
    const double build_seconds = seconds_since(build_start);
    const double eye_seconds = seconds_since(eye_start);

    const auto photon_start = std::chrono::steady_clock::now();
    photon_tracer_.trace_pass(scene_->context(), render_scene_, pass_settings_, pass, estimator_, cancel_requested_);
    if (cancelled()) {
        estimator_.discard_photons();
        discard();
    }
    last_photon_seconds_ = seconds_since(photon_start);
    last_eye_seconds_ = eye_seconds;
    last_search_build_seconds_ = build_seconds;
    if (mode.pass_independent())
        film_.commit_independent_pass(scene_->context(), estimator_, index, pass_settings_.photons_per_pass);
    else
        film_.commit_pass(scene_->context(), estimator_, settings_.alpha, pass_settings_.photons_per_pass);
}

} // namespace ppm
