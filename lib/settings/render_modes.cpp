// SPDX-License-Identifier: Apache-2.0
#include "settings/render_modes.h"

#include "core/error.h"

namespace ppm {

const std::vector<ModeTraits> &render_modes() {
    //                                       pass independent, bidirectional,
    //                                       stores visible points, partials
    static const std::vector<ModeTraits> modes = {
        {RenderMode::Sppm, "sppm", false, false, true, false}, {RenderMode::Ppm, "ppm", false, false, true, false},
        {RenderMode::Pppm, "pppm", true, false, true, true},   {RenderMode::Vcm, "vcm", true, true, false, true},
        {RenderMode::Bpt, "bpt", true, true, false, true},     {RenderMode::Vm, "vm", true, true, false, true},
    };
    return modes;
}

const ModeTraits *find_mode(std::uint32_t number) {
    for (const ModeTraits &m : render_modes())
        if (static_cast<std::uint32_t>(m.mode) == number) return &m;
    return nullptr;
}

const ModeTraits *find_mode(const std::string &name) {
    for (const ModeTraits &m : render_modes())
        if (name == m.name) return &m;
    return nullptr;
}

const ModeTraits &mode_traits(RenderMode mode) {
    if (const ModeTraits *m = find_mode(static_cast<std::uint32_t>(mode))) return *m;
    fail(PPM_ERROR_INVALID_ARGUMENT, "no render mode number " + std::to_string(static_cast<std::uint32_t>(mode)));
}

std::string mode_names(bool ModeTraits::*trait) {
    std::string names;
    for (const ModeTraits &m : render_modes())
        if (m.*trait) names += (names.empty() ? "" : ", ") + std::string(m.name);
    return names;
}

} // namespace ppm
