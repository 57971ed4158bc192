// SPDX-License-Identifier: Apache-2.0
// The benchmark's ray sets. Every ray has a unit direction, tnear = 0 and tfar = INFINITY,
// so t is a distance and comparable across single- and double-precision intersectors. All
// sets are reproducible from the seed: the generator is the bench's own (rng.h).
#pragma once

#include "reference_truth.h"

#include <ppm/ppm.h>

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

// libppm's default scene tolerance (the scene setting "tolerance").
constexpr double default_tolerance = 1e-9;

struct Bounds {
    double lower[3], upper[3];
    double diagonal() const;
    double center(int axis) const { return 0.5 * (lower[axis] + upper[axis]); }
};

// Bounds of all control points (48 doubles per patch).
Bounds control_point_bounds(const std::vector<double> &control_points);

// Rays with the reference's answer for each (filled by compute_truth).
struct RayBatch {
    std::vector<ppm_ray> rays;
    Truth truth;
};

struct RaySet {
    std::string name;        // "random", "camera", "grazing-1e-3", "seams", "poles", "leaving"
    std::string description; // one line: how the rays were made
    RayBatch base;
    // Rays leaving the surface: their origin is offset by ppm_hit_spawn_ray by twice the hit's
    // error bound, which follows the scene tolerance. The exact method at tolerance X traces
    // the variant spawned with p_error = X * diagonal; every other method traces `base`
    // (spawned at the default tolerance 1e-9). Empty for the other sets.
    std::vector<std::pair<double, RayBatch>> variants;

    size_t size() const { return base.rays.size(); }
    // The rays a method whose hits carry `spawn_tolerance` traces.
    const RayBatch &batch(double spawn_tolerance) const;
};

// `count` incoherent rays: origins uniform on the sphere around the box's centre with radius
// equal to the box diagonal, aimed at points uniform inside the box.
RaySet random_rays(const Bounds &box, size_t count, uint64_t seed);

// A width x height pinhole camera, one ray through each pixel centre, row-major from the top
// left. It looks at the box centre from the front-right-above (+x, -y, +z) with a 40 degree
// vertical field of view, from the closest distance at which the whole box projects inside
// the central 95% of the image.
RaySet camera_rays(const Bounds &box, int width, int height);

// Rays at `angle` (radians) to the tangent plane at random surface points (random patch,
// (u, v) uniform in [0.01, 0.99]^2 where the normal is regular), from either side, in a
// random tangent direction, the point lying 0.06 to 0.36 diagonals along the ray.
RaySet grazing_rays(const ref::Intersector &reference, double angle, size_t count, uint64_t seed);

// Rays through points of shared patch edges (two thirds of the rays; edges whose four control
// points coincide, either way round) and through corners shared by three or more patches (one
// third): a third of them along the +-normal there, the rest in uniformly random directions,
// the point lying 0.05 to 0.3 diagonals along the ray. Empty if the model has no seams.
RaySet seam_rays(const ref::Intersector &reference, size_t count, uint64_t seed);

// Rays through the points where a patch edge collapses to a point (the teapot's lid apex
// (0, 0, 3.15) and bottom centre (0, 0, 0)), in uniformly random directions: half exactly
// through the point, half passing it at 1e-9 to 1e-3 diagonals. Empty if there is none.
RaySet pole_rays(const ref::Intersector &reference, size_t count, uint64_t seed);

// Rays leaving the surface: the first robust reference root of random rays (as `random_rays`
// makes them), a cosine-distributed direction on alternately the front and the back side,
// and the origin moved off the surface by ppm_hit_spawn_ray from a hit record with the
// reference's point and normal and p_error = tolerance * diagonal: `base` for the default
// tolerance 1e-9, one variant per entry of `spawn_tolerances`. The truths of the primary
// rays are computed here (on `threads` threads); those of the returned rays are not.
RaySet leaving_rays(const ref::Intersector &reference, const Bounds &box, size_t count, uint64_t seed,
                    const std::vector<double> &spawn_tolerances, int threads);

// "1e-3" for powers of ten, otherwise %g.
std::string format_number(double x);

} // namespace bench
