// SPDX-License-Identifier: Apache-2.0
// Probabilistic PPM (Knaus and Zwicker 2011, "Progressive photon mapping: a probabilistic
// approach"): every pass is SPPM's eye pass with a fresh jittered camera path per pixel, but
// its gather radius follows a global schedule that depends on the pass index only,
//     r_i^2 = r_0^2 prod_{k=1}^{i} (k - 1 + alpha) / k,       i = 0, 1, 2, ...
// (their r_{j+1}^2 / r_j^2 = (j + alpha) / (j + 1) with j = i + 1), where r_0 is the visible
// point's initial radius; the image is the mean of the passes' estimates. No state carries
// over from one pass to the next, so any subset of passes can be rendered by any process and
// the sums merged (Film::commit_independent_pass, PassSums).
#pragma once

#include "integrator/sppm_integrator.h"

namespace ppm {

class PppmIntegrator : public SppmIntegrator {
public:
    // r_i^2 / r_0^2 above. The product is evaluated term by term (each an IEEE operation, so
    // every machine gets the same bits), in O(i).
    static double radius2_scale(std::uint64_t pass, double alpha);

protected:
    std::optional<HitPointBounds> eye_pass(const PassInputs &in, std::uint32_t pass, Film &film,
                                           DensityEstimator &estimator) override;
    double gather_r2(const Film &, std::uint32_t, const VisiblePoint &vp) const override {
        return vp.initial_r2 * scale_;
    }

private:
    double scale_ = 1; // radius2_scale of the running pass
    std::uint64_t scale_pass_ = 0;
    double scale_alpha_ = 0;
};

} // namespace ppm
