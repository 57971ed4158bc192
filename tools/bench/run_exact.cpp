#include "measure.h"
#include "method.h"

#include <ppm/ppm.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace bench {

namespace {

void check(ppm_status status, const char *call) {
    if (status != PPM_OK)
        throw std::runtime_error(std::string(call) + ": " + ppm_status_string(status) + ": " +
                                 ppm_last_error_message());
}

// Releases the handles however the run ends.
struct Handles {
    ppm_context context = nullptr;
    ppm_scene scene = nullptr;
    ~Handles() {
        ppm_scene_release(scene);
        ppm_context_release(context);
    }
};

void trace_set(ppm_scene scene, const RaySet &set, Trace &trace) {
    // Batches small enough to stay in cache; the per-call overhead is negligible at this size.
    constexpr size_t batch = 4096;
    std::vector<ppm_hit> hits(batch);
    trace.resize(set.rays.size());
    Stopwatch clock;
    for (size_t first = 0; first < set.rays.size(); first += batch) {
        const size_t count = std::min(batch, set.rays.size() - first);
        check(ppm_scene_intersect(scene, set.rays.data() + first, count, hits.data()),
              "ppm_scene_intersect");
        for (size_t k = 0; k < count; ++k) {
            const ppm_hit &hit = hits[k];
            const size_t i = first + k;
            if (hit.geom_id == PPM_INVALID_ID) continue;
            const double *d = set.rays[i].dir;
            trace.t[i] = hit.t;
            trace.patch[i] = hit.prim_id;
            trace.cos_normal[i] = float(std::fabs(hit.ng[0] * d[0] + hit.ng[1] * d[1] + hit.ng[2] * d[2]));
            trace.u[i] = float(hit.u);
            trace.v[i] = float(hit.v);
        }
    }
    trace.wall_seconds = clock.wall_seconds();
    trace.cpu_seconds = clock.cpu_seconds();
}

} // namespace

MethodRun run_exact(const std::string &bpt_path, const std::vector<RaySet> &sets) {
    MethodRun run;
    run.name = run.family = "exact";
    Handles h;
    check(ppm_context_create(&h.context), "ppm_context_create");
    check(ppm_context_set_int(h.context, "threads", 1), "ppm_context_set_int(threads)");
    check(ppm_scene_create(h.context, &h.scene), "ppm_scene_create");
    // The context's Embree device and thread pool are not part of the structure.
    MemoryDelta memory;
    Stopwatch load;
    check(ppm_scene_load_bpt(h.scene, bpt_path.c_str(), nullptr), "ppm_scene_load_bpt");
    const double load_seconds = load.wall_seconds();
    Stopwatch build;
    check(ppm_scene_commit(h.scene), "ppm_scene_commit");
    run.build_seconds = build.cpu_seconds();
    run.structure_bytes = memory.take();
    size_t patches = 0;
    check(ppm_scene_get_primitive_count(h.scene, 0, &patches), "ppm_scene_get_primitive_count");
    run.array_bytes = patches * 16 * 3 * sizeof(double);
    std::fprintf(stderr, "exact: %zu patches loaded in %.3f ms, committed in %.3f ms\n", patches,
                 1e3 * load_seconds, 1e3 * run.build_seconds);

    for (const RaySet &set : sets) {
        std::fprintf(stderr, "exact: tracing %zu %s rays\n", set.rays.size(), set.name.c_str());
        run.traces.emplace_back();
        trace_set(h.scene, set, run.traces.back());
    }
    return run;
}

} // namespace bench
