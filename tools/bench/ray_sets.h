// The benchmark's ray sets. Every ray has a unit direction, tnear = 0 and tfar = INFINITY,
// so t is a distance and comparable across single- and double-precision intersectors.
#pragma once

#include <ppm/ppm.h>

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

struct Bounds {
    double lower[3], upper[3];
    double diagonal() const;
    double center(int axis) const { return 0.5 * (lower[axis] + upper[axis]); }
};

// Bounds of all control points (48 doubles per patch).
Bounds control_point_bounds(const std::vector<double> &control_points);

struct RaySet {
    std::string name;
    std::vector<ppm_ray> rays;
};

// `count` incoherent rays: origins uniform on the sphere around the box's centre with radius
// equal to the box diagonal, aimed at points uniform inside the box. Reproducible: the
// generator is our own (splitmix64), not the platform's <random> distributions.
RaySet random_rays(const Bounds &box, size_t count, uint64_t seed);

// A width x height pinhole camera, one ray through each pixel centre, row-major from the top
// left. It looks at the box centre from the front-right-above (+x, -y, +z) with a 40 degree
// vertical field of view, from the closest distance at which the whole box projects inside
// the central 95% of the image.
RaySet camera_rays(const Bounds &box, int width, int height);

} // namespace bench
