// SPDX-License-Identifier: Apache-2.0
// Shading normals in light-path (adjoint) transport.
//
// A mesh's interpolated vertex normals (and any shading normal that differs from the
// geometric one) bend the cosine of the scattering integral: camera paths, like Mitsuba 3's
// path tracer, estimate L(wo) = integral of f(wo, wi) L(wi) |wi . ns| dwi, with ns the shading
// normal. Light paths carry flux, which lands on geometric area, so with f alone they would
// estimate the integral with |wi . ng| instead and disagree with the camera paths wherever
// ns != ng (a smooth mesh seen at grazing angles, by a factor of two and more). Veach's
// correction for non-symmetric scattering (thesis, 1997, section 5.3; pbrt-v3's
// CorrectShadingNormal) makes them estimate the camera paths' integral:
// - a light path arriving from a (towards the light) and leaving along b, whose throughput
//   took f |b . ns| / pdf, is multiplied by |a . ns| |b . ng| / (|a . ng| |b . ns|); the same
//   factor applies where a light vertex is joined along b to the camera or to a camera vertex;
// - flux arriving along wi at a camera vertex (a photon or a merged light vertex, density
//   estimated per area of the surface it landed on) is weighed by |wi . ns| / |wi . ng'|,
//   ng' the geometric normal where it landed: on the camera vertex's own surface that is
//   ng, and a light vertex gathered from a neighbouring surface (a box's other side within
//   the radius) keeps a bounded weight, where |wi . ng| would divide by nearly 0.
// Both are exactly 1 where the camera or light vertex's normals agree. Directions are local
// to the shading frame.
#pragma once

#include "shading/render_scene.h"

#include <cmath>

namespace ppm {

// 1 - |cos| between the normals below which they count as one (an angle of about 1.4e-6).
constexpr double kShadingNormalTolerance = 1e-12;

// Whether `sp`'s shading normal is its geometric one (up to orientation and rounding: a flat
// mesh's stored normals differ from its computed face normals in the last bits), so that no
// correction is made. Rounding must not switch the correction on: at a corner, flux that
// landed on the neighbouring face would take |wi . ns| / |wi . ng'| for nothing.
inline bool shading_normal_is_geometric(const SurfacePoint &sp) {
    return std::fabs(dot(sp.frame.n, sp.ng)) >= 1.0 - kShadingNormalTolerance;
}

// |a . ns| |b . ng| / (|a . ng| |b . ns|) for a light path arriving from a and leaving along
// b at `sp`; 0 where a denominator is 0.
inline double light_path_shading_correction(const SurfacePoint &sp, const Vec3 &a, const Vec3 &b) {
    if (shading_normal_is_geometric(sp)) return 1.0;
    const Vec3 ng = sp.frame.to_local(sp.ng);
    const double denominator = std::fabs(dot(a, ng)) * std::fabs(b.z);
    return denominator > 0 ? std::fabs(a.z) * std::fabs(dot(b, ng)) / denominator : 0.0;
}

// |wi . ns| / cos_landing for flux arriving along wi at camera vertex `sp`, cos_landing being
// |wi . ng'| where it landed; 0 for flux that landed tangentially.
inline double arriving_flux_shading_factor(const SurfacePoint &sp, const Vec3 &wi, double cos_landing) {
    if (shading_normal_is_geometric(sp)) return 1.0;
    return cos_landing > 0 ? std::fabs(wi.z) / cos_landing : 0.0;
}

} // namespace ppm
