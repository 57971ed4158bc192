// SPDX-License-Identifier: Apache-2.0
// What the bidirectional modes' two halves share (vcm_integrator.cpp traces the light
// subpaths, vcm_camera_paths.cpp the camera subpaths): the stored light vertices, the pass's
// state and the per-vertex rules.
#pragma once

#include "render/vcm_integrator.h"

#include <cstdint>
#include <vector>

namespace ppm {

// Random streams (CounterRng's second key); 0 to 2 are the camera, photon and direct ones.
constexpr std::uint8_t kVcmLightStream = 3;
constexpr std::uint8_t kVcmCameraStream = 4;

struct VcmIntegrator::LightVertex {
    SurfacePoint sp; // wo_local points back along the subpath, towards the light
    Rgb throughput;  // the subpath's weight up to here (flux per light subpath)
    SubpathMis mis;
    std::uint32_t path_length = 0; // segments from the light
};

struct VcmIntegrator::PassState {
    MisFactors mis;
    double radius = 0;
    double pixel_area = 0;         // of one pixel on the plane at unit distance along the view axis
    int max_length = 0;            // segments of a full path: max_depth scattering vertices + 1
    bool light_tracing = false;    // light vertices connect to the camera (not through a thin lens)
    std::uint32_t light_paths = 0; // light subpaths this pass (RenderSettings::paths_per_pass)
    // The stored light vertices live in block_vertices; vertices[k] points at the k-th in
    // subpath order (one copy of them, not two: they are most of the pass's memory).
    std::vector<const LightVertex *> vertices;
    std::vector<std::uint32_t> path_start; // light subpath i's vertices: [path_start[i], path_start[i + 1])
    LightVertexGrid grid;                  // over the vertices, when merging
    std::vector<Rgb> splat;                // per pixel: light tracing's sum
    std::vector<Vec3> points;              // the vertices' positions, for the grid
    // What merging reads of a light vertex, in the grid's order: a query reads its buckets'
    // records one after the other instead of whole vertices at random.
    struct MergeRecord {
        Vec3 arriving; // world direction towards where the light came from
        Rgb throughput;
        double dvcm = 0, dvm = 0;
        std::uint32_t path_length = 0;
    };
    std::vector<MergeRecord> merge_records;
    // Per block of light subpaths while they are traced (vcm_integrator.cpp).
    std::vector<std::vector<LightVertex>> block_vertices;
    std::vector<std::vector<std::uint32_t>> block_counts;
    std::vector<std::vector<std::pair<std::uint32_t, Rgb>>> block_splats;
};

// Whether a BSDF has a part other techniques can reach (eval and pdf non-zero): every
// non-specular one and the rough interface, which is continued, never gathered, by the photon
// modes but is an ordinary lobe here.
inline bool vcm_connectible(const Bsdf &bsdf) {
    return bsdf.has_non_specular() || bsdf.type() == Bsdf::Type::RoughDielectric;
}

// Russian roulette's continuation probability at a vertex: its BSDF's alone (vcm_integrator.h).
// Diffuse: its largest reflectance; a coat over a diffuse base reflects a little more (its
// Fresnel share): that plus 0.1. Metals and glass lose little: 1.
inline double vcm_continuation(const Bsdf &bsdf) {
    switch (bsdf.type()) {
    case Bsdf::Type::Diffuse: return std::min(1.0, std::max(0.05, bsdf.reflectance().max()));
    case Bsdf::Type::Coated:
    case Bsdf::Type::RoughPlastic: return std::min(1.0, std::max(0.05, bsdf.reflectance().max() + 0.1));
    default: return 1.0;
    }
}

// The solid-angle density of the pinhole camera's ray along unit `direction`: film positions
// are uniform per pixel, and a pixel of area A on the unit plane subtends A cos^3 steradians.
inline double vcm_camera_pdf_w(const Camera &camera, double pixel_area, const Vec3 &direction) {
    const double c = dot(camera.forward(), direction);
    return c > 0 ? 1.0 / (pixel_area * c * c * c) : 0.0;
}

// The next subpath vertex's sampled direction, with the densities the weights need.
struct VcmScatter {
    Vec3 wi;    // local
    Rgb weight; // f |cos| / pdf, over the continuation probability
    double pdf_fwd = 0, pdf_rev = 0;
    bool specular = false;
};

// Samples a continuation at `sp` (Russian roulette included); false when the subpath ends.
inline bool vcm_scatter(const SurfacePoint &sp, CounterRng &rng, TransportMode mode, VcmScatter &out) {
    const double u_lobe = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform(), u_rr = rng.uniform();
    const BsdfSample s = sp.bsdf.sample(sp.wo_local, u_lobe, u1, u2, mode);
    if (!s.valid() || s.weight.is_black()) return false;
    const double cont = vcm_continuation(sp.bsdf);
    if (u_rr >= cont) return false;
    out.wi = s.wi;
    out.specular = s.is_specular;
    out.weight = s.weight / cont;
    // A specular lobe's density is the same both ways (the ratio cancels in the weights); a
    // non-specular one's comes from pdf(), the density every other technique evaluates.
    out.pdf_fwd = (s.is_specular ? s.pdf : sp.bsdf.pdf(sp.wo_local, s.wi)) * cont;
    out.pdf_rev = s.is_specular ? out.pdf_fwd : sp.bsdf.pdf(s.wi, sp.wo_local) * cont;
    return out.pdf_fwd > 0;
}

} // namespace ppm
