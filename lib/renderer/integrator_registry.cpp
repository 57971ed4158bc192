// SPDX-License-Identifier: Apache-2.0
// The integrator of every mode. The mode's name, number (what checkpoints record) and traits
// are its row in settings/render_modes.cpp.
#include "renderer/integrator_registry.h"

#include "core/error.h"
#include "integrator/ppm_integrator.h"
#include "integrator/pppm_integrator.h"
#include "integrator/sppm_integrator.h"
#include "integrator/vcm/vcm_integrator.h"

namespace ppm {

namespace {

struct Registration {
    RenderMode mode;
    std::unique_ptr<Integrator> (*make)();
};

template <class T> std::unique_ptr<Integrator> make() { return std::make_unique<T>(); }
template <VcmIntegrator::Techniques T> std::unique_ptr<Integrator> make_vcm() {
    return std::make_unique<VcmIntegrator>(T);
}

constexpr Registration kIntegrators[] = {
    {RenderMode::Sppm, make<SppmIntegrator>},
    {RenderMode::Ppm, make<PpmIntegrator>},
    {RenderMode::Pppm, make<PppmIntegrator>},
    {RenderMode::Vcm, make_vcm<VcmIntegrator::Techniques::All>},
    {RenderMode::Bpt, make_vcm<VcmIntegrator::Techniques::ConnectOnly>},
    {RenderMode::Vm, make_vcm<VcmIntegrator::Techniques::MergeOnly>},
};

} // namespace

std::unique_ptr<Integrator> make_integrator(RenderMode mode) {
    for (const Registration &r : kIntegrators)
        if (r.mode == mode) return r.make();
    fail(PPM_ERROR_INVALID_ARGUMENT, "no integrator for mode " + std::to_string(static_cast<int>(mode)));
}

} // namespace ppm
