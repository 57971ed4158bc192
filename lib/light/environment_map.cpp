// SPDX-License-Identifier: Apache-2.0
#include "light/environment_map.h"

#include "core/error.h"
#include "material/texture.h"
#include "math/sin_cos.h"
#include "math/warp.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace ppm {

namespace {

double luminance(const Rgb &c) { return 0.212671 * c.r + 0.715160 * c.g + 0.072169 * c.b; }

// Index of the first cdf entry above u (the entries are increasing, the last is 1).
size_t find_interval(const double *cdf, size_t count, double u) {
    return std::min<size_t>(std::upper_bound(cdf, cdf + count, u) - cdf, count - 1);
}

} // namespace

EnvironmentMap::EnvironmentMap(const Texture &image, double scale) : scale_(scale) {
    if (!(scale > 0) || !std::isfinite(scale))
        invalid_argument("envmap scale must be finite and > 0, not " + format_number(scale));
    if (image.width() < 2 || image.height() < 3)
        invalid_argument("envmap '" + image.name() + "' has " + std::to_string(image.width()) + " x " +
                         std::to_string(image.height()) + " pixels; it needs at least 2 x 3");
    width_ = image.width();
    height_ = image.height();
    rgb_.resize(static_cast<size_t>(width_) * height_ * 3);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const Rgb c = image.pixel(x, y);
            float *p = &rgb_[(static_cast<size_t>(y) * width_ + x) * 3];
            p[0] = static_cast<float>(c.r), p[1] = static_cast<float>(c.g), p[2] = static_cast<float>(c.b);
        }
    // Cells of the bilinear grid: (i, j) spans columns i, i + 1 and rows j, j + 1.
    const int rows = height_ - 1;
    const double dtheta = kPi / rows, dphi = 2 * kPi / width_;
    row_cdf_.assign(rows, 0);
    cell_cdf_.assign(static_cast<size_t>(rows) * width_, 0);
    cell_prob_.assign(static_cast<size_t>(rows) * width_, 0);
    double total = 0;
    for (int j = 0; j < rows; ++j) {
        // Solid angle of a cell of this row, and the mean of sin(theta) over its theta range.
        const double band = std::cos(j * dtheta) - std::cos((j + 1) * dtheta);
        const double mean_sin = band / dtheta;
        double row_sum = 0;
        for (int i = 0; i < width_; ++i) {
            const Rgb mean = (vertex(i, j) + vertex(i + 1, j) + vertex(i, j + 1) + vertex(i + 1, j + 1)) * 0.25;
            // The bilinear patch's integral over the cell's solid angle, to first order.
            integral_ += mean * (band * dphi * scale_);
            const double w = luminance(mean) * mean_sin;
            row_sum += w;
            cell_prob_[static_cast<size_t>(j) * width_ + i] = w;
            cell_cdf_[static_cast<size_t>(j) * width_ + i] = row_sum;
        }
        for (int i = 0; i < width_; ++i) {
            double &c = cell_cdf_[static_cast<size_t>(j) * width_ + i];
            c = row_sum > 0 ? c / row_sum : 0;
        }
        total += row_sum;
        row_cdf_[j] = total;
    }
    for (double &p : cell_prob_) p = total > 0 ? p / total : 0;
    for (double &c : row_cdf_) c = total > 0 ? c / total : 0;
}

Rgb EnvironmentMap::vertex(int x, int y) const {
    if (x >= width_) x -= width_;
    const float *p = &rgb_[(static_cast<size_t>(y) * width_ + x) * 3];
    return {p[0], p[1], p[2]};
}

void EnvironmentMap::direction_to_uv(const Vec3 &d, double *u, double *v) {
    *u = std::atan2(d.x, -d.z) * (0.5 * kInvPi);
    *v = std::acos(std::clamp(d.y, -1.0, 1.0)) * kInvPi;
}

Vec3 EnvironmentMap::uv_to_direction(double u, double v) {
    const double theta = v * kPi;
    const double sin_theta = std::sin(theta), cos_theta = std::cos(theta);
    double sin_phi, cos_phi;
    sin_cos_2pi(u, &sin_phi, &cos_phi);
    return {sin_phi * sin_theta, cos_theta, -cos_phi * sin_theta};
}

Rgb EnvironmentMap::eval_uv(double u, double v) const {
    // Mitsuba's eval_spectrum: shift by half a texel, wrap, scale to the (W + 1) x H grid.
    u -= 0.5 / width_;
    u -= std::floor(u);
    // Mitsuba wraps v too, which makes the south pole (v = 1 exactly) read the top row; a
    // clamp keeps the pole its own row.
    v = std::clamp(v, 0.0, 1.0);
    const double x = u * width_, y = v * (height_ - 1);
    const int x0 = std::min(static_cast<int>(x), width_ - 1), y0 = std::min(static_cast<int>(y), height_ - 2);
    const double ax = x - x0, ay = y - y0;
    const Rgb value = vertex(x0, y0) * ((1 - ax) * (1 - ay)) + vertex(x0 + 1, y0) * (ax * (1 - ay)) +
                      vertex(x0, y0 + 1) * ((1 - ax) * ay) + vertex(x0 + 1, y0 + 1) * (ax * ay);
    return value * scale_;
}

Rgb EnvironmentMap::eval(const Vec3 &d) const {
    double u, v;
    direction_to_uv(d, &u, &v);
    return eval_uv(u, v);
}

double EnvironmentMap::cell_pdf(int i, int j) const {
    return cell_prob_[static_cast<size_t>(j) * width_ + i] * (static_cast<double>(width_) * (height_ - 1));
}

Vec3 EnvironmentMap::sample(double u1, double u2, double *pdf) const {
    *pdf = 0;
    const int rows = height_ - 1;
    if (!(row_cdf_.back() > 0)) return {0, 1, 0};
    const int j = static_cast<int>(find_interval(row_cdf_.data(), rows, u2));
    const double row_lo = j > 0 ? row_cdf_[j - 1] : 0.0, row_p = row_cdf_[j] - row_lo;
    const double t = std::clamp((u2 - row_lo) / row_p, 0.0, 1.0 - 0x1p-53);
    const double *cdf = &cell_cdf_[static_cast<size_t>(j) * width_];
    const int i = static_cast<int>(find_interval(cdf, width_, u1));
    const double cell_lo = i > 0 ? cdf[i - 1] : 0.0, cell_p = cdf[i] - cell_lo;
    const double s = std::clamp((u1 - cell_lo) / cell_p, 0.0, 1.0 - 0x1p-53);
    // Sample space to image coordinates: the grid's columns sit half a texel right.
    const double u = (i + s) / width_ + 0.5 / width_, v = (j + t) / rows;
    const Vec3 d = uv_to_direction(u, v);
    const double sin_theta = std::sin(v * kPi);
    if (!(sin_theta > 0)) return d;
    *pdf = cell_pdf(i, j) / (2 * kPi * kPi * sin_theta);
    return d;
}

double EnvironmentMap::pdf(const Vec3 &d) const {
    double u, v;
    direction_to_uv(d, &u, &v);
    u -= 0.5 / width_;
    u -= std::floor(u);
    const int i = std::min(static_cast<int>(u * width_), width_ - 1);
    const int j = std::min(static_cast<int>(v * (height_ - 1)), height_ - 2);
    const double sin_theta = std::sqrt(d.x * d.x + d.z * d.z);
    if (!(sin_theta > 0)) return 0;
    return cell_pdf(i, j) / (2 * kPi * kPi * sin_theta);
}

} // namespace ppm
