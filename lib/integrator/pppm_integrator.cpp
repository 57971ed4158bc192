// SPDX-License-Identifier: Apache-2.0
#include "integrator/pppm_integrator.h"

namespace ppm {

double PppmIntegrator::radius2_scale(std::uint64_t pass, double alpha) {
    double scale = 1;
    for (std::uint64_t k = 1; k <= pass; ++k) scale *= (static_cast<double>(k - 1) + alpha) / static_cast<double>(k);
    return scale;
}

std::optional<HitPointBounds> PppmIntegrator::eye_pass(const PassInputs &in, std::uint32_t pass, Film &film,
                                                       DensityEstimator &estimator) {
    // Consecutive passes extend the last product by one factor instead of starting over.
    if (scale_alpha_ == in.settings.alpha && scale_pass_ + 1 == pass) {
        scale_ *= (static_cast<double>(pass - 1) + in.settings.alpha) / static_cast<double>(pass);
    } else if (!(scale_alpha_ == in.settings.alpha && scale_pass_ == pass)) {
        scale_ = radius2_scale(pass, in.settings.alpha);
    }
    scale_pass_ = pass, scale_alpha_ = in.settings.alpha;
    return SppmIntegrator::eye_pass(in, pass, film, estimator);
}

} // namespace ppm
