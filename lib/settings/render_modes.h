// SPDX-License-Identifier: Apache-2.0
// The renderer's modes, one row each (render_modes.cpp): the name that settings, scene files
// and the CLI use, the number that checkpoints and partial renders record, and the traits
// that the renderer, the film and the file formats ask about. A new mode is a row here, its
// integrator in its own file, and a line of the integrator registry
// (renderer/integrator_registry.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ppm {

// Numbers are written to files: never renumbered.
enum class RenderMode : std::uint32_t { Sppm = 0, Ppm = 1, Pppm = 2, Vcm = 3, Bpt = 4, Vm = 5 };

struct ModeTraits {
    RenderMode mode;
    const char *name;
    // Each pass stands alone (its radii depend on its index only): the film sums per-pass
    // estimates, passes may be rendered in any order, and every pass must share the settings
    // that pass-independent renders fix (render_settings.h).
    bool pass_independent;
    // Light and camera subpaths (integrator/vcm/vcm_integrator.h): paths_per_pass counts light
    // subpaths, one per pixel by default; the photon modes count photon paths.
    bool bidirectional;
    // Camera paths leave visible points that a photon pass gathers at (the film's slots carry
    // progressive statistics or per-pass photons); the bidirectional modes estimate a pass
    // whole.
    bool stores_visible_points;
    // Partial renders: passes rendered apart (processes, machines) and merged exactly; their
    // checkpoints are partial renders too. Requires pass_independent.
    bool supports_partials;
};

// Every mode, in number order.
const std::vector<ModeTraits> &render_modes();
const ModeTraits &mode_traits(RenderMode mode);
// The row of a number read from a file or of a name, or nullptr.
const ModeTraits *find_mode(std::uint32_t number);
const ModeTraits *find_mode(const std::string &name);
// The names of the modes with a trait, for messages: "pppm, vcm, bpt, vm".
std::string mode_names(bool ModeTraits::*trait);

} // namespace ppm
