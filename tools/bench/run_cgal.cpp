// SPDX-License-Identifier: Apache-2.0
// CGAL's AABB tree baseline, alone in its translation unit: CGAL headers compile slowly.
#include "measure.h"
#include "method.h"
#include "tessellate.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>

namespace bench {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

class CgalMethod final : public Method {
public:
    explicit CgalMethod(std::shared_ptr<const Mesh> mesh) : mesh_(std::move(mesh)) {
        const bool uniform = mesh_->grid > 0;
        info_.name = "cgal-" + mesh_->label;
        info_.family = uniform ? "cgal-uniform" : "cgal-adaptive";
        info_.parameter = uniform ? "grid" : "mesh_tolerance";
        info_.value = uniform ? mesh_->grid : mesh_->relative_tolerance;
        info_.primitives = mesh_->triangle_count();
        info_.tessellate_seconds = mesh_->seconds;
        info_.deviation = mesh_->deviation;
    }

    const MethodInfo &info() const override { return info_; }

    // CGAL builds the tree on one thread whatever `threads` says; queries on a built tree are
    // const and run from the driver's threads.
    BuildMemory build(int) override {
        release();
        MemoryDelta memory;
        // The degenerate triangles of a uniform grid at collapsed edges are left out: CGAL's
        // ray / triangle intersection does not accept them.
        auto point = [&](uint32_t index) {
            const double *p = &mesh_->positions[size_t(index) * 3];
            return Point(p[0], p[1], p[2]);
        };
        triangles_.reserve(mesh_->triangle_count());
        source_.reserve(mesh_->triangle_count());
        for (size_t k = 0; k < mesh_->triangle_count(); ++k) {
            const uint32_t *i = &mesh_->indices[k * 3];
            const Triangle triangle(point(i[0]), point(i[1]), point(i[2]));
            if (triangle.is_degenerate()) continue;
            triangles_.push_back(triangle);
            source_.push_back(uint32_t(k));
        }
        tree_ = std::make_unique<Tree>(triangles_.begin(), triangles_.end());
        tree_->build();
        BuildMemory m;
        m.array_bytes = triangles_.size() * sizeof(Triangle) + source_.size() * sizeof(uint32_t);
        const size_t total = memory.take();
        m.structure_bytes = total > m.array_bytes ? total - m.array_bytes : 0;
        return m;
    }

    void release() override {
        tree_.reset();
        triangles_ = {};
        source_ = {};
    }

    void trace(const std::vector<ppm_ray> &rays, size_t begin, size_t end, Trace &out) const override {
        for (size_t i = begin; i < end; ++i) {
            const ppm_ray &ray = rays[i];
            const Point origin(ray.org[0], ray.org[1], ray.org[2]);
            const Kernel::Ray_3 query(origin, Kernel::Vector_3(ray.dir[0], ray.dir[1], ray.dir[2]));
            const auto hit = tree_->first_intersection(query);
            if (!hit) continue;
            // A point, or a segment when the ray lies in a triangle's plane; t along the unit
            // direction.
            auto along = [&](const Point &p) {
                return (p.x() - ray.org[0]) * ray.dir[0] + (p.y() - ray.org[1]) * ray.dir[1] +
                       (p.z() - ray.org[2]) * ray.dir[2];
            };
            Point at;
            if (const Point *p = boost::get<Point>(&hit->first)) {
                at = *p;
            } else if (const Kernel::Segment_3 *s = boost::get<Kernel::Segment_3>(&hit->first)) {
                at = along(s->source()) <= along(s->target()) ? s->source() : s->target();
            } else {
                continue;
            }
            out.t[i] = along(at);
            const size_t index = size_t(hit->second - triangles_.begin());
            const size_t tri = source_[index];
            out.patch[i] = mesh_->triangle_patch[tri];
            const Triangle &triangle = triangles_[index];
            const Kernel::Vector_3 e1 = triangle[1] - triangle[0], e2 = triangle[2] - triangle[0];
            const Kernel::Vector_3 n = CGAL::cross_product(e1, e2);
            const double l = std::sqrt(n.squared_length());
            const double ng[3] = {n.x() / l, n.y() / l, n.z() / l};
            for (int c = 0; c < 3; ++c) out.ng[3 * i + c] = float(ng[c]);
            // Barycentric coordinates of the hit point for the interpolated normal.
            const Kernel::Vector_3 w = at - triangle[0];
            const double d11 = e1 * e1, d12 = e1 * e2, d22 = e2 * e2, w1 = w * e1, w2 = w * e2;
            const double det = d11 * d22 - d12 * d12;
            const double b1 = det != 0 ? (d22 * w1 - d12 * w2) / det : 1.0 / 3;
            const double b2 = det != 0 ? (d11 * w2 - d12 * w1) / det : 1.0 / 3;
            interpolate_normal(*mesh_, tri, b1, b2, &out.ns[3 * i]);
        }
    }

private:
    std::shared_ptr<const Mesh> mesh_;
    MethodInfo info_;
    std::vector<Triangle> triangles_;
    std::vector<uint32_t> source_; // mesh triangle of each CGAL triangle
    std::unique_ptr<Tree> tree_;
};

} // namespace

bool cgal_available() { return true; }

std::unique_ptr<Method> make_cgal_method(std::shared_ptr<const Mesh> mesh) {
    return std::make_unique<CgalMethod>(std::move(mesh));
}

} // namespace bench
