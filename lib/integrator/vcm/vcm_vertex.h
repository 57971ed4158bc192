// SPDX-License-Identifier: Apache-2.0
// The per-vertex rules that the bidirectional modes' two halves share (vcm_integrator.cpp
// traces the light subpaths, vcm_camera_paths.cpp the camera subpaths).
#pragma once

#include "camera/camera.h"
#include "integrator/vcm/vcm_pass_state.h"
#include "material/bsdf.h"
#include "photon/random.h"
#include "shading/render_scene.h"

#include <algorithm>
#include <cstdint>

namespace ppm {

// Random streams (CounterRng's second key); 0 to 2 are the camera, photon and direct ones.
constexpr std::uint8_t kVcmLightStream = 3;
constexpr std::uint8_t kVcmCameraStream = 4;

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
