// SPDX-License-Identifier: Apache-2.0
// Disks (ellipses under a general transform) as Embree user geometry, intersected in double
// precision: {center + x axis_u + y axis_v : x^2 + y^2 <= 1}, Mitsuba 3's `disk`
// (src/shapes/disk.cpp: the unit disk at z = 0, normal +z, placed by to_world).
#pragma once

#include "scene/geometry.h"

namespace ppm {

class DiskGeometry : public Geometry {
public:
    DiskGeometry(const Vec3 &center, const Vec3 &axis_u, const Vec3 &axis_v);

    const char *kind() const override { return "disk"; }
    size_t primitive_count() const override { return 1; }
    bool planar() const override { return true; }
    Box3 world_bounds(const Affine &transform) const override;
    Box3 prepare(const Affine &transform) override;
    RTCGeometry create_embree(RTCDevice device, const EmbreeFrame &frame) override;
    // Normal axis_u x axis_v (unit); (u, v) = (r, phi / 2 pi) as Mitsuba's disk: r the radial
    // coordinate in [0, 1], phi the angle from axis_u towards axis_v in [0, 2 pi).
    void describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const override;

    struct Data {
        Vec3 center, axis_u, axis_v, normal; // normal = axis_u x axis_v, not normalised
        double uu, uv, vv, det;              // Gram matrix of the axes and its determinant
        Box3 box;
        Vec3 unit_normal;
        double rounding = 0;
        EmbreeFrame frame;
    };

    const Data &data() const { return data_; } // world space, valid after commit

private:
    Vec3 source_[3];
    Data data_{};
};

} // namespace ppm
