// SPDX-License-Identifier: Apache-2.0
// Open cylinders (tubes without caps) as Embree user geometry, intersected in double
// precision: Mitsuba 3's `cylinder` (src/shapes/cylinder.cpp), the points at `radius` from
// the segment p0 -> p1, normals outward.
#pragma once

#include "math/frame.h"
#include "scene/geometry.h"

namespace ppm {

class CylinderGeometry : public Geometry {
public:
    CylinderGeometry(const Vec3 &p0, const Vec3 &p1, double radius);

    const char *kind() const override { return "cylinder"; }
    size_t primitive_count() const override { return 1; }
    // Rotations, translations and uniform scaling only (the tube stays circular).
    void check_transform(const Affine &transform) const override;
    Box3 world_bounds(const Affine &transform) const override;
    Box3 prepare(const Affine &transform) override;
    RTCGeometry create_embree(RTCDevice device, const EmbreeFrame &frame) override;
    // Normal outward from the axis; (u, v) = (phi / 2 pi, z / |p1 - p0|) as Mitsuba's cylinder:
    // phi the angle about the axis from the frame's s towards t (Frame::from_normal of the
    // unit axis, Duff et al.'s basis as Mitsuba's coordinate_system), z the height above p0.
    void describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const override;

    struct Data {
        Vec3 p0, p1;
        Frame frame_axis; // n = unit axis p0 -> p1
        double height, radius;
        Box3 box;
        double rounding = 0;
        EmbreeFrame frame;
    };

    const Data &data() const { return data_; } // world space, valid after commit

private:
    Vec3 source_p0_, source_p1_;
    double source_radius_;
    Data data_{};
};

} // namespace ppm
