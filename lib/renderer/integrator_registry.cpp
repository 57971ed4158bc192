// SPDX-License-Identifier: Apache-2.0
// The integrator of every mode. The mode's name and number (what checkpoints record) live in
// render_settings.
#include "integrator/integrator.h"

#include "core/error.h"
#include "integrator/ppm_integrator.h"
#include "integrator/pppm_integrator.h"
#include "integrator/sppm_integrator.h"
#include "integrator/vcm/vcm_integrator.h"

namespace ppm {

namespace {

struct Registration {
    RenderSettings::Mode mode;
    std::unique_ptr<Integrator> (*make)();
};

template <class T> std::unique_ptr<Integrator> make() { return std::make_unique<T>(); }
template <VcmIntegrator::Techniques T> std::unique_ptr<Integrator> make_vcm() {
    return std::make_unique<VcmIntegrator>(T);
}

constexpr Registration kIntegrators[] = {
    {RenderSettings::Mode::Sppm, make<SppmIntegrator>},
    {RenderSettings::Mode::Ppm, make<PpmIntegrator>},
    {RenderSettings::Mode::Pppm, make<PppmIntegrator>},
    {RenderSettings::Mode::Vcm, make_vcm<VcmIntegrator::Techniques::All>},
    {RenderSettings::Mode::Bpt, make_vcm<VcmIntegrator::Techniques::ConnectOnly>},
    {RenderSettings::Mode::Vm, make_vcm<VcmIntegrator::Techniques::MergeOnly>},
};

} // namespace

void Integrator::estimate_pass(const PassInputs &, std::uint32_t, PassEstimate &) {
    fail(PPM_ERROR_INVALID_OPERATION, "this mode estimates a pass from camera paths and photons, not by itself");
}

std::unique_ptr<Integrator> make_integrator(RenderSettings::Mode mode) {
    for (const Registration &r : kIntegrators)
        if (r.mode == mode) return r.make();
    fail(PPM_ERROR_INVALID_ARGUMENT, "no integrator for mode " + std::to_string(static_cast<int>(mode)));
}

} // namespace ppm
