// What every intersection method reports, and the runners that produce it. A runner builds
// its structure once, traces every ray set single-threaded and keeps, per ray, what the
// comparison with the exact intersector needs.
#pragma once

#include "ray_sets.h"
#include "tessellate.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace bench {

// One ray set traced by one method; vectors are indexed by ray.
struct Trace {
    double wall_seconds = 0, cpu_seconds = 0;
    std::vector<double> t;         // INFINITY on a miss
    std::vector<uint32_t> patch;   // patch index of the hit
    std::vector<float> cos_normal; // |cos| between the ray and the geometric normal at the hit
    std::vector<float> u, v;       // patch parameters of the hit (approximate for meshes)

    void resize(size_t count) {
        t.assign(count, INFINITY);
        patch.assign(count, 0);
        cos_normal.assign(count, 0.0f);
        u.assign(count, 0.0f);
        v.assign(count, 0.0f);
    }
};

struct MethodRun {
    std::string name;             // "exact", "embree-N128", ...
    std::string family;           // "exact", "embree", "cgal"
    int grid = 0;                 // segments per patch edge; 0 for the exact method
    double build_seconds = 0;     // building the acceleration structure, single thread
    size_t array_bytes = 0;       // input arrays kept by the structure (vertices, indices)
    size_t structure_bytes = 0;   // memory of the built structure (see each runner)
    std::vector<Trace> traces;    // one per ray set, in the order given
};

// libppm's exact intersector through the public C API, one thread. Throws on errors.
MethodRun run_exact(const std::string &bpt_path, const std::vector<RaySet> &sets);

// Embree 3 on `mesh` (float vertices, robust scene, one thread, rtcIntersect1).
MethodRun run_embree(const Mesh &mesh, const std::vector<RaySet> &sets);

// Whether CGAL was found at build time; run_cgal throws otherwise.
bool cgal_available();
// CGAL's AABB tree (Epick kernel, AABB_triangle_primitive, first_intersection) on `mesh`.
MethodRun run_cgal(const Mesh &mesh, const std::vector<RaySet> &sets);

} // namespace bench
