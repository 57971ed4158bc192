// SPDX-License-Identifier: Apache-2.0
// PPM (Hachisuka, Ogaki and Jensen 2008): the first pass traces the camera paths once,
// splitting at glass and at coats (both branches, weighted), and every resulting visible
// point is a slot with its own statistics; later passes only estimate direct light again at
// the fixed points.
#pragma once

#include "integrator/photon_integrator.h"
#include "integrator/visible_point.h"

#include <vector>

namespace ppm {

class PpmIntegrator : public PhotonIntegrator {
protected:
    std::optional<HitPointBounds> eye_pass(const PassInputs &in, std::uint32_t pass, Film &film,
                                           DensityEstimator &estimator) override;
    void make_eye_slots(const PassInputs &in, Film &film, DensityEstimator &estimator) override;

private:
    // Rows are traced in parallel into their own lists, joined in row order so slot numbers do
    // not depend on scheduling.
    void trace_fixed_points(const PassInputs &in, Film &film, DensityEstimator &estimator);
    template <class Emit> static void trace_split_path(const PassInputs &in, const ppm_ray &ray, const ppm_hit *leaving,
                                                       Rgb weight, int depth, double length, int &budget,
                                                       std::uint32_t pixel, Emit &&emit);

    std::vector<VisiblePoint> visible_; // per slot, fixed by the first pass
    std::vector<Rgb> fixed_emitted_;    // per slot: emission seen along its split path (constant)
};

} // namespace ppm
