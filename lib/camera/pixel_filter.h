// SPDX-License-Identifier: Apache-2.0
// Pixel reconstruction filters with Mitsuba 3's definitions (src/rfilters/): `box` (the pixel
// itself), `tent` (1 - |x| / radius, radius 1 by default) and `gaussian` (exp(-x^2 / (2
// stddev^2)) minus its value at the radius 4 stddev, stddev 0.5 by default: Mitsuba's default
// filter). All are separable: w(x, y) = w(x) w(y), x and y in pixels from the pixel centre.
//
// A pixel's value is the filter-weighted mean of the radiance over the image around its
// centre, restricted to the image as Mitsuba's film restricts its samples (no sample border):
//   I_p = integral over the image of w(x - c_p) L(x) dx / integral over the image of w(x - c_p).
// Camera paths draw their film position with density W_p(x) = w(x - c_p) / (that integral)
// (filter importance sampling, every sample of weight 1), and light tracing splats to every
// pixel p within the radius with weight W_p(x), so both estimate I_p. The box filter is the
// current pixel: positions p + (u1, u2), a splat to the one pixel that holds them.
//
// Mitsuba's scalar variants evaluate a discretised filter, its LLVM ones the exact formula;
// libppm tabulates w in 1024 steps over [-radius, radius] (linear within a step for its
// integrals and sampling; 1e-6 of the exact), and camera paths and light tracing use the
// same table, so their estimates agree exactly. The filters with negative lobes (mitchell,
// catmullrom, lanczos) are not supported: the pass-independent modes sum non-negative pass
// estimates per pixel.
#pragma once

#include <cstdint>
#include <vector>

namespace ppm {

enum class PixelFilterType : std::uint32_t { Box = 0, Tent = 1, Gaussian = 2 };

struct PixelFilterSettings {
    PixelFilterType type = PixelFilterType::Box;
    double parameter = 0; // tent: radius (> 0), gaussian: stddev (> 0); 0: Mitsuba's default
};

// One axis of a filter over an image `size` pixels long.
class PixelFilterAxis {
public:
    PixelFilterAxis() = default;
    // Throws ppm::Error (invalid argument) for a non-finite or non-positive parameter.
    PixelFilterAxis(const PixelFilterSettings &settings, int size);

    bool is_box() const { return radius_ == 0.5 && table_.empty(); }
    double radius() const { return radius_; }
    // A film coordinate for pixel `pixel` from u in [0, 1), with density W_pixel(x).
    double sample(int pixel, double u) const;
    // W_pixel(x): the density sample() draws x with; 0 beyond the radius or the image.
    double density(int pixel, double x) const;

private:
    double cdf_at(double offset) const; // of the unnormalised table, offset from the centre
    double weight_at(double offset) const;
    double radius_ = 0.5;
    int size_ = 0;
    std::vector<double> table_; // w at the step boundaries (empty for the box)
    std::vector<double> cdf_;   // its running integral at the same points
    double step_ = 0;
    // Per pixel: the table's integral up to the image's near edge (or the support's), and its
    // mass within the image, which normalises W_pixel (computed once: light tracing asks for
    // the densities of some 25 pixels per vertex).
    std::vector<double> cdf_lo_, mass_;
};

// Both axes of a filter over a width x height image.
class PixelFilter {
public:
    PixelFilter() = default;
    PixelFilter(const PixelFilterSettings &settings, int width, int height)
        : x_(settings, width), y_(settings, height) {}

    bool is_box() const { return x_.is_box(); }
    double radius() const { return x_.radius(); }
    // A film position for pixel (px, py) from (u1, u2) in [0, 1)^2; its density per pixel
    // area is W(px, py; x, y), returned in *density (1 for the box).
    void sample(int px, int py, double u1, double u2, double *x, double *y, double *density) const;
    // W(px, py; x, y) = W_px(x) W_py(y).
    double density(int px, int py, double x, double y) const { return x_.density(px, x) * y_.density(py, y); }

private:
    PixelFilterAxis x_, y_;
};

// Checks settings (throws ppm::Error naming the bad value) and returns the parameter in use:
// the given one, or Mitsuba's default for 0.
double pixel_filter_parameter(const PixelFilterSettings &settings);

} // namespace ppm
