#include "measure.h"
#include "method.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace bench {

namespace {

// Embree reports every allocation it makes (BVH nodes, buffers) to this monitor.
std::atomic<long long> embree_bytes{0};

bool monitor(void *, ssize_t bytes, bool) {
    embree_bytes += bytes;
    return true;
}

struct EmbreeHandles {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    ~EmbreeHandles() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

void check_device(RTCDevice device, const char *what) {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE)
        throw std::runtime_error(std::string("embree: ") + what + " failed (error " +
                                 std::to_string(int(error)) + ")");
}

void trace_set(RTCScene scene, const Mesh &mesh, const RaySet &set, Trace &trace) {
    trace.resize(set.rays.size());
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    Stopwatch clock;
    for (size_t i = 0; i < set.rays.size(); ++i) {
        const ppm_ray &ray = set.rays[i];
        RTCRayHit rh;
        rh.ray.org_x = float(ray.org[0]);
        rh.ray.org_y = float(ray.org[1]);
        rh.ray.org_z = float(ray.org[2]);
        rh.ray.dir_x = float(ray.dir[0]);
        rh.ray.dir_y = float(ray.dir[1]);
        rh.ray.dir_z = float(ray.dir[2]);
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = INFINITY;
        rh.ray.time = 0.0f;
        rh.ray.mask = 0xFFFFFFFFu; // masks are enabled in Debian's Embree build
        rh.ray.id = 0;
        rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;

        trace.t[i] = rh.ray.tfar;
        const double n[3] = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
        const double n_length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        const double dot = n[0] * ray.dir[0] + n[1] * ray.dir[1] + n[2] * ray.dir[2];
        trace.cos_normal[i] = n_length > 0 ? float(std::fabs(dot) / n_length) : 0.0f;
        double u, v;
        triangle_patch_uv(mesh, rh.hit.primID, rh.hit.u, rh.hit.v, &trace.patch[i], &u, &v);
        trace.u[i] = float(u);
        trace.v[i] = float(v);
    }
    trace.wall_seconds = clock.wall_seconds();
    trace.cpu_seconds = clock.cpu_seconds();
}

} // namespace

MethodRun run_embree(const Mesh &mesh, const std::vector<RaySet> &sets) {
    MethodRun run;
    run.family = "embree";
    run.grid = mesh.n;
    run.name = "embree-N" + std::to_string(mesh.n);

    EmbreeHandles h;
    h.device = rtcNewDevice("threads=1,set_affinity=0,verbose=0");
    if (!h.device) throw std::runtime_error("embree: rtcNewDevice failed");
    rtcSetDeviceMemoryMonitorFunction(h.device, monitor, nullptr);
    embree_bytes = 0;

    Stopwatch build;
    h.scene = rtcNewScene(h.device);
    rtcSetSceneFlags(h.scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geometry = rtcNewGeometry(h.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto *vertices = static_cast<float *>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertex_count()));
    auto *indices = static_cast<uint32_t *>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.triangle_count()));
    check_device(h.device, "buffer allocation");
    for (size_t k = 0; k < mesh.positions.size(); ++k) vertices[k] = float(mesh.positions[k]);
    std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(h.scene, geometry);
    rtcReleaseGeometry(geometry);
    const long long buffers = embree_bytes;
    rtcCommitScene(h.scene);
    check_device(h.device, "scene commit");
    run.build_seconds = build.cpu_seconds();
    run.array_bytes = size_t(buffers);
    run.structure_bytes = size_t(embree_bytes - buffers);
    std::fprintf(stderr, "%s: %zu triangles, built in %.3f ms\n", run.name.c_str(),
                 mesh.triangle_count(), 1e3 * run.build_seconds);

    for (const RaySet &set : sets) {
        std::fprintf(stderr, "%s: tracing %zu %s rays\n", run.name.c_str(), set.rays.size(),
                     set.name.c_str());
        run.traces.emplace_back();
        trace_set(h.scene, mesh, set, run.traces.back());
    }
    return run;
}

} // namespace bench
