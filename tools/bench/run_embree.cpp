// SPDX-License-Identifier: Apache-2.0
// Embree 3 triangles: the mesh baseline as a renderer would use it.
#include "measure.h"
#include "method.h"
#include "tessellate.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bench {

namespace {

// Embree reports every allocation it makes (BVH nodes, buffers) to this monitor.
std::atomic<long long> embree_bytes{0};

bool monitor(void *, ssize_t bytes, bool) {
    embree_bytes += bytes;
    return true;
}

void check_device(RTCDevice device, const char *what) {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE)
        throw std::runtime_error(std::string("embree: ") + what + " failed (error " + std::to_string(int(error)) + ")");
}

class EmbreeMethod final : public Method {
public:
    explicit EmbreeMethod(std::shared_ptr<const Mesh> mesh) : mesh_(std::move(mesh)) {
        const bool uniform = mesh_->grid > 0;
        info_.name = "embree-" + mesh_->label;
        info_.family = uniform ? "embree-uniform" : "embree-adaptive";
        info_.parameter = uniform ? "grid" : "mesh_tolerance";
        info_.value = uniform ? mesh_->grid : mesh_->relative_tolerance;
        info_.primitives = mesh_->triangle_count();
        info_.tessellate_seconds = mesh_->seconds;
        info_.deviation = mesh_->deviation;
    }
    ~EmbreeMethod() override { release(); }

    const MethodInfo &info() const override { return info_; }

    BuildMemory build(int threads) override {
        release();
        const std::string config = "threads=" + std::to_string(threads) + ",set_affinity=0,verbose=0";
        device_ = rtcNewDevice(config.c_str());
        if (!device_) throw std::runtime_error("embree: rtcNewDevice failed");
        rtcSetDeviceMemoryMonitorFunction(device_, monitor, nullptr);
        embree_bytes = 0;

        scene_ = rtcNewScene(device_);
        rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
        RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto *vertices = static_cast<float *>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh_->vertex_count()));
        auto *indices = static_cast<uint32_t *>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh_->triangle_count()));
        check_device(device_, "buffer allocation");
        for (size_t k = 0; k < mesh_->positions.size(); ++k) vertices[k] = float(mesh_->positions[k]);
        std::copy(mesh_->indices.begin(), mesh_->indices.end(), indices);
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene_, geometry);
        rtcReleaseGeometry(geometry);
        const long long buffers = embree_bytes;
        rtcCommitScene(scene_);
        check_device(device_, "scene commit");
        BuildMemory m;
        m.array_bytes = size_t(buffers);
        m.structure_bytes = size_t(embree_bytes - buffers);
        return m;
    }

    void release() override {
        if (scene_) rtcReleaseScene(scene_);
        if (device_) rtcReleaseDevice(device_);
        scene_ = nullptr;
        device_ = nullptr;
    }

    void trace(const std::vector<ppm_ray> &rays, size_t begin, size_t end, Trace &out) const override {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (size_t i = begin; i < end; ++i) {
            const ppm_ray &ray = rays[i];
            RTCRayHit rh;
            rh.ray.org_x = float(ray.org[0]);
            rh.ray.org_y = float(ray.org[1]);
            rh.ray.org_z = float(ray.org[2]);
            rh.ray.dir_x = float(ray.dir[0]);
            rh.ray.dir_y = float(ray.dir[1]);
            rh.ray.dir_z = float(ray.dir[2]);
            rh.ray.tnear = float(ray.tnear);
            rh.ray.tfar = INFINITY;
            rh.ray.time = 0.0f;
            rh.ray.mask = 0xFFFFFFFFu; // masks are enabled in Debian's Embree build
            rh.ray.id = 0;
            rh.ray.flags = 0;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene_, &context, &rh);
            if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;

            out.t[i] = rh.ray.tfar;
            out.patch[i] = mesh_->triangle_patch[rh.hit.primID];
            const double n[3] = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
            const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int c = 0; c < 3; ++c) out.ng[3 * i + c] = l > 0 ? float(n[c] / l) : 0.0f;
            interpolate_normal(*mesh_, rh.hit.primID, rh.hit.u, rh.hit.v, &out.ns[3 * i]);
        }
    }

private:
    std::shared_ptr<const Mesh> mesh_;
    MethodInfo info_;
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
};

} // namespace

std::unique_ptr<Method> make_embree_method(std::shared_ptr<const Mesh> mesh) {
    return std::make_unique<EmbreeMethod>(std::move(mesh));
}

} // namespace bench
