// SPDX-License-Identifier: Apache-2.0
// Triangle meshes as native Embree triangles (single precision traversal); a filter function
// recomputes each candidate hit in double precision and keeps the closest in the RayQuery.
#pragma once

#include "geometry/mesh_data.h"
#include "scene/geometry.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace ppm {

class MeshGeometry : public Geometry {
public:
    explicit MeshGeometry(MeshData mesh);

    const char *kind() const override { return "triangle mesh"; }
    size_t primitive_count() const override { return source_.indices.size() / 3; }
    Box3 world_bounds(const Affine &transform) const override;
    Box3 prepare(const Affine &transform) override;
    RTCGeometry create_embree(RTCDevice device, const EmbreeFrame &frame) override;
    void describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const override;
    // Interpolated vertex uvs when the mesh has them, else the barycentric (u, v).
    void texture_coordinates(const ppm_hit &hit, double *s, double *t) const override;

    bool has_vertex_normals() const { return !source_.normals.empty() || computes_vertex_normals_; }
    // Flat shading from here on (Mitsuba's face_normals): the next prepare() has no normals.
    void drop_vertex_normals() {
        source_.normals.clear();
        computes_vertex_normals_ = false;
    }
    // For a mesh without normals, what Mitsuba does with a mesh file that has none: vertex
    // normals computed from the placed positions at every prepare() (geometry/vertex_normals.h;
    // from the world positions, as Mitsuba computes them after its to_world).
    void compute_vertex_normals() { computes_vertex_normals_ = source_.normals.empty(); }

    const MeshData &world() const { return *world_; }
    // The world-space data, shared with whoever keeps it (a mesh light) without a copy; a
    // later commit makes a new one and leaves this one to its holders.
    std::shared_ptr<const MeshData> shared_world() const { return world_; }

private:
    MeshData source_;
    std::shared_ptr<MeshData> world_ = std::make_shared<MeshData>();
    double magnitude_ = 0;
    bool computes_vertex_normals_ = false;
};

} // namespace ppm
