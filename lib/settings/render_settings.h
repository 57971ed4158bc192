// SPDX-License-Identifier: Apache-2.0
// The renderer's settings: one table of string keys with types, defaults and checks, so the
// C API, ppm-render's --set and the docs agree.
//
// | key                | type   | default | meaning                                            |
// |--------------------|--------|---------|----------------------------------------------------|
// | mode               | string | vcm     | "sppm": new jittered eye pass every pass (Hachisuka |
// |                    |        |         | and Jensen 2009); "ppm": hit points fixed by the    |
// |                    |        |         | first eye pass, split at glass and coats (2008);    |
// |                    |        |         | "pppm": pass-independent radii (Knaus and Zwicker   |
// |                    |        |         | 2011): passes can be rendered apart and merged;     |
// |                    |        |         | "vcm": vertex connection and merging (Georgiev et   |
// |                    |        |         | al. 2012), "bpt" its connections only, "vm" its     |
// |                    |        |         | merging only (vcm_integrator.h); pass-independent.  |
// |                    |        |         | vcm is the default: the least error at equal time   |
// |                    |        |         | (docs/bench/converge.md)                            |
// | photons_per_pass   | int    | 0       | photon paths (photon modes) or light subpaths       |
// |                    |        |         | (bidirectional modes) per pass, 1 .. 2^31; 0 =      |
// |                    |        |         | automatic, from the pixel count: paths_per_pass     |
// | alpha              | double | 2/3     | radius reduction, in (0, 1]                         |
// | initial_radius     | double | 0       | gather radius in scene units; 0 = automatic:        |
// |                    |        |         | initial_radius_pixels pixel footprints at each      |
// |                    |        |         | pixel's first visible point                         |
// | initial_radius_pixels | double | 1    | the automatic radius in pixel footprints, > 0       |
// | max_depth          | int    | 16      | scattering events per camera or photon path, 1..1000|
// | seed               | int    | 0       | random sequence; same seed, same image (any thread  |
// |                    |        |         | count)                                              |
// | hit_point_search   | string | grid    | "grid" (hashed grid) or "kdtree" (nanoflann); both  |
// |                    |        |         | find the same hit points, the grid faster           |
// | direct_lighting    | int    | 1       | 1: direct light by shadow rays in the eye pass;     |
// |                    |        |         | 0: from photons too (for tests and comparisons)     |
// | glossy_gather_alpha | double | 0.2    | microfacet lobes with min(alpha_u, alpha_v) >= this |
// |                    |        |         | are gathered at visible points, narrower ones are   |
// |                    |        |         | followed like mirrors (Bsdf::continue_probability); |
// |                    |        |         | >= 0, finite                                        |
//
// mode, seed, direct_lighting, initial_radius, initial_radius_pixels and glossy_gather_alpha are fixed once the
// first pass has run;
// in pppm mode photons_per_pass, alpha and max_depth too (every pass must be the same
// experiment for the mean, and for partial renders to merge); the others may change between
// passes.
#pragma once

#include "settings/render_modes.h"

#include <cstdint>
#include <string>

namespace ppm {

// The ranges of the integer settings (their checks and the checkpoint's plausibility bounds).
constexpr std::int64_t kMaxPhotonsPerPass = std::int64_t(1) << 31;
constexpr int kMaxDepthLimit = 1000;

// The automatic photons_per_pass (RenderSettings::paths_per_pass).
// Bidirectional modes: one light subpath per pixel and pass, at most this many: the stored
// vertices take about 2 KB per subpath in a closed room, so the cap bounds them to ~ 0.5 GB
// at any film size. Camera subpath p connects to light subpath p mod the count.
constexpr std::uint64_t kMaxLightSubpathsPerPass = std::uint64_t(1) << 18;
// Photon modes: this many photon paths per pixel, so that the eye pass (one camera path per
// pixel) and the photon pass keep the same share of a pass at any film size; the count the
// equal-time benchmark chose (docs/bench/converge.md), within the bounds below.
constexpr std::uint64_t kPhotonsPerPixel = 6;
constexpr std::uint64_t kMinAutoPhotons = 10000, kMaxAutoPhotons = std::uint64_t(1) << 22;

struct RenderSettings {
    // The modes and their traits: render_modes.h.
    using Mode = RenderMode;
    enum class Search { Grid, KdTree };

    Mode mode = Mode::Vcm;
    std::uint64_t photons_per_pass = 0; // 0: automatic (paths_per_pass)
    double alpha = 2.0 / 3.0;
    double initial_radius = 0;
    double initial_radius_pixels = 1;
    int max_depth = 16;
    std::uint64_t seed = 0;
    Search search = Search::Grid;
    bool direct_lighting = true;
    // Why 0.2: a lobe's reflected image is about 2 alpha wide (the half vector doubles
    // angles), so at 0.2 it spans ~ 0.4 rad, far more than the blur r / distance of a gather
    // radius of a pixel footprint or so, and photons land in it often enough (it covers ~ 1/20
    // of the projected hemisphere). Narrower lobes (Mitsuba's default roughconductor alpha 0.1
    // among them) are continued, which is unbiased and cheap.
    double glossy_gather_alpha = 0.2;

    // The paths a pass traces on a film of `pixels` pixels: photons_per_pass, or when that is
    // 0 kPhotonsPerPixel photon paths per pixel within [kMinAutoPhotons, kMaxAutoPhotons] in
    // the photon modes, one light subpath per pixel up to kMaxLightSubpathsPerPass in the
    // bidirectional ones.
    std::uint64_t paths_per_pass(std::uint64_t pixels) const;

    // Set one setting from its key; `started` is whether a pass has run. Throws ppm::Error:
    // INVALID_ARGUMENT for an unknown key, a key of another type or a value out of range
    // (the message lists the keys or the range), INVALID_OPERATION for a fixed setting.
    void set_int(const std::string &key, std::int64_t value, bool started);
    void set_double(const std::string &key, double value, bool started);
    void set_string(const std::string &key, const std::string &value, bool started);

    std::int64_t get_int(const std::string &key) const;
    double get_double(const std::string &key) const;
    std::string get_string(const std::string &key) const;

    static const char *mode_name(Mode mode) { return mode_traits(mode).name; }
    // The name of a mode number read from a file ("unknown" for a number no mode has).
    static const char *mode_name(std::uint32_t number) {
        const ModeTraits *m = find_mode(number);
        return m ? m->name : "unknown";
    }
};

} // namespace ppm
