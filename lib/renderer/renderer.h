// SPDX-License-Identifier: Apache-2.0
// The renderer: the scene, camera and settings of one render, and its film. One
// render_pass() is one pass of the mode's integrator (integrator/integrator.h): in the photon
// modes an eye pass, a photon pass and the statistics update (photon_integrator.h); in the
// bidirectional ones light and camera subpaths joined under multiple importance sampling
// (vcm/vcm_integrator.h). What the renderer needs to know of a mode is its row of traits
// (settings/render_modes.h).
//
// The parts, each with its own state:
//  - the integrator of the mode (made by renderer/integrator_registry.cpp);
//  - the film (film/film.h) keeps the progressive statistics or the pass sums and gives the
//    image layers;
//  - checkpoints (checkpoint.cpp) save and restore the film with the render's identity;
//  - partial renders (film/partial.h, renderer_partial.cpp): the pass sums of a
//    pass-independent render, saved and merged exactly; its checkpoints are partials too.
//
// Determinism: each camera path and each photon draws counter-based random numbers from
// (seed, pass, index) and photon flux is summed in fixed point, so an image depends on the
// seed and settings only, not on the thread count or scheduling.
//
// Threads: render_pass() runs on the context's worker threads. image() and the other
// readers may be called from any thread at any time, also during a pass: they see the state
// after the last completed pass. cancel() may be called from any thread.
#pragma once

#include "camera/camera.h"
#include "core/ref_counted.h"
#include "film/film.h"
#include "film/partial.h"
#include "integrator/integrator.h"
#include "scene/scene.h"
#include "settings/render_settings.h"
#include "shading/render_scene.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace ppm {

class Renderer : public RefCounted {
public:
    // Keeps the scene alive; copies what it needs of `shading` (the scene's materials and
    // lights). Throws ppm::Error for an uncommitted scene, bad camera settings or materials
    // (see RenderScene, Camera).
    Renderer(Scene &scene, const SceneShading &shading, const CameraSettings &camera);
    ~Renderer() override;

    Context &context() const { return scene_->context(); }
    RenderSettings &settings() { return settings_; }
    // The paths a pass traces: photons_per_pass, or the automatic count for this film.
    std::uint64_t paths_per_pass() const {
        return settings_.paths_per_pass(static_cast<std::uint64_t>(camera_.width()) * camera_.height());
    }
    bool started() const { return film_.passes() > 0; }

    // One pass. Throws ppm::Error: CANCELLED when cancel() was called before or during it
    // (the pass is then discarded: the image stays as it was), INVALID_OPERATION when another
    // pass is running or the scene was changed and not committed again.
    void render_pass();
    // Pass `index` of a pass-independent render (pppm mode), in any order; render_pass() there
    // renders the lowest index not yet rendered. Throws as render_pass(), and INVALID_OPERATION
    // in another mode or for a pass already rendered, INVALID_ARGUMENT for an index >= 2^32.
    void render_pass_index(std::uint64_t index);
    // Asks the running pass, or the next one if none runs, to stop as soon as it can.
    void cancel() { cancel_requested_.store(true); }

    int width() const { return camera_.width(); }
    int height() const { return camera_.height(); }
    std::uint64_t passes() const { return film_.passes(); }
    std::uint64_t photons_emitted() const { return film_.photons_emitted(); }
    // Point, spot and area lights: the sources photons leave (none: the image is black).
    std::size_t light_count() const { return render_scene_.lights().size(); }
    double last_eye_seconds() const { return last_eye_seconds_; }
    // The part of last_eye_seconds() spent building the hit point grid or tree.
    double last_search_build_seconds() const { return last_search_build_seconds_; }
    double last_photon_seconds() const { return last_photon_seconds_; }

    // The image layers (Film::read_layer).
    static size_t layer_channels(const std::string &name) { return Film::layer_channels(name); }
    void read_layer(const std::string &name, float *out) const { film_.read_layer(name, out); }

    // Checkpoints (checkpoint.cpp; the file layout is described there). save may run during
    // a pass and saves the state after the last completed one, atomically. load only before
    // the first pass; throws ppm::Error: IO, PARSE (not a checkpoint, other version,
    // corrupt), INVALID_ARGUMENT (another scene, camera or fixed settings),
    // INVALID_OPERATION (a pass has run).
    void save_checkpoint(const std::string &path) const;
    void load_checkpoint(const std::string &path);

    // Partial renders (pppm mode; INVALID_OPERATION in another mode). make_partial: the state
    // after the last completed pass (INVALID_OPERATION before any), the caller owns the one
    // reference. merge_partial: adds a partial's passes; INVALID_ARGUMENT for one of another
    // render or with passes this renderer holds (the message names both), INVALID_OPERATION
    // while a pass runs.
    RenderIdentity identity() const;
    Partial *make_partial() const;
    void merge_partial(const Partial &partial);

private:
    void run_pass(std::uint64_t index); // under pass_mutex_
    // Throws INVALID_OPERATION unless the mode has `trait`: "<what> needs a mode that ...".
    void require_mode(bool ModeTraits::*trait, const char *what) const;
    void load_partial_checkpoint(const std::string &path, const std::string &bytes);
    PassInputs pass_inputs() const; // refreshes pass_settings_
    // The integrator of the current mode (made anew while the mode may still change).
    Integrator &integrator();
    double flux_scale() const; // for the FluxAccumulator
    bool cancelled() const { return cancel_requested_.load(std::memory_order_relaxed); }
    // Throws PARSE, naming the slot and field, for statistics no render could have made.
    void check_statistics(const std::string &path, const std::vector<PixelStatistics> &stats, std::uint64_t passes,
                          std::uint64_t emitted) const;
    // What a checkpoint records to recognise its render.
    std::uint64_t camera_hash() const;
    std::uint64_t scene_hash() const;

    Scene *scene_;               // retained
    std::size_t geometry_count_; // of the scene when the renderer was made: what render_scene_ describes
    RenderScene render_scene_;
    CameraSettings camera_settings_;
    Camera camera_;
    std::size_t material_count_, point_light_count_; // of the scene's shading, for scene_hash()
    RenderSettings settings_;
    // What integrators see: settings_ with photons_per_pass resolved, made by pass_inputs()
    // (which the pass mutex or the checkpoint load's serialises).
    mutable RenderSettings pass_settings_;

    std::unique_ptr<Integrator> integrator_;
    RenderMode integrator_mode_ = RenderMode::Sppm;
    Film film_;

    // Atomic: a progress display may read them during a pass.
    std::atomic<double> last_eye_seconds_{0}, last_photon_seconds_{0}, last_search_build_seconds_{0};
    std::atomic<bool> cancel_requested_{false};
    std::mutex pass_mutex_; // one pass at a time
};

} // namespace ppm
