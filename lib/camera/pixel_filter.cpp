// SPDX-License-Identifier: Apache-2.0
#include "camera/pixel_filter.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>

namespace ppm {

namespace {

constexpr int kSteps = 1024;

double mitsuba_weight(PixelFilterType type, double parameter, double radius, double x) {
    x = std::fabs(x);
    if (type == PixelFilterType::Tent) return std::max(0.0, 1.0 - x / parameter);
    // Gaussian, shifted to 0 at the radius (src/rfilters/gaussian.cpp).
    const double alpha = -1.0 / (2.0 * parameter * parameter);
    return std::max(0.0, std::exp(alpha * x * x) - std::exp(alpha * radius * radius));
}

} // namespace

double pixel_filter_parameter(const PixelFilterSettings &settings) {
    if (settings.type == PixelFilterType::Box) return 0;
    if (settings.type != PixelFilterType::Tent && settings.type != PixelFilterType::Gaussian)
        invalid_argument("pixel filter " + std::to_string(static_cast<std::uint32_t>(settings.type)) +
                         " is not box (0), tent (1) or gaussian (2)");
    if (settings.parameter == 0) return settings.type == PixelFilterType::Tent ? 1.0 : 0.5;
    if (!(settings.parameter > 0 && settings.parameter <= 16))
        invalid_argument(std::string("pixel filter ") + (settings.type == PixelFilterType::Tent ? "radius" : "stddev") +
                         " must lie in (0, 16], not " + format_number(settings.parameter));
    return settings.parameter;
}

PixelFilterAxis::PixelFilterAxis(const PixelFilterSettings &settings, int size) : size_(size) {
    const double parameter = pixel_filter_parameter(settings);
    if (settings.type == PixelFilterType::Box) return;
    radius_ = settings.type == PixelFilterType::Tent ? parameter : 4 * parameter;
    step_ = 2 * radius_ / kSteps;
    table_.resize(kSteps + 1);
    cdf_.resize(kSteps + 1);
    for (int i = 0; i <= kSteps; ++i)
        table_[i] = mitsuba_weight(settings.type, parameter, radius_, -radius_ + i * step_);
    cdf_[0] = 0;
    for (int i = 1; i <= kSteps; ++i) cdf_[i] = cdf_[i - 1] + 0.5 * (table_[i - 1] + table_[i]) * step_;
    cdf_lo_.resize(size);
    mass_.resize(size);
    for (int pixel = 0; pixel < size; ++pixel) {
        // The offsets the image allows, within the filter's support.
        const double centre = pixel + 0.5;
        const double lo = std::max(-radius_, -centre), hi = std::min(radius_, size - centre);
        cdf_lo_[pixel] = cdf_at(lo);
        mass_[pixel] = cdf_at(hi) - cdf_lo_[pixel];
    }
}

double PixelFilterAxis::weight_at(double offset) const {
    const double t = (offset + radius_) / step_;
    if (!(t >= 0 && t <= kSteps)) return 0;
    const int i = std::min(kSteps - 1, static_cast<int>(t));
    const double f = t - i;
    return table_[i] + f * (table_[i + 1] - table_[i]);
}

double PixelFilterAxis::cdf_at(double offset) const {
    const double t = std::clamp((offset + radius_) / step_, 0.0, double(kSteps));
    const int i = std::min(kSteps - 1, static_cast<int>(t));
    const double f = t - i;
    // The integral of the linear piece from its start to f of the step.
    return cdf_[i] + step_ * f * (table_[i] + 0.5 * f * (table_[i + 1] - table_[i]));
}

double PixelFilterAxis::sample(int pixel, double u) const {
    if (is_box()) return pixel + u;
    const double centre = pixel + 0.5;
    const double lo = std::max(-radius_, -centre), hi = std::min(radius_, size_ - centre);
    const double target = cdf_lo_[pixel] + u * mass_[pixel];
    // The step holding the target, then the root of the linear piece's quadratic integral.
    const int i = std::clamp(static_cast<int>(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin()) - 1, 0,
                             kSteps - 1);
    const double a = table_[i], slope = (table_[i + 1] - table_[i]) / step_, rest = target - cdf_[i];
    double x;
    if (std::fabs(slope) * step_ < 1e-12 * std::max(a, 1e-300))
        x = a > 0 ? rest / a : 0.0;
    else
        x = (-a + std::sqrt(std::max(0.0, a * a + 2 * slope * rest))) / slope;
    const double offset = std::clamp(-radius_ + i * step_ + std::clamp(x, 0.0, step_), lo, hi);
    // A position on the image's far edge belongs to no pixel: keep it inside.
    return std::min(centre + offset, std::nextafter(double(size_), 0.0));
}

double PixelFilterAxis::density(int pixel, double x) const {
    if (is_box()) return x >= pixel && x < pixel + 1 ? 1.0 : 0.0;
    if (!(x >= 0 && x <= size_)) return 0;
    const double offset = x - (pixel + 0.5);
    if (!(std::fabs(offset) <= radius_)) return 0;
    return mass_[pixel] > 0 ? weight_at(offset) / mass_[pixel] : 0.0;
}

void PixelFilter::sample(int px, int py, double u1, double u2, double *x, double *y, double *density) const {
    *x = x_.sample(px, u1);
    *y = y_.sample(py, u2);
    *density = is_box() ? 1.0 : this->density(px, py, *x, *y);
}

} // namespace ppm
