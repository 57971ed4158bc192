// CGAL's AABB tree baseline, alone in its translation unit: CGAL headers compile slowly.
#include "measure.h"
#include "method.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <cstdio>

namespace bench {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

// The mesh's triangles without the degenerate ones (collapsed patch edges), which CGAL's
// ray/triangle intersection does not accept; `source` maps back to mesh triangle indices.
struct TriangleSoup {
    std::vector<Triangle> triangles;
    std::vector<uint32_t> source;
};

TriangleSoup make_soup(const Mesh &mesh) {
    TriangleSoup soup;
    soup.triangles.reserve(mesh.triangle_count());
    soup.source.reserve(mesh.triangle_count());
    auto point = [&](uint32_t index) {
        const double *p = &mesh.positions[size_t(index) * 3];
        return Point(p[0], p[1], p[2]);
    };
    for (size_t k = 0; k < mesh.triangle_count(); ++k) {
        const uint32_t *i = &mesh.indices[k * 3];
        const Triangle triangle(point(i[0]), point(i[1]), point(i[2]));
        if (triangle.is_degenerate()) continue;
        soup.triangles.push_back(triangle);
        soup.source.push_back(static_cast<uint32_t>(k));
    }
    return soup;
}

void trace_set(const Tree &tree, const TriangleSoup &soup, const Mesh &mesh, const RaySet &set,
               Trace &trace) {
    trace.resize(set.rays.size());
    Stopwatch clock;
    for (size_t i = 0; i < set.rays.size(); ++i) {
        const ppm_ray &ray = set.rays[i];
        const Point origin(ray.org[0], ray.org[1], ray.org[2]);
        const Kernel::Ray_3 query(origin, Kernel::Vector_3(ray.dir[0], ray.dir[1], ray.dir[2]));
        const auto hit = tree.first_intersection(query);
        if (!hit) continue;

        // The first intersection is a point, or a segment when the ray lies in a triangle's
        // plane; the distance along the unit direction is t.
        auto along = [&](const Point &p) {
            return (p.x() - ray.org[0]) * ray.dir[0] + (p.y() - ray.org[1]) * ray.dir[1] +
                   (p.z() - ray.org[2]) * ray.dir[2];
        };
        if (const Point *p = boost::get<Point>(&hit->first)) {
            trace.t[i] = along(*p);
        } else if (const Kernel::Segment_3 *s = boost::get<Kernel::Segment_3>(&hit->first)) {
            trace.t[i] = std::min(along(s->source()), along(s->target()));
        } else {
            continue;
        }
        const size_t index = size_t(hit->second - soup.triangles.begin());
        const Triangle &triangle = soup.triangles[index];
        const Kernel::Vector_3 n = CGAL::cross_product(triangle[1] - triangle[0], triangle[2] - triangle[0]);
        const double n_length = std::sqrt(n.squared_length());
        const double dot = n.x() * ray.dir[0] + n.y() * ray.dir[1] + n.z() * ray.dir[2];
        trace.cos_normal[i] = n_length > 0 ? float(std::fabs(dot) / n_length) : 0.0f;
        double u, v; // the triangle's centroid: enough to tell hits near a patch edge
        triangle_patch_uv(mesh, soup.source[index], 1.0 / 3, 1.0 / 3, &trace.patch[i], &u, &v);
        trace.u[i] = float(u);
        trace.v[i] = float(v);
    }
    trace.wall_seconds = clock.wall_seconds();
    trace.cpu_seconds = clock.cpu_seconds();
}

} // namespace

bool cgal_available() { return true; }

MethodRun run_cgal(const Mesh &mesh, const std::vector<RaySet> &sets) {
    MethodRun run;
    run.family = "cgal";
    run.grid = mesh.n;
    run.name = "cgal-N" + std::to_string(mesh.n);

    const TriangleSoup soup = make_soup(mesh);
    run.array_bytes = soup.triangles.size() * sizeof(Triangle);
    MemoryDelta memory;
    Stopwatch build;
    Tree tree(soup.triangles.begin(), soup.triangles.end());
    tree.build();
    run.build_seconds = build.cpu_seconds();
    run.structure_bytes = memory.take();
    std::fprintf(stderr, "%s: %zu triangles (%zu degenerate dropped), built in %.3f ms\n",
                 run.name.c_str(), soup.triangles.size(),
                 mesh.triangle_count() - soup.triangles.size(), 1e3 * run.build_seconds);

    for (const RaySet &set : sets) {
        std::fprintf(stderr, "%s: tracing %zu %s rays\n", run.name.c_str(), set.rays.size(),
                     set.name.c_str());
        run.traces.emplace_back();
        trace_set(tree, soup, mesh, set, run.traces.back());
    }
    return run;
}

} // namespace bench
