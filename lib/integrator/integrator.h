// SPDX-License-Identifier: Apache-2.0
// An integrator mode: how a pass's camera paths make the film's slots, their direct light and
// the hit points the photons are gathered at. The renderer runs the rest of a pass the same
// way for every mode (photon tracing, density estimate, statistics update).
//
// A new mode is one file that implements Integrator and one line in integrator_registry.cpp.
#pragma once

#include "camera/camera.h"
#include "core/context.h"
#include "film/film.h"
#include "film/pass_estimate.h"
#include "integrator/density_estimator.h"
#include "photon/hit_point.h"
#include "settings/render_settings.h"
#include "shading/render_scene.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace ppm {

// What a pass's camera paths read; the film and the estimator are what they write.
struct PassInputs {
    Context &context;
    const RenderScene &scene;
    const Camera &camera;
    const RenderSettings &settings;
    const std::atomic<bool> &cancel; // stop as soon as possible; the pass is then discarded
    double flux_scale;               // for the estimator's FluxAccumulator

    bool cancelled() const { return cancel.load(std::memory_order_relaxed); }
};

class Integrator {
public:
    virtual ~Integrator() = default;

    // Pass `pass`: makes the film's slots if it has none (the first pass, or after a first pass
    // that was cancelled or failed; the estimator is then reset to as many slots), sets every
    // slot's direct light and stores its hit point in the estimator. Returns the hit points'
    // bounds if they were measured on the way (the estimator measures them otherwise).
    // Throws ppm::Error (OUT_OF_MEMORY for slots that do not fit). On cancel it may return
    // early with any state that the renderer then discards.
    virtual std::optional<HitPointBounds> eye_pass(const PassInputs &in, std::uint32_t pass, Film &film,
                                                   DensityEstimator &estimator) = 0;

    // Makes the film's slots exactly as the first pass makes them, and nothing else (to check
    // a checkpoint's slots against).
    virtual void make_slots(const PassInputs &in, Film &film, DensityEstimator &estimator) = 0;

    // Whether each pass stands alone (its radii depend on its index only): the film then sums
    // pass estimates (Film::commit_independent_pass) instead of carrying statistics over.
    virtual bool pass_independent() const { return false; }

    // Whether this mode makes a pass's whole estimate itself (the bidirectional modes,
    // vcm_integrator.h), with estimate_pass instead of eye_pass and the renderer's photon pass.
    // Such modes are pass-independent.
    virtual bool estimates_whole_pass() const { return false; }
    // Pass `pass`'s estimate of every pixel. Throws ppm::Error; on cancel it may return early
    // with any estimate, which the renderer then discards.
    virtual void estimate_pass(const PassInputs &in, std::uint32_t pass, PassEstimate &out);
};

// The integrator of a mode (integrator_registry.cpp).
std::unique_ptr<Integrator> make_integrator(RenderSettings::Mode mode);

} // namespace ppm
