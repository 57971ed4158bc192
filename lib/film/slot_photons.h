// SPDX-License-Identifier: Apache-2.0
// What a photon pass leaves at each of the film's slots: the hit point photons were gathered
// at and the photons found there. The film folds them into its statistics at the end of the
// pass (Film::commit_pass); the density estimator of the photon modes is one
// (integrator/density_estimator.h). An interface, so that the film knows no search structure.
#pragma once

#include "photon/hit_point.h"
#include "photon/sppm_statistics.h"

#include <cstdint>

namespace ppm {

class SlotPhotons {
public:
    // The slot's hit point this pass (absent if its camera path stored none).
    virtual const HitPoint &hit_point(std::uint32_t slot) const = 0;
    // The slot's photons this pass, reset to none for the next one. Thread-safe for distinct
    // slots.
    virtual PassPhotons take(std::uint32_t slot) = 0;

protected:
    ~SlotPhotons() = default;
};

} // namespace ppm
