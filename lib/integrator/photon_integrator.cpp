// SPDX-License-Identifier: Apache-2.0
#include "integrator/photon_integrator.h"

#include <chrono>

namespace ppm {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

bool PhotonIntegrator::render_pass(const PassInputs &in, std::uint32_t pass, Film &film, PassTimes &times) {
    const auto eye_start = std::chrono::steady_clock::now();
    const std::optional<HitPointBounds> eye_bounds = eye_pass(in, pass, film, estimator_);
    if (in.cancelled()) return false;
    const auto build_start = std::chrono::steady_clock::now();
    estimator_.build(in.context, in.settings.search, eye_bounds);
    const double build_seconds = seconds_since(build_start);
    const double eye_seconds = seconds_since(eye_start);

    const auto photon_start = std::chrono::steady_clock::now();
    photon_tracer_.trace_pass(in.context, in.scene, in.settings, pass, estimator_, in.cancel);
    if (in.cancelled()) {
        estimator_.discard_photons();
        return false;
    }
    times.photon_seconds = seconds_since(photon_start);
    times.eye_seconds = eye_seconds;
    times.search_build_seconds = build_seconds;
    if (film.pass_independent())
        film.commit_independent_pass(in.context, estimator_, pass, in.settings.photons_per_pass);
    else
        film.commit_pass(in.context, estimator_, in.settings.alpha, in.settings.photons_per_pass);
    return true;
}

} // namespace ppm
