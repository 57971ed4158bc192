// SPDX-License-Identifier: Apache-2.0
// Vertex connection and merging (Georgiev et al. 2012; Hachisuka et al. 2012 call it unified
// path sampling), modes "vcm", "bpt" (connections only: bidirectional path tracing) and "vm"
// (merging only: progressive photon mapping on light subpaths).
//
// A pass traces L light subpaths, one per pixel up to a cap (RenderSettings::paths_per_pass), stores
// their non-specular vertices and connects each to the camera (light tracing); then one camera
// subpath per pixel, which at each non-specular vertex takes a sample on a light (next event),
// connects to every vertex of light subpath (pixel mod L), and merges with the light vertices within the pass's
// radius r_i = r_1 (i + 1)^((alpha - 1) / 2) (Knaus and Zwicker 2011's schedule, so that
// passes stand alone). Emission the camera subpath hits is counted too. All of it is weighted
// by the balance heuristic (vcm_mis.h). Each pass is an unbiased estimate apart from merging's
// blur, which vanishes as r_i -> 0; passes are independent, so checkpoints and partial
// renders are those of pppm mode.
//
// "vm" merges at the camera subpath's first non-specular vertex only, with weight 1, and
// counts emission only on purely specular camera paths: the classic photon map estimate with
// the direct light from photons too. "bpt" never merges.
//
// Russian roulette: a subpath continues at a vertex with a probability that depends on its
// BSDF alone (the largest diffuse reflectance, plus 0.1 under a coat; 1 for metals and glass), so that both directions
// see the same probability and the densities of every technique include it.
//
// Deterministic: every subpath draws counter-based random numbers from (seed, pass, index),
// light tracing's splats are summed in subpath order and merges in the grid's fixed order.
// A thin lens camera is not sampled by light subpaths: the light tracing technique is then
// off (and weighted out). Blends and masks pick one component per vertex, whose densities the weights use.
#pragma once

#include "film/pass_estimate.h"
#include "integrator/integrator.h"

namespace ppm {

struct VcmLightVertex; // vcm_pass_state.h
struct VcmPassState;

class VcmIntegrator : public Integrator {
public:
    enum class Techniques { All, ConnectOnly, MergeOnly };
    explicit VcmIntegrator(Techniques techniques) : techniques_(techniques) {}

    // Traces the pass's light and camera subpaths and commits their estimate to the
    // (pass-independent) film.
    bool render_pass(const PassInputs &in, std::uint32_t pass, Film &film, PassTimes &times) override;
    // One slot per pixel.
    void make_slots(const PassInputs &in, Film &film) override;

    // The merge radius of pass `pass`: initial_radius, or initial_radius_pixels pixel footprints
    // at the distance from the camera to the scene's centre, reduced by alpha.
    static double merge_radius(const PassInputs &in, std::uint32_t pass);

private:
    bool connects() const { return techniques_ != Techniques::MergeOnly; }
    bool merges() const { return techniques_ != Techniques::ConnectOnly; }

    // Pass `pass`'s estimate of every pixel; on cancel it may return early with any estimate.
    void estimate_pass(const PassInputs &in, std::uint32_t pass, PassEstimate &out);

    void trace_light_paths(const PassInputs &in, std::uint32_t pass, VcmPassState &state) const;
    // Light subpath `index`: its stored vertices appended to `vertices`, its light tracing
    // splats (pixel, radiance) to `splats`.
    void trace_light_path(const PassInputs &in, const VcmPassState &state, std::uint32_t pass, std::uint32_t index,
                          std::vector<VcmLightVertex> &vertices,
                          std::vector<std::pair<std::uint32_t, Rgb>> &splats) const;
    // Camera subpath of `pixel`: its radiance estimate; `merge_count` counts the light vertices merged.
    Rgb trace_camera_path(const PassInputs &in, const VcmPassState &state, std::uint32_t pass, std::uint32_t pixel,
                          std::uint32_t &merge_count) const;

    Techniques techniques_;
    std::shared_ptr<VcmPassState> state_; // reused from pass to pass
};

} // namespace ppm
