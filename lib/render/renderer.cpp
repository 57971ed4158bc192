// Pass orchestration, the end-of-pass statistics update and the image layers. The camera
// paths are in eye_pass.cpp, the photon paths in photon_tracer.cpp, the density estimate in
// density_estimator.cpp.
#include "render/renderer.h"

#include "core/error.h"
#include "scene/scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
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
      material_count_(shading.materials().size()), point_light_count_(shading.lights().size()) {
    const std::uint64_t pixels = static_cast<std::uint64_t>(camera_.width()) * camera_.height();
    if (pixels > (std::uint64_t(1) << 28))
        invalid_argument("image of " + std::to_string(camera_.width()) + " x " + std::to_string(camera_.height()) +
                         " pixels exceeds the limit of 2^28 pixels");
    scene_->retain();
}

Renderer::~Renderer() { scene_->release(); }

void Renderer::render_pass() {
    std::unique_lock<std::mutex> one_pass(pass_mutex_, std::try_to_lock);
    if (!one_pass.owns_lock()) fail(PPM_ERROR_INVALID_OPERATION, "another pass of this renderer is running");
    if (!scene_->committed())
        fail(PPM_ERROR_INVALID_OPERATION, "the scene was changed after the renderer was created and is not committed");
    const auto check_cancel = [this] {
        if (cancel_requested_.exchange(false)) fail(PPM_ERROR_CANCELLED, "render pass cancelled");
    };
    check_cancel();
    const std::uint32_t pass = static_cast<std::uint32_t>(passes_.load());
    const bool ppm_mode = settings_.mode == RenderSettings::Mode::Ppm;

    const auto eye_start = std::chrono::steady_clock::now();
    std::optional<HitPointBounds> eye_bounds;
    if (!ppm_mode || slot_pixel_.empty()) eye_bounds = eye_pass(pass);
    if (ppm_mode) direct_pass(pass);
    if (cancelled()) {
        if (ppm_mode && pass == 0) slot_pixel_.clear(); // the fixed points are redone next time
        check_cancel();
    }
    const auto build_start = std::chrono::steady_clock::now();
    build_search(eye_bounds);
    const double build_seconds = seconds_since(build_start);
    const double eye_seconds = seconds_since(eye_start);

    const auto photon_start = std::chrono::steady_clock::now();
    photon_tracer_.trace_pass(scene_->context(), render_scene_, settings_, pass, estimator_, cancel_requested_);
    if (cancelled()) {
        estimator_.discard_photons();
        if (ppm_mode && pass == 0) slot_pixel_.clear();
        check_cancel();
    }
    last_photon_seconds_ = seconds_since(photon_start);
    last_eye_seconds_ = eye_seconds;
    last_search_build_seconds_ = build_seconds;
    commit_pass();
}

void Renderer::store_hit_point(std::uint32_t slot, const VisiblePoint &vp) {
    estimator_.store(slot, vp, stats_[slot].r2 > 0 ? stats_[slot].r2 : vp.initial_r2);
}

// The search over this pass's hit points, one per slot (absent ones are skipped). SPPM's camera
// paths stored theirs; PPM's fixed visible points are stored here, with this pass's radii.
void Renderer::build_search(const std::optional<HitPointBounds> &eye_bounds) {
    if (settings_.mode == RenderSettings::Mode::Ppm) {
        using Range = tbb::blocked_range<std::size_t>;
        scene_->context().run([&] {
            tbb::parallel_for(Range(0, visible_.size(), 4096), [&](const Range &range) {
                for (std::size_t slot = range.begin(); slot < range.end(); ++slot)
                    store_hit_point(static_cast<std::uint32_t>(slot), visible_[slot]);
            });
        });
    }
    estimator_.build(scene_->context(), settings_.search, eye_bounds);
}

void Renderer::commit_pass() {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    const double alpha = settings_.alpha;
    scene_->context().run([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slot_pixel_.size(), 4096), [&](const auto &range) {
            for (std::size_t slot = range.begin(); slot < range.end(); ++slot) {
                PixelStatistics &s = stats_[slot];
                const std::uint32_t index = static_cast<std::uint32_t>(slot);
                const PassPhotons photons = estimator_.take(index);
                // The first pass's radius: the hit point's (the initial radius while s.r2 == 0).
                const HitPoint &hit_point = estimator_.hit_point(index);
                if (hit_point.present() && s.r2 == 0) s.r2 = hit_point.r2;
                progressive_update(s, photons, alpha);
                s.direct += pass_direct_[slot];
            }
        });
    });
    photons_emitted_ += settings_.photons_per_pass;
    passes_ += 1;
}

size_t Renderer::layer_channels(const std::string &name) {
    if (name == "radiance") return 3;
    if (name == "radius" || name == "photons") return 1;
    invalid_argument("unknown image layer '" + name + "' (layers: radiance, radius, photons)");
}

void Renderer::read_layer(const std::string &name, float *out) const {
    const size_t channels = layer_channels(name);
    const size_t pixels = static_cast<size_t>(width()) * height();
    std::fill(out, out + pixels * channels, 0.0f);
    std::lock_guard<std::mutex> lock(stats_mutex_);
    const std::uint64_t emitted = photons_emitted_.load(), passes = passes_.load();
    // Until a pass completes, the running pass makes the slots and statistics without this
    // lock (init_pixel_slots, PPM's first eye pass): there is nothing to read yet, and
    // touching them would race. passes_ grows under the lock once they are final.
    if (passes == 0) return;
    for (size_t slot = 0; slot < slot_pixel_.size(); ++slot) {
        const PixelStatistics &s = stats_[slot];
        float *pixel = out + static_cast<size_t>(slot_pixel_[slot]) * channels;
        if (name == "radiance") {
            const Rgb l = radiance_estimate(s, emitted, passes);
            pixel[0] += static_cast<float>(l.r);
            pixel[1] += static_cast<float>(l.g);
            pixel[2] += static_cast<float>(l.b);
        } else if (name == "radius") {
            pixel[0] = std::max(pixel[0], static_cast<float>(std::sqrt(s.r2)));
        } else {
            pixel[0] += static_cast<float>(s.n);
        }
    }
}

} // namespace ppm
