// SPDX-License-Identifier: Apache-2.0
#include "settings/render_settings.h"

#include "core/error.h"
#include "core/suggest.h"
#include "math/limits.h"

#include <algorithm>
#include <cmath>

namespace ppm {

namespace {

// The settings, in the order messages list them, with the article and type they take.
struct KnownSetting {
    const char *name;
    const char *type;
};
constexpr KnownSetting kSettings[] = {
    {"mode", "a string"},
    {"photons_per_pass", "an integer"},
    {"alpha", "a number"},
    {"initial_radius", "a number"},
    {"initial_radius_pixels", "a number"},
    {"max_depth", "an integer"},
    {"seed", "an integer"},
    {"hit_point_search", "a string"},
    {"direct_lighting", "an integer"},
    {"glossy_gather_alpha", "a number"},
};

// The type of a known key with its article, or nullptr.
const char *type_of(const std::string &key) {
    for (const KnownSetting &setting : kSettings)
        if (key == setting.name) return setting.type;
    return nullptr;
}

// `key` asked for as `type`: either it does not exist or it has another type.
[[noreturn]] void unknown(const std::string &key, const char *type) {
    if (const char *actual = type_of(key))
        invalid_argument("unknown " + std::string(type) + " render setting '" + key + "': '" + key + "' is " + actual +
                         " setting");
    std::vector<std::string> names;
    std::string list;
    for (const KnownSetting &setting : kSettings) {
        names.emplace_back(setting.name);
        list += (list.empty() ? "" : ", ") + names.back();
    }
    invalid_argument("unknown " + std::string(type) + " render setting '" + key + "'" + did_you_mean(key, names) +
                     " (settings: " + list + ")");
}

void require_not_started(const std::string &key, bool started) {
    if (started) fail(PPM_ERROR_INVALID_OPERATION, "render setting '" + key + "' cannot change after the first pass");
}

// Settings that every pass of a pass-independent render must share.
void require_not_started_in_pppm(const std::string &key, RenderSettings::Mode mode, bool started) {
    if (started && mode_traits(mode).pass_independent)
        fail(PPM_ERROR_INVALID_OPERATION, "render setting '" + key + "' cannot change after the first pass in " +
                                              RenderSettings::mode_name(mode) + " mode");
}

} // namespace

void RenderSettings::set_int(const std::string &key, std::int64_t value, bool started) {
    if (key == "photons_per_pass") {
        require_not_started_in_pppm(key, mode, started);
        if (value < 0 || value > kMaxPhotonsPerPass)
            invalid_argument("photons_per_pass must be in 1 .. 2^31, or 0 for automatic, not " + std::to_string(value));
        photons_per_pass = static_cast<std::uint64_t>(value);
    } else if (key == "max_depth") {
        require_not_started_in_pppm(key, mode, started);
        if (value < 1 || value > kMaxDepthLimit)
            invalid_argument("max_depth must be in 1 .. " + std::to_string(kMaxDepthLimit) + ", not " +
                             std::to_string(value));
        max_depth = static_cast<int>(value);
    } else if (key == "seed") {
        require_not_started(key, started);
        seed = static_cast<std::uint64_t>(value);
    } else if (key == "direct_lighting") {
        require_not_started(key, started);
        if (value != 0 && value != 1) invalid_argument("direct_lighting must be 0 or 1, not " + std::to_string(value));
        direct_lighting = value == 1;
    } else if (key == "alpha" || key == "initial_radius" || key == "initial_radius_pixels" ||
               key == "glossy_gather_alpha") {
        set_double(key, static_cast<double>(value), started);
    } else {
        unknown(key, "integer");
    }
}

void RenderSettings::set_double(const std::string &key, double value, bool started) {
    if (!std::isfinite(value))
        invalid_argument("render setting '" + key + "' must be finite, not " + format_number(value));
    if (key == "alpha") {
        require_not_started_in_pppm(key, mode, started);
        if (!(value > 0 && value <= 1)) invalid_argument("alpha must be in (0, 1], not " + format_number(value));
        alpha = value;
    } else if (key == "initial_radius") {
        require_not_started(key, started);
        if (!(value >= 0 && value <= kCoordinateLimit))
            invalid_argument("initial_radius must lie in [0, " + format_number(kCoordinateLimit) +
                             "] (0 = automatic), not " + format_number(value));
        initial_radius = value;
    } else if (key == "initial_radius_pixels") {
        require_not_started(key, started);
        if (!(value > 0 && value <= 1e6))
            invalid_argument("initial_radius_pixels must be in (0, 1e6], not " + format_number(value));
        initial_radius_pixels = value;
    } else if (key == "glossy_gather_alpha") {
        require_not_started(key, started);
        if (!(value >= 0)) invalid_argument("glossy_gather_alpha must be >= 0, not " + format_number(value));
        glossy_gather_alpha = value;
    } else if (key == "photons_per_pass" || key == "max_depth" || key == "seed" || key == "direct_lighting") {
        if (value != std::floor(value)) invalid_argument("render setting '" + key + "' must be a whole number");
        set_int(key, static_cast<std::int64_t>(value), started);
    } else {
        unknown(key, "number");
    }
}

void RenderSettings::set_string(const std::string &key, const std::string &value, bool started) {
    if (key == "mode") {
        require_not_started(key, started);
        const ModeTraits *found = find_mode(value);
        if (!found) {
            std::vector<std::string> names;
            for (const ModeTraits &m : render_modes()) names.emplace_back(m.name);
            std::string list; // "sppm", "ppm", ... or "vm"
            for (std::size_t i = 0; i < names.size(); ++i)
                list += std::string(i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + "\"" + names[i] + "\"";
            invalid_argument("mode must be " + list + ", not \"" + value + "\"" + did_you_mean(value, names));
        }
        mode = found->mode;
    } else if (key == "hit_point_search") {
        if (value == "grid")
            search = Search::Grid;
        else if (value == "kdtree")
            search = Search::KdTree;
        else
            invalid_argument("hit_point_search must be \"grid\" or \"kdtree\", not \"" + value + "\"");
    } else {
        unknown(key, "string");
    }
}

std::int64_t RenderSettings::get_int(const std::string &key) const {
    if (key == "photons_per_pass") return static_cast<std::int64_t>(photons_per_pass);
    if (key == "max_depth") return max_depth;
    if (key == "seed") return static_cast<std::int64_t>(seed);
    if (key == "direct_lighting") return direct_lighting ? 1 : 0;
    unknown(key, "integer");
}

double RenderSettings::get_double(const std::string &key) const {
    if (key == "alpha") return alpha;
    if (key == "initial_radius") return initial_radius;
    if (key == "initial_radius_pixels") return initial_radius_pixels;
    if (key == "glossy_gather_alpha") return glossy_gather_alpha;
    if (key == "photons_per_pass" || key == "max_depth" || key == "seed" || key == "direct_lighting")
        return static_cast<double>(get_int(key));
    unknown(key, "number");
}

std::string RenderSettings::get_string(const std::string &key) const {
    if (key == "mode") return mode_name(mode);
    if (key == "hit_point_search") return search == Search::Grid ? "grid" : "kdtree";
    unknown(key, "string");
}

std::uint64_t RenderSettings::paths_per_pass(std::uint64_t pixels) const {
    if (photons_per_pass > 0) return photons_per_pass;
    if (mode_traits(mode).bidirectional) return std::min(pixels, kMaxLightSubpathsPerPass);
    return std::clamp(kPhotonsPerPixel * pixels, kMinAutoPhotons, kMaxAutoPhotons);
}

} // namespace ppm
