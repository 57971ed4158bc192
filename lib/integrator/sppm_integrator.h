// SPDX-License-Identifier: Apache-2.0
// SPPM (Hachisuka and Jensen 2009): every pass traces a new jittered camera path per pixel,
// through mirrors and glass (one branch, chosen by Fresnel), to its first non-specular vertex;
// one slot per pixel, whose statistics (N, R, tau) carry over from pass to pass.
#pragma once

#include "integrator/photon_integrator.h"
#include "photon/random.h"

namespace ppm {

class SppmIntegrator : public PhotonIntegrator {
protected:
    std::optional<HitPointBounds> eye_pass(const PassInputs &in, std::uint32_t pass, Film &film,
                                           DensityEstimator &estimator) override;
    void make_eye_slots(const PassInputs &in, Film &film, DensityEstimator &estimator) override;
    // The gather radius squared of the slot's visible point this pass: its statistics'.
    virtual double gather_r2(const Film &film, std::uint32_t slot, const VisiblePoint &vp) const {
        return film.radius2(slot, vp.initial_r2);
    }

private:
    struct PathGroup; // a group's rays, hits and visible points (sppm_integrator.cpp)
    // The paths of `count` (at most Scene::max_stream) pixels from `first` on, their camera
    // rays traced together; each path goes on alone from its camera ray's hit to its visible
    // point, then the group's direct light is estimated together.
    void trace_paths(const PassInputs &in, std::uint32_t first, std::uint32_t count, std::uint32_t pass, Film &film,
                     DensityEstimator &estimator, PathGroup &group) const;
    // From the camera ray's hit (sp, if found) through mirrors and glass to the visible point
    // (vp, left invalid if none); returns the emission seen on the way. sp ends as vp's hit.
    static Rgb follow_path(const PassInputs &in, CounterRng &rng, ppm_ray ray, SurfacePoint &sp, bool found,
                           VisiblePoint &vp);
};

} // namespace ppm
