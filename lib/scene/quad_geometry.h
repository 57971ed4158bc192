// SPDX-License-Identifier: Apache-2.0
// Parallelograms as Embree user geometry, intersected in double precision.
#pragma once

#include "scene/geometry.h"

namespace ppm {

class QuadGeometry : public Geometry {
public:
    QuadGeometry(const Vec3 &origin, const Vec3 &edge_u, const Vec3 &edge_v);

    const char *kind() const override { return "quad"; }
    size_t primitive_count() const override { return 1; }
    bool planar() const override { return true; }
    Box3 world_bounds(const Affine &transform) const override;
    Box3 prepare(const Affine &transform) override;
    RTCGeometry create_embree(RTCDevice device, const EmbreeFrame &frame) override;
    void describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const override;

    struct Data {
        Vec3 origin, edge_u, edge_v, normal; // normal = edge_u x edge_v, not normalised
        double uu, uv, vv, det;              // Gram matrix of the edges and its determinant
        Box3 box;
        // What every hit needs, made once: the unit normal and the rounding part of p_error.
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
