// SPDX-License-Identifier: Apache-2.0
// Linear RGB triple for reflectances, path weights and radiance. Double precision like Vec3:
// photon flux is accumulated over billions of photons, and after ~1e9 additions a float
// sum loses the bits of each new one.
#pragma once

#include <algorithm>
#include <cmath>

namespace ppm {

struct Rgb {
    double r = 0, g = 0, b = 0;

    constexpr Rgb() = default;
    constexpr Rgb(double r_, double g_, double b_) : r(r_), g(g_), b(b_) {}
    constexpr explicit Rgb(double v) : r(v), g(v), b(v) {}

    Rgb operator+(const Rgb &o) const { return {r + o.r, g + o.g, b + o.b}; }
    Rgb operator-(const Rgb &o) const { return {r - o.r, g - o.g, b - o.b}; }
    Rgb operator*(const Rgb &o) const { return {r * o.r, g * o.g, b * o.b}; }
    Rgb operator*(double s) const { return {r * s, g * s, b * s}; }
    Rgb operator/(double s) const { return {r / s, g / s, b / s}; }
    Rgb &operator+=(const Rgb &o) {
        r += o.r;
        g += o.g;
        b += o.b;
        return *this;
    }
    Rgb &operator*=(const Rgb &o) {
        r *= o.r;
        g *= o.g;
        b *= o.b;
        return *this;
    }
    Rgb &operator*=(double s) {
        r *= s;
        g *= s;
        b *= s;
        return *this;
    }

    double mean() const { return (r + g + b) / 3.0; }
    double max() const { return std::max(r, std::max(g, b)); }
    double min() const { return std::min(r, std::min(g, b)); }
    bool is_black() const { return r == 0 && g == 0 && b == 0; }
    bool is_finite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};

inline Rgb operator*(double s, const Rgb &c) { return c * s; }

} // namespace ppm
