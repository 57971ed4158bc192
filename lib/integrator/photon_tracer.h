// SPDX-License-Identifier: Apache-2.0
// Photon paths: emitted by lights in proportion to power, scattered with the adjoint BSDFs
// and Russian roulette. Where a photon may be gathered it is buffered; each batch of photons
// is then sorted along a Morton curve and deposited in the density estimator in that order,
// so consecutive searches touch the same hit points (gathering in path order missed the cache
// at nearly every photon). Batches keep the buffers' size independent of photons_per_pass.
#pragma once

#include "integrator/density_estimator.h"
#include "integrator/visible_point.h"
#include "settings/render_settings.h"
#include "shading/render_scene.h"

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <cstdint>
#include <vector>

namespace ppm {

class PhotonTracer {
public:
    // Traces settings.photons_per_pass photon paths of `pass` on the context's workers and
    // deposits them in `estimator` (built for this pass). Stops early, leaving a partial sum
    // to be discarded, once `cancel` is set.
    void trace_pass(Context &context, const RenderScene &scene, const RenderSettings &settings, std::uint32_t pass,
                    DensityEstimator &estimator, const std::atomic<bool> &cancel);

private:
    // One photon path; appends where it may be gathered to `hits`.
    static void trace_photon(const RenderScene &scene, const RenderSettings &settings,
                             const DensityEstimator &estimator, std::uint64_t index, std::uint32_t pass,
                             std::vector<PhotonHit> &hits);
    // Deposits the threads' buffered photons in Morton order and empties the buffers.
    void gather_sorted(DensityEstimator &estimator, const std::atomic<bool> &cancel);

    // Per-thread buffers of the photons that landed, then one sorted list.
    tbb::enumerable_thread_specific<std::vector<PhotonHit>> thread_hits_;
    std::vector<std::vector<PhotonHit> *> batch_parts_; // the non-empty thread buffers ...
    std::vector<std::size_t> batch_part_starts_;        // ... and the index of each one's first photon
    std::vector<std::uint64_t> batch_order_;            // Morton key << index bits | index
};

} // namespace ppm
