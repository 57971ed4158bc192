// SPDX-License-Identifier: Apache-2.0
// ppm_camera_v2 as it crosses to Python: a tuple (origin, target, up, fov, width, height,
// aperture_radius, focus_distance, near_clip, crop, principal point offset, pixel filter and
// its parameter), which libppm/camera.py turns into libppm.Camera.
#pragma once

#include <ppm/ppm.h>

#include <nanobind/nanobind.h>
#include <nanobind/stl/array.h>
#include <nanobind/stl/tuple.h>

#include <array>
#include <cstring>
#include <tuple>

namespace ppm_py {

using Vec3 = std::array<double, 3>;
// origin, target, up, fov, width, height, aperture_radius, focus_distance, near_clip, crop
// (x0, y0, x1, y1; all 0: none), principal point offset (x, y), pixel filter (PPM_PIXEL_FILTER_*)
// and its parameter.
using Crop = std::array<uint32_t, 4>;
using Offset = std::array<double, 2>;
using CameraTuple =
    std::tuple<Vec3, Vec3, Vec3, double, uint32_t, uint32_t, double, double, double, Crop, Offset, uint32_t, double>;

inline ppm_camera_v2 to_camera(const CameraTuple &t) {
    ppm_camera_v2 c;
    ppm_camera_v2_init(&c);
    std::memcpy(c.origin, std::get<0>(t).data(), sizeof c.origin);
    std::memcpy(c.target, std::get<1>(t).data(), sizeof c.target);
    std::memcpy(c.up, std::get<2>(t).data(), sizeof c.up);
    c.fov = std::get<3>(t);
    c.width = std::get<4>(t);
    c.height = std::get<5>(t);
    c.aperture_radius = std::get<6>(t);
    c.focus_distance = std::get<7>(t);
    c.near_clip = std::get<8>(t);
    const Crop &crop = std::get<9>(t);
    c.crop_x0 = crop[0];
    c.crop_y0 = crop[1];
    c.crop_x1 = crop[2];
    c.crop_y1 = crop[3];
    c.principal_point_offset_x = std::get<10>(t)[0];
    c.principal_point_offset_y = std::get<10>(t)[1];
    c.pixel_filter = std::get<11>(t);
    c.pixel_filter_parameter = std::get<12>(t);
    return c;
}

inline CameraTuple from_camera(const ppm_camera_v2 &c) {
    return {Vec3{c.origin[0], c.origin[1], c.origin[2]},
            Vec3{c.target[0], c.target[1], c.target[2]},
            Vec3{c.up[0], c.up[1], c.up[2]},
            c.fov,
            c.width,
            c.height,
            c.aperture_radius,
            c.focus_distance,
            c.near_clip,
            Crop{c.crop_x0, c.crop_y0, c.crop_x1, c.crop_y1},
            Offset{c.principal_point_offset_x, c.principal_point_offset_y},
            c.pixel_filter,
            c.pixel_filter_parameter};
}

} // namespace ppm_py
