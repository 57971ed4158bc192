// SPDX-License-Identifier: Apache-2.0
// Spheres as Embree user geometry, intersected in double precision.
#pragma once

#include "scene/geometry.h"

namespace ppm {

class SphereGeometry : public Geometry {
public:
    SphereGeometry(const Vec3 &center, double radius);

    const char *kind() const override { return "sphere"; }
    size_t primitive_count() const override { return 1; }
    void check_transform(const Affine &transform) const override;
    Box3 world_bounds(const Affine &transform) const override;
    Box3 prepare(const Affine &transform) override;
    RTCGeometry create_embree(RTCDevice device, const EmbreeFrame &frame) override;
    void describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const override;
    void compute_uv(ppm_hit &hit) const override;

    struct Data {
        Vec3 center;
        double radius, inv_radius;
        Vec3 axis[3];        // the object's x, y, z axes in world space, for (u, v)
        double rounding = 0; // bound on the rounding of a hit point: 32 ulps of its magnitude
        EmbreeFrame frame;
    };

    const Data &data() const { return data_; } // world space, valid after commit

private:
    Vec3 source_center_;
    double source_radius_;
    Data data_{};
};

} // namespace ppm
