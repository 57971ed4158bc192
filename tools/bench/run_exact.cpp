// SPDX-License-Identifier: Apache-2.0
// libppm's exact intersector, through the public C API only.
#include "common/handle.h"
#include "common/status.h"
#include "measure.h"
#include "method.h"
#include "ray_sets.h"

#include <ppm/ppm.h>

#include <algorithm>
#include <stdexcept>

namespace bench {

using ppm_tools::check_with_status;

namespace {

class ExactMethod final : public Method {
public:
    ExactMethod(const std::vector<double> &control_points, double tolerance, int presplit)
        : control_points_(control_points), presplit_(presplit) {
        if (presplit > 0) {
            info_.name = "exact-presplit-" + std::to_string(presplit);
            info_.family = "exact-presplit";
            info_.parameter = "presplit";
            info_.value = presplit;
        } else {
            info_.name = "exact-" + format_number(tolerance);
            info_.family = "exact";
            info_.parameter = "tolerance";
            info_.value = tolerance;
        }
        info_.primitives = control_points.size() / 48;
        info_.tolerance = tolerance;
        info_.spawn_tolerance = tolerance;
    }
    ~ExactMethod() override { release(); }

    const MethodInfo &info() const override { return info_; }
    bool threads_inside() const override { return true; }

    BuildMemory build(int threads) override {
        release();
        check_with_status(ppm_context_create(context_.out()), "ppm_context_create");
        // The context's Embree device and worker pool are not part of the structure.
        MemoryDelta memory;
        check_with_status(ppm_context_set_int(context_, "threads", threads), "ppm_context_set_int(threads)");
        check_with_status(ppm_scene_create(context_, scene_.out()), "ppm_scene_create");
        check_with_status(ppm_scene_set_double(scene_, "tolerance", info_.tolerance),
                          "ppm_scene_set_double(tolerance)");
        if (presplit_ > 0)
            check_with_status(ppm_scene_set_double(scene_, "patch_presplit", presplit_),
                              "ppm_scene_set_double(patch_presplit)");
        check_with_status(ppm_scene_add_bezier_patches(scene_, control_points_.data(), info_.primitives, nullptr),
                          "ppm_scene_add_bezier_patches");
        check_with_status(ppm_scene_commit(scene_), "ppm_scene_commit");
        BuildMemory m;
        m.structure_bytes = memory.take();
        m.array_bytes = control_points_.size() * sizeof(double);
        return m;
    }

    void release() override {
        scene_.reset();
        context_.reset();
    }

    void trace(const std::vector<ppm_ray> &rays, size_t begin, size_t end, Trace &out) const override {
        // Batches large enough for the library to spread over its workers, small enough to
        // stay in cache.
        constexpr size_t batch = 8192;
        std::vector<ppm_hit> hits(std::min(batch, end - begin));
        for (size_t first = begin; first < end; first += batch) {
            const size_t count = std::min(batch, end - first);
            check_with_status(ppm_scene_intersect(scene_, rays.data() + first, count, hits.data()),
                              "ppm_scene_intersect");
            for (size_t k = 0; k < count; ++k) {
                const ppm_hit &hit = hits[k];
                if (hit.geom_id == PPM_INVALID_ID) continue;
                const size_t i = first + k;
                out.t[i] = hit.t;
                out.patch[i] = hit.prim_id;
                for (int c = 0; c < 3; ++c) {
                    out.ng[3 * i + c] = float(hit.ng[c]);
                    out.ns[3 * i + c] = float(hit.ns[c]);
                }
            }
        }
    }

private:
    std::vector<double> control_points_;
    int presplit_; // 0: libppm's default
    MethodInfo info_;
    ppm_tools::Context context_;
    ppm_tools::Scene scene_;
};

} // namespace

void warm_up_library(const std::vector<double> &control_points) {
    ExactMethod method(control_points, 1e-9, 0);
    method.build(1);
    method.release();
}

std::unique_ptr<Method> make_exact_method(const std::vector<double> &control_points, double tolerance, int presplit) {
    return std::make_unique<ExactMethod>(control_points, tolerance, presplit);
}

} // namespace bench
