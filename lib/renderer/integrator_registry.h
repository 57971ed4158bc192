// SPDX-License-Identifier: Apache-2.0
// The integrator of each mode (integrator_registry.cpp): one line per mode.
#pragma once

#include "integrator/integrator.h"
#include "settings/render_modes.h"

#include <memory>

namespace ppm {

// A new integrator for `mode`. Throws INVALID_ARGUMENT for a mode without one.
std::unique_ptr<Integrator> make_integrator(RenderMode mode);

} // namespace ppm
