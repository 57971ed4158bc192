// SPDX-License-Identifier: Apache-2.0
// What every mode's camera paths share: the jittered camera ray of a pixel, the visible point
// a path leaves on a non-specular surface with its initial gather radius, and the direct light
// estimated there by shadow rays.
#pragma once

#include "integrator/integrator.h"
#include "integrator/visible_point.h"
#include "photon/random.h"

#include <cstdint>

namespace ppm {

// Random streams (CounterRng's second key) of the camera paths.
constexpr std::uint8_t kCameraStream = 0;
constexpr std::uint8_t kDirectStream = 2; // PPM: direct light at the fixed points
// (kPhotonStream = 1 is the photon tracer's.)

// Pixel `pixel`'s ray through a point of the film drawn by the camera's pixel filter (a
// uniformly jittered point of the pixel for the box) and of the lens; `film_density`, when
// given, receives that point's density per pixel area (camera/pixel_filter.h).
ppm_ray camera_ray(const Camera &camera, std::uint32_t pixel, CounterRng &rng, double *film_density = nullptr);

// The squared initial gather radius of a visible point `path_length` from the camera.
double footprint_r2(const PassInputs &in, double path_length);

VisiblePoint make_visible_point(const PassInputs &in, const SurfacePoint &sp, const Vec3 &ray_dir, const Rgb &weight,
                                double path_length);

// The most visible points add_direct_light takes at once.
constexpr std::uint32_t kMaxDirectGroup = static_cast<std::uint32_t>(Scene::max_stream);

// One sample on every light, with a shadow ray each, for `count` (<= kMaxDirectGroup) visible
// points, added to direct[k]; invalid points get nothing. at[k]: point k's hit, if kept (the
// shadow rays leave it: RayHints::leaving). Nothing without settings.direct_lighting.
void add_direct_light(const PassInputs &in, const VisiblePoint *vps, const ppm_hit *const *at, CounterRng *rngs,
                      std::uint32_t count, Rgb *direct);

} // namespace ppm
