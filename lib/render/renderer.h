// The progressive photon mapper: one render_pass() is an eye pass (visible points and their
// direct light), a photon pass (photons traced from the lights and gathered at the visible
// points within their radii) and the statistics update that shrinks the radii.
//
// Two modes (render_settings.h):
//  - SPPM (default; Hachisuka and Jensen 2009): every pass traces a new jittered camera path
//    per pixel, through mirrors and glass (one branch, chosen by Fresnel), to its first
//    non-specular vertex, and the pixel's statistics (N, R, tau) carry over;
//  - PPM (Hachisuka, Ogaki and Jensen 2008): the first pass traces the camera paths once,
//    splitting at glass and at coats (both branches, weighted), and every resulting hit point
//    keeps its own statistics; later passes only re-sample direct light and trace photons.
// Direct light (light sources seen by a visible point, and emitters seen through specular
// chains) is estimated by ray tracing in the eye pass, so photons are not stored at their
// first hit: there they would count direct light a second time.
//
// Determinism: each camera path and each photon draws counter-based random numbers from
// (seed, pass, index) and photon flux is summed in fixed point, so an image depends on the
// seed and settings only, not on the thread count or scheduling.
//
// Threads: render_pass() runs on the context's worker threads. image() and the other
// readers may be called from any thread at any time, also during a pass: they see the state
// after the last completed pass. cancel() may be called from any thread.
#pragma once

#include "core/ref_counted.h"
#include "photon/hit_point.h"
#include "photon/random.h"
#include "photon/sppm_statistics.h"
#include "render/camera.h"
#include "render/density_estimator.h"
#include "render/photon_tracer.h"
#include "render/render_scene.h"
#include "render/render_settings.h"
#include "render/visible_point.h"
#include "scene/scene.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
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
    bool started() const { return passes_.load() > 0; }

    // One pass. Throws ppm::Error: CANCELLED when cancel() was called before or during it
    // (the pass is then discarded: the image stays as it was), INVALID_OPERATION when another
    // pass is running or the scene was changed and not committed again.
    void render_pass();
    // Asks the running pass, or the next one if none runs, to stop as soon as it can.
    void cancel() { cancel_requested_.store(true); }

    int width() const { return camera_.width(); }
    int height() const { return camera_.height(); }
    std::uint64_t passes() const { return passes_.load(); }
    std::uint64_t photons_emitted() const { return photons_emitted_.load(); }
    // Point, spot and area lights: the sources photons leave (none: the image is black).
    std::size_t light_count() const { return render_scene_.lights().size(); }
    double last_eye_seconds() const { return last_eye_seconds_; }
    // The part of last_eye_seconds() spent building the hit point grid or tree.
    double last_search_build_seconds() const { return last_search_build_seconds_; }
    double last_photon_seconds() const { return last_photon_seconds_; }

    // Per-pixel layers, row-major from the top-left pixel:
    //   "radiance": 3 floats per pixel, linear RGB radiance (the image);
    //   "radius":   1 float, the gather radius (largest over a pixel's slots, 0 before any);
    //   "photons":  1 float, N, the (alpha-reduced) photon count of the pixel's statistics.
    static size_t layer_channels(const std::string &name); // throws for an unknown name
    void read_layer(const std::string &name, float *out) const;

    // Checkpoints (checkpoint.cpp; the file layout is described there). save may run during
    // a pass and saves the state after the last completed one, atomically. load only before
    // the first pass; throws ppm::Error: IO, PARSE (not a checkpoint, other version,
    // corrupt), INVALID_ARGUMENT (another scene, camera or fixed settings),
    // INVALID_OPERATION (a pass has run).
    void save_checkpoint(const std::string &path) const;
    void load_checkpoint(const std::string &path);

private:
    // SPPM returns the bounds of the hit points it stored (measured while they are in the
    // cache); PPM's fixed points are stored and measured by build_search().
    std::optional<HitPointBounds> eye_pass(std::uint32_t pass);
    void init_pixel_slots();              // SPPM: one slot per pixel, statistics zero
    void init_ppm_slots();                // PPM: the first eye pass's split paths, traced in parallel
    std::string film_description() const; // "the film of W x H pixels", for messages
    double flux_scale() const;            // for the FluxAccumulator
    void direct_pass(std::uint32_t pass); // PPM: direct light again at the fixed points
    // The slot's hit point and gather data for this pass (absent unless vp.valid), with the
    // slot's radius (the initial one before its first pass).
    void store_hit_point(std::uint32_t slot, const VisiblePoint &vp);
    void build_search(const std::optional<HitPointBounds> &eye_bounds);
    void commit_pass();
    bool cancelled() const { return cancel_requested_.load(std::memory_order_relaxed); }

    // Camera paths (eye_pass.cpp).
    // SPPM: the paths of `count` (at most Scene::max_stream) pixels from `first` on, their
    // camera rays traced together; each path goes on alone from its camera ray's hit to its
    // visible point, then the group's direct light is estimated together.
    struct PathGroup; // a group's rays, hits and visible points (eye_pass.cpp)
    void trace_sppm_paths(std::uint32_t first, std::uint32_t count, std::uint32_t pass, PathGroup &group);
    // From the camera ray's hit (sp, if found) through mirrors and glass to the visible point
    // (vp, left invalid if none); returns the emission seen on the way. sp ends as vp's hit.
    Rgb follow_sppm_path(CounterRng &rng, ppm_ray ray, SurfacePoint &sp, bool found, VisiblePoint &vp) const;
    template <class Emit> void trace_split_path(const ppm_ray &ray, const ppm_hit *leaving, Rgb weight, int depth,
                                                double length, int &budget, std::uint32_t pixel, Emit &&emit);
    void add_direct_light(const VisiblePoint *vps, const ppm_hit *const *at, CounterRng *rngs, std::uint32_t count,
                          Rgb *direct) const;
    VisiblePoint make_visible_point(const SurfacePoint &sp, const Vec3 &ray_dir, const Rgb &weight,
                                    double path_length) const;
    double footprint_r2(double path_length) const;
    // Throws PARSE, naming the slot and field, for statistics no render could have made.
    void check_statistics(const std::string &path, const std::vector<PixelStatistics> &stats, std::uint64_t passes,
                          std::uint64_t emitted) const;
    // What a checkpoint records to recognise its render.
    std::uint64_t camera_hash() const;
    std::uint64_t scene_hash() const;

    Scene *scene_; // retained
    RenderScene render_scene_;
    CameraSettings camera_settings_;
    Camera camera_;
    std::size_t material_count_, point_light_count_; // of the scene's shading, for scene_hash()
    RenderSettings settings_;

    // Slots: one per pixel in SPPM, one per split camera path in PPM (set by the first pass).
    std::vector<std::uint32_t> slot_pixel_;
    std::vector<PixelStatistics> stats_;
    // This pass: direct light per slot, and the visible points (PPM only: fixed by the first
    // pass; SPPM stores its points straight into the estimator).
    std::vector<VisiblePoint> visible_;
    std::vector<Rgb> pass_direct_;
    std::vector<Rgb> fixed_emitted_; // PPM: emission seen along each split path (constant)
    DensityEstimator estimator_;     // this pass's hit points and the photons they gather
    PhotonTracer photon_tracer_;

    std::atomic<std::uint64_t> passes_{0};
    std::atomic<std::uint64_t> photons_emitted_{0};
    // Atomic like the counters above: a progress display may read them during a pass.
    std::atomic<double> last_eye_seconds_{0}, last_photon_seconds_{0}, last_search_build_seconds_{0};
    std::atomic<bool> cancel_requested_{false};
    std::mutex pass_mutex_;          // one pass at a time
    mutable std::mutex stats_mutex_; // readers against the end-of-pass update
};

} // namespace ppm
