// SPDX-License-Identifier: Apache-2.0
#include "camera/camera.h"

#include "core/error.h"
#include "math/limits.h"
#include "math/warp.h"

#include <cmath>

namespace ppm {

namespace {

void require_finite(const Vec3 &v, const char *name) {
    if (!is_finite(v)) invalid_argument(std::string("camera ") + name + " is not finite");
    if (!within_coordinate_limit(v))
        invalid_argument(std::string("camera ") + name + " has a coordinate beyond +-" +
                         format_number(kCoordinateLimit) + " (the limit of scene coordinates)");
}

} // namespace

Camera::Camera(const CameraSettings &s) {
    require_finite(s.origin, "origin");
    require_finite(s.target, "target");
    require_finite(s.up, "up");
    if (!(s.fov > 0 && s.fov < 180))
        invalid_argument("camera fov must lie in (0, 180) degrees, got " + format_number(s.fov));
    if (s.width <= 0 || s.height <= 0)
        invalid_argument("camera image size must be positive, got " + std::to_string(s.width) + " x " +
                         std::to_string(s.height));
    if (!(s.aperture_radius >= 0 && std::isfinite(s.aperture_radius)))
        invalid_argument("camera aperture_radius must be finite and >= 0, got " + format_number(s.aperture_radius));
    if (s.aperture_radius > 0 && !(s.focus_distance > 0 && std::isfinite(s.focus_distance)))
        invalid_argument("camera focus_distance must be finite and > 0 for a thin lens, got " +
                         format_number(s.focus_distance));

    const Vec3 view = s.target - s.origin;
    const double view_length = length(view);
    if (!(view_length > 0)) invalid_argument("camera target equals its origin");
    forward_ = view / view_length;
    const double up_length = length(s.up);
    if (!(up_length > 0)) invalid_argument("camera up vector is zero");
    // |cross| = sin of the angle between up and the view: below ~1e-9 the frame is noise.
    const Vec3 left = cross(s.up / up_length, forward_);
    const double sin_angle = length(left);
    if (!(sin_angle > 1e-9)) invalid_argument("camera up vector is parallel to the view direction");
    left_ = left / sin_angle;
    up_ = cross(forward_, left_);

    origin_ = s.origin;
    tan_half_fov_ = std::tan(0.5 * s.fov * (kPi / 180.0));
    aspect_ = double(s.width) / double(s.height);
    x_scale_ = 2.0 * tan_half_fov_ / s.width;
    y_scale_ = 2.0 * tan_half_fov_ / aspect_ / s.height;
    width_ = s.width;
    height_ = s.height;
    if (s.cropped()) {
        if (!(0 <= s.crop_x0 && s.crop_x0 < s.crop_x1 && s.crop_x1 <= s.width && 0 <= s.crop_y0 &&
              s.crop_y0 < s.crop_y1 && s.crop_y1 <= s.height))
            invalid_argument("camera crop window " + std::to_string(s.crop_x0) + "," + std::to_string(s.crop_y0) + "," +
                             std::to_string(s.crop_x1) + "," + std::to_string(s.crop_y1) +
                             " must satisfy 0 <= x0 < x1 <= width and 0 <= y0 < y1 <= height (" +
                             std::to_string(s.width) + " x " + std::to_string(s.height) + ")");
        crop_x0_ = s.crop_x0;
        crop_y0_ = s.crop_y0;
        width_ = s.crop_x1 - s.crop_x0;
        height_ = s.crop_y1 - s.crop_y0;
    }
    for (const double offset : {s.principal_point_offset_x, s.principal_point_offset_y})
        if (!(std::fabs(offset) <= 1048576.0))
            invalid_argument("camera principal point offset must be finite and within +-2^20 film sizes, got " +
                             format_number(offset));
    // The cropped image's top-left corner: the full film's, moved by the crop offset and by
    // the principal point offset (in pixels of the full film).
    x_left_ = tan_half_fov_ - (crop_x0_ + s.principal_point_offset_x * s.width) * x_scale_;
    y_top_ = tan_half_fov_ / aspect_ - (crop_y0_ + s.principal_point_offset_y * s.height) * y_scale_;
    aperture_radius_ = s.aperture_radius;
    focus_distance_ = s.focus_distance;
    if (!(s.near_clip >= 0 && std::isfinite(s.near_clip)))
        invalid_argument("camera near_clip must be finite and >= 0, got " + format_number(s.near_clip));
    near_clip_ = s.near_clip;
    filter_ = PixelFilter(s.filter, width_, height_);
}

CameraRay Camera::generate_ray(double x, double y, double lens_u, double lens_v) const {
    // Local direction to the film position on the plane z = 1 (Mitsuba's sample_to_camera).
    const double px = x_left_ - x * x_scale_;
    const double py = y_top_ - y * y_scale_;
    if (aperture_radius_ <= 0) {
        // d has unit length along the view axis, so the near plane lies at near_clip * |d|.
        const Vec3 d = left_ * px + up_ * py + forward_;
        const double length_d = std::sqrt(dot(d, d));
        return {origin_, d * (1.0 / length_d), near_clip_ * length_d};
    }
    double ax, ay;
    square_to_uniform_disk_concentric(lens_u, lens_v, &ax, &ay);
    ax *= aperture_radius_;
    ay *= aperture_radius_;
    // Focus point (px, py, 1) * focus_distance minus the aperture point (ax, ay, 0).
    const Vec3 d = left_ * (px * focus_distance_ - ax) + up_ * (py * focus_distance_ - ay) + forward_ * focus_distance_;
    const Vec3 unit = normalize(d);
    return {origin_ + left_ * ax + up_ * ay, unit, near_clip_ / dot(unit, forward_)};
}

bool Camera::project(const Vec3 &p, double *x, double *y) const {
    const Vec3 v = p - origin_;
    const double z = dot(v, forward_);
    if (!(z > 0)) return false;
    const double px = dot(v, left_) / z, py = dot(v, up_) / z;
    *x = (x_left_ - px) / x_scale_;
    *y = (y_top_ - py) / y_scale_;
    return true;
}

} // namespace ppm
