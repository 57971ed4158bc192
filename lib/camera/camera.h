// SPDX-License-Identifier: Apache-2.0
// Look-at perspective camera, pinhole or thin lens, with Mitsuba 3's conventions so images
// can be compared pixel for pixel with Mitsuba's `perspective` and `thinlens` sensors.
//
// Frame (Mitsuba 3 `Transform4f::look_at`, include/mitsuba/core/transform.h):
//   forward = normalize(target - origin)
//   left    = normalize(cross(up, forward))
//   up'     = cross(forward, left)
// The camera looks along local +z with local +x = left and +y = up' (right-handed).
//
// Image plane (Mitsuba 3 `perspective_projection`, include/mitsuba/render/sensor.h, and
// src/sensors/perspective.cpp): `fov` is the full angle in degrees along the image x axis
// (fov_axis "x", Mitsuba's default). A film position (x, y) in pixel units, x in [0, width]
// to the right and y in [0, height] DOWN the image, maps to the local direction
//   ( (1 - 2 x / width) tan(fov/2),  (1 - 2 y / height) tan(fov/2) / aspect,  1 ),
// aspect = width / height. So x = 0 is the image's left edge, seen along +left, and the
// pixel (i, j) spans [i, i+1] x [j, j+1] with its centre at (i + 0.5, j + 0.5). Pixels are
// square: the vertical fov follows from the aspect ratio.
//
// Thin lens (Mitsuba 3 src/sensors/thinlens.cpp): the aperture point is
// aperture_radius * square_to_uniform_disk_concentric(lens sample) in the local xy plane
// (the lens sits at the origin), and every ray for one film position passes through the
// point where the pinhole ray meets the plane local z = focus_distance: the plane of focus
// is perpendicular to the view axis (not a sphere around the lens).
//
// Near clip (Mitsuba's `near_clip`): rays start where they cross the plane local z =
// near_clip (tnear = near_clip / cos of the angle to the view axis). Mitsuba's default is
// 0.01; ours is 0, rays start at the lens. There is no far clip.
//
// Principal point offset (Mitsuba's principal_point_offset_x / _y): film position (x, y) is
// imaged as the centred camera images (x + ox width, y + oy height), so the image window
// slides over the plane z = 1 by ox and oy of its own size, keeping its size.
//
// Crop window (Mitsuba's film crop_offset / crop_size): the pixels [crop_x0, crop_x1) x
// [crop_y0, crop_y1) of the width x height film, projected exactly as in the full image,
// make an image of crop_x1 - crop_x0 by crop_y1 - crop_y0 pixels; film positions and pixel
// indices of the camera (generate_ray, project, width, height) are those of the cropped
// image, and pixel (i, j) of it is pixel (crop_x0 + i, crop_y0 + j) of the full one. All four
// 0: the whole film.
#pragma once

#include "camera/pixel_filter.h"
#include "math/vec3.h"

namespace ppm {

struct CameraSettings {
    Vec3 origin{0, 0, 0};
    Vec3 target{0, 0, 1};
    Vec3 up{0, 1, 0};           // need not be unit or perpendicular, only not along the view
    double fov = 45.0;          // degrees, full angle along the image x axis, in (0, 180)
    int width = 0, height = 0;  // pixels, both > 0
    double aperture_radius = 0; // scene units; 0 is a pinhole
    double focus_distance = 0;  // scene units along the view axis; > 0 when aperture_radius > 0
    double near_clip = 0;       // scene units along the view axis, >= 0
    // Crop window in pixels, 0 <= x0 < x1 <= width and 0 <= y0 < y1 <= height; all 0: none.
    int crop_x0 = 0, crop_y0 = 0, crop_x1 = 0, crop_y1 = 0;
    // Fractions of the film's width and height, finite.
    double principal_point_offset_x = 0, principal_point_offset_y = 0;
    PixelFilterSettings filter; // the pixel reconstruction filter (camera/pixel_filter.h)
    bool offset() const { return principal_point_offset_x != 0 || principal_point_offset_y != 0; }
    bool cropped() const { return crop_x0 != 0 || crop_y0 != 0 || crop_x1 != 0 || crop_y1 != 0; }
};

struct CameraRay {
    Vec3 origin;
    Vec3 direction;   // unit length
    double tnear = 0; // where the ray crosses the near clip plane
};

class Camera {
public:
    // Throws ppm::Error (invalid argument) naming the bad setting: non-finite values, fov
    // outside (0, 180), a non-positive image size, origin == target, up along the view
    // direction, a negative aperture, a thin lens without a positive focus distance, or a
    // principal point offset that is not finite or beyond 2^20.
    explicit Camera(const CameraSettings &settings);

    // Primary ray through film position (x, y) in pixel units (see above; pass pixel + jitter).
    // (lens_u, lens_v) in [0,1)^2 picks the aperture point; a pinhole ignores it.
    CameraRay generate_ray(double x, double y, double lens_u, double lens_v) const;

    // Film position of world point p through the lens centre (where p is imaged when in
    // focus). False when p is not in front of the camera (local z <= 0); positions outside
    // the image are returned as they are.
    bool project(const Vec3 &p, double *x, double *y) const;

    // Width of one pixel on the plane at unit distance along the view axis: a pixel's
    // footprint at depth d is about d times this (for initial photon radii).
    double pixel_size_at_unit_distance() const { return x_scale_; }

    // The size of the image rendered: the crop window's, else the film's.
    int width() const { return width_; }
    int height() const { return height_; }
    bool is_thin_lens() const { return aperture_radius_ > 0; }
    // The pixel filter over the rendered image: where camera paths sample and light tracing
    // splats (camera/pixel_filter.h).
    const PixelFilter &filter() const { return filter_; }
    double near_clip() const { return near_clip_; }
    const Vec3 &position() const { return origin_; }
    const Vec3 &forward() const { return forward_; }
    const Vec3 &left() const { return left_; }
    const Vec3 &up() const { return up_; }

private:
    Vec3 origin_, forward_, left_, up_;
    double tan_half_fov_ = 0;
    double aspect_ = 1;
    // The film's top-left corner in local x and y (tan(fov/2) and that / aspect) and the steps
    // per pixel: film to local direction with multiplications only (one ray per pixel and pass).
    double x_left_ = 0, y_top_ = 0, x_scale_ = 0, y_scale_ = 0;
    int width_ = 0, height_ = 0;
    double crop_x0_ = 0, crop_y0_ = 0;
    double aperture_radius_ = 0, focus_distance_ = 0, near_clip_ = 0;
    PixelFilter filter_;
};

} // namespace ppm
