// SPDX-License-Identifier: Apache-2.0
// The photon density estimator of one pass: a hit point and a gather point per slot, a search
// structure over them (hashed grid or KD-tree), and the fixed-point flux accumulator that the
// photons landing within a hit point's radius add to. The camera paths store points, the
// photon tracer deposits photons, and the end of the pass takes each slot's photons into its
// statistics.
#pragma once

#include "core/context.h"
#include "film/slot_photons.h"
#include "integrator/visible_point.h"
#include "photon/hash_grid.h"
#include "photon/hit_point.h"
#include "photon/hit_point_tree.h"
#include "photon/sppm_statistics.h"
#include "settings/render_settings.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace ppm {

class DensityEstimator final : public SlotPhotons {
public:
    // Bytes per slot, for the allocation messages of the slots' owners.
    static constexpr std::uint64_t kSlotBytes = sizeof(HitPoint) + sizeof(GatherPoint) + 64;

    // `slots` absent hit points and zero flux, summed in quanta of flux_scale (FluxAccumulator).
    // Built aside and swapped in: a failed allocation leaves the estimator as it was.
    // full_lobes: room for a FullLobe per slot, which visible points on rough lobes need
    // (RenderScene::gathers_full_lobes).
    void reset(std::size_t slots, double flux_scale, bool full_lobes = false);
    std::size_t slots() const { return hit_points_.size(); }

    // The slot's hit point for this pass with squared radius r2 (absent unless vp.valid).
    // Thread-safe for distinct slots.
    void store(std::uint32_t slot, const VisiblePoint &vp, double r2);
    const HitPoint &hit_point(std::uint32_t slot) const override { return hit_points_[slot]; }

    // Builds the search over the stored points on the context's workers. `bounds`: the points'
    // bounds if the caller measured them while storing, else they are measured here.
    void build(Context &context, RenderSettings::Search search, const std::optional<HitPointBounds> &bounds);
    std::size_t present() const { return present_; }
    // Whether a photon at p can lie within any hit point's radius (the points' bounds, grown
    // by the largest radius): photons outside need not be kept.
    bool may_gather(const Vec3 &p) const;
    // The box may_gather() tests, for ordering photons along a space-filling curve.
    const Box3 &gather_bounds() const { return gather_bounds_; }

    // Adds the photon to every hit point within whose radius it lies, on its front side.
    // Thread-safe between builds.
    void deposit(const PhotonHit &photon);
    // The slot's photons of this pass, reset to none for the next one. Not during deposits.
    PassPhotons take(std::uint32_t slot) override { return flux_->take(slot); }
    void discard_photons(); // every slot's, for a cancelled pass

private:
    std::vector<HitPoint> hit_points_; // per slot: position and radius (absent: no point) ...
    std::vector<GatherPoint> gather_;  // ... and what deposit() needs of it
    std::vector<FullLobe> full_;       // ... and of a rough lobe (empty unless reset asked)
    std::unique_ptr<FluxAccumulator> flux_;
    RenderSettings::Search search_ = RenderSettings::Search::Grid;
    HitPointGrid grid_;
    HitPointTree tree_;
    std::size_t present_ = 0;
    Box3 gather_bounds_;
};

} // namespace ppm
