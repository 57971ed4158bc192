// SPDX-License-Identifier: Apache-2.0
// An integrator: how a mode renders one pass into the film. A new mode is one file that
// implements Integrator, a row of traits in settings/render_modes.cpp and a line in
// renderer/integrator_registry.cpp.
#pragma once

#include "camera/camera.h"
#include "core/context.h"
#include "film/film.h"
#include "settings/render_settings.h"
#include "shading/render_scene.h"

#include <atomic>
#include <cstdint>

namespace ppm {

// What a pass reads; the film (and a photon mode's estimator) is what it writes.
struct PassInputs {
    Context &context;
    const RenderScene &scene;
    const Camera &camera;
    const RenderSettings &settings;
    const std::atomic<bool> &cancel; // stop as soon as possible; the pass is then discarded
    double flux_scale;               // for the estimator's FluxAccumulator

    bool cancelled() const { return cancel.load(std::memory_order_relaxed); }
};

// How long a pass's parts took, for the renderer's readers (last_eye_seconds and the others).
struct PassTimes {
    double eye_seconds = 0;          // camera paths, with the search build (the whole pass in the bidirectional modes)
    double search_build_seconds = 0; // the hit points' grid or tree
    double photon_seconds = 0;       // the photon pass
};

// The one interface of every mode (pbrt-v4's and Mitsuba 3's integrators have one entry too):
// a pass in, a committed pass in the film out. The photon modes implement it through
// PhotonIntegrator (photon_integrator.h), the bidirectional ones through VcmIntegrator
// (vcm/vcm_integrator.h). What the renderer needs to know of a mode beyond this is its row
// of traits (settings/render_modes.h).
class Integrator {
public:
    virtual ~Integrator() = default;

    // Renders pass `pass` and commits it to the film: a pass-independent film (set by the
    // renderer from the mode's traits) adds it to its pass sums, another film folds it into
    // its statistics. Makes the film's slots first if it has none (the first pass, or after a
    // first pass that was cancelled or failed). Returns false, with nothing committed, when it
    // stopped because in.cancelled(); the renderer then discards the pass. Throws ppm::Error
    // (OUT_OF_MEMORY for what does not fit).
    virtual bool render_pass(const PassInputs &in, std::uint32_t pass, Film &film, PassTimes &times) = 0;

    // Makes the film's slots exactly as the first pass makes them, and nothing else (to check
    // a checkpoint's slots against).
    virtual void make_slots(const PassInputs &in, Film &film) = 0;
};

} // namespace ppm
