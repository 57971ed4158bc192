// SPDX-License-Identifier: Apache-2.0
// What every intersection method of the benchmark implements and reports. The driver
// (driver.h) builds a method once on one thread and once on all threads, and traces every
// ray set with each build.
#pragma once

#include <ppm/ppm.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace bench {

// One ray set traced by one method; vectors are indexed by ray.
struct Trace {
    std::vector<double> t;       // INFINITY on a miss; a distance (unit directions)
    std::vector<uint32_t> patch; // patch index of the hit
    std::vector<float> ng;       // 3 per ray: the method's unit geometric normal (0 if none)
    std::vector<float> ns;       // 3 per ray: its shading normal (interpolated on meshes)

    void resize(size_t count) {
        t.assign(count, INFINITY);
        patch.assign(count, 0);
        ng.assign(3 * count, 0.0f);
        ns.assign(3 * count, 0.0f);
    }
    size_t size() const { return t.size(); }
};

// The part of a method's description the reports need.
struct MethodInfo {
    std::string name;              // "exact-1e-9", "embree-N32", "newton-r16", ...
    std::string family;            // exact, newton, embree-uniform, embree-adaptive, cgal-uniform, cgal-adaptive
    std::string parameter;         // "tolerance", "grid", "starts", ...
    double value = 0;              // the parameter's value
    size_t primitives = 0;         // patches or triangles
    double tessellate_seconds = 0; // wall time to make the mesh (library, all threads); 0 for patches
    double deviation = 0;          // the mesh's measured max distance from the patches, / diagonal
    double tolerance = 0;          // the |dt| / diagonal the method promises (libppm's scene tolerance); 0: none
    // Tolerance of the hits this method's rays are spawned from (the `leaving` set): the
    // scene tolerance for the exact method, libppm's default 1e-9 for every other one.
    double spawn_tolerance = 1e-9;
};

struct BuildMemory {
    size_t array_bytes = 0;     // input kept by the structure (control points, vertices, indices)
    size_t structure_bytes = 0; // the acceleration structure itself (see each method)
};

class Method {
public:
    virtual ~Method() = default;
    virtual const MethodInfo &info() const = 0;
    // Builds the structure for `threads` threads (building itself may use them). Replaces any
    // earlier build.
    virtual BuildMemory build(int threads) = 0;
    virtual void release() = 0;
    // Whether trace() spreads one call over the build's threads itself (libppm's batch
    // queries); otherwise the driver calls it on chunks from its own threads.
    virtual bool threads_inside() const { return false; }
    // Traces rays[begin, end) into out (sized for all rays). Thread safe for disjoint ranges.
    virtual void trace(const std::vector<ppm_ray> &rays, size_t begin, size_t end, Trace &out) const = 0;
};

// libppm's exact intersector through the public C API, scene tolerance `tolerance`. With
// `presplit` > 0 the scene setting "patch_presplit" is set too and the method is named after
// it (exact-presplit-N, family exact-presplit); 0 leaves libppm's default.
std::unique_ptr<Method> make_exact_method(const std::vector<double> &control_points, double tolerance,
                                          int presplit = 0);

// Builds and drops one exact scene. Embree and TBB allocate global state (task scheduler,
// per-thread data) at the first commit of the process and keep it until exit; without this
// the first method measured, whichever it is, is charged 1.5 to 4 MB for it.
void warm_up_library(const std::vector<double> &control_points);

// The naive methods of the original course project, implemented in the bench: per patch a
// ray / control-point box test, then Newton on S(u, v) - o - t d = 0 from fixed starts.
enum class NewtonStarts { center, subpatch_centers, random };
// `count`: sub-patches per direction (subpatch_centers: count^2 starts) or random starts.
std::unique_ptr<Method> make_newton_method(const std::vector<double> &control_points, NewtonStarts starts, int count);

struct Mesh; // tessellate.h
// Embree 3 triangles (float vertices, robust scene, rtcIntersect1) on `mesh`.
std::unique_ptr<Method> make_embree_method(std::shared_ptr<const Mesh> mesh);

// Whether CGAL was found at build time; make_cgal_method throws otherwise.
bool cgal_available();
// CGAL's AABB tree (Epick kernel, AABB_triangle_primitive, first_intersection) on `mesh`.
std::unique_ptr<Method> make_cgal_method(std::shared_ptr<const Mesh> mesh);

} // namespace bench
