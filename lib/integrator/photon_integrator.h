// SPDX-License-Identifier: Apache-2.0
// The photon modes (sppm, ppm, pppm): a pass is an eye pass, in which the mode's camera paths
// set each slot's direct light and store its hit point in the density estimator; the search
// build over the hit points; a photon pass that traces photons from the lights and gathers
// them there (photon_tracer.h); and the film's update with the photons found. Only the eye
// pass differs from mode to mode.
//
// Direct light (light sources seen by a visible point, and emitters seen through specular
// chains) is estimated by ray tracing in the eye pass, so photons are not stored at their
// first hit: there they would count direct light a second time.
#pragma once

#include "integrator/density_estimator.h"
#include "integrator/integrator.h"
#include "integrator/photon_tracer.h"
#include "photon/hit_point.h"

#include <cstdint>
#include <optional>

namespace ppm {

class PhotonIntegrator : public Integrator {
public:
    bool render_pass(const PassInputs &in, std::uint32_t pass, Film &film, PassTimes &times) final;
    void make_slots(const PassInputs &in, Film &film) final { make_eye_slots(in, film, estimator_); }

protected:
    // Pass `pass`'s camera paths: makes the film's slots if it has none (the estimator is then
    // reset to as many slots), sets every slot's direct light and stores its hit point in the
    // estimator. Returns the hit points' bounds if they were measured on the way (the
    // estimator measures them otherwise). Throws ppm::Error (OUT_OF_MEMORY for slots that do
    // not fit). On cancel it may return early with any state, which is then discarded.
    virtual std::optional<HitPointBounds> eye_pass(const PassInputs &in, std::uint32_t pass, Film &film,
                                                   DensityEstimator &estimator) = 0;
    // The film's slots as the first pass makes them, and the estimator reset to as many.
    virtual void make_eye_slots(const PassInputs &in, Film &film, DensityEstimator &estimator) = 0;

private:
    DensityEstimator estimator_;
    PhotonTracer photon_tracer_;
};

} // namespace ppm
