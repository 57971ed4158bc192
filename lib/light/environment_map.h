// SPDX-License-Identifier: Apache-2.0
// A latitude-longitude environment map as Mitsuba 3 reads one (src/emitters/envmap.cpp):
//  - direction d (emitter space, pointing away from the scene) to image coordinates:
//    u = atan2(d.x, -d.z) / (2 pi), v = acos(d.y) / pi, so +Y is up (v = 0, the top row)
//    and u = 0 (the left edge) looks along -Z, u = 1/4 along +X;
//  - lookup: bilinear; horizontally pixel x's centre is at u = (x + 1/2) / W and wraps
//    around (column W is column 0 again), vertically row y sits at v = y / (H - 1), so the
//    top row is the north pole and the bottom row the south pole;
//  - importance sampling: a 2D piecewise-constant distribution over the W x (H - 1) cells of
//    that bilinear grid, each weighted by its corners' mean luminance times the mean of
//    sin(theta) over the cell, uniform inside a cell: pdf in (u, v) p(u, v), in solid angle
//    p(u, v) / (2 pi^2 sin theta). (Mitsuba samples the bilinear function itself; any
//    density that is positive wherever L is gives the same expectation.)
#pragma once

#include "math/rgb.h"
#include "math/vec3.h"

#include <vector>

namespace ppm {

class Texture;

class EnvironmentMap {
public:
    // Throws ppm::Error INVALID_ARGUMENT for an image under 2 x 3 pixels (as Mitsuba) or a
    // scale that is not finite and > 0.
    EnvironmentMap(const Texture &image, double scale);

    // Radiance from emitter-space direction d (unit).
    Rgb eval(const Vec3 &d) const;
    Rgb eval_uv(double u, double v) const;
    // A direction (emitter space, unit) from two uniform numbers, with its solid-angle pdf;
    // pdf 0 when none (a black map, or a sample exactly at a pole).
    Vec3 sample(double u1, double u2, double *pdf) const;
    double pdf(const Vec3 &d) const;
    // Integral of the radiance over all directions (for the light's power).
    Rgb integral() const { return integral_; }
    int width() const { return width_; }
    int height() const { return height_; }

    static void direction_to_uv(const Vec3 &d, double *u, double *v);
    static Vec3 uv_to_direction(double u, double v);

private:
    Rgb vertex(int x, int y) const;      // x in [0, W] (W wraps to 0), y in [0, H)
    double cell_pdf(int i, int j) const; // pdf in (u, v) over cell (i, j)

    int width_ = 0, height_ = 0;
    double scale_ = 1;
    std::vector<float> rgb_;        // W x H, row-major from the top row
    std::vector<double> row_cdf_;   // H - 1 entries: marginal over cell rows
    std::vector<double> cell_cdf_;  // (H - 1) x W: conditional within each row
    std::vector<double> cell_prob_; // (H - 1) x W: probability of each cell
    Rgb integral_;
};

} // namespace ppm
