// SPDX-License-Identifier: Apache-2.0
#include "integrator/density_estimator.h"

#include "core/error.h"
#include "shading/shading_normals.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

namespace ppm {

void DensityEstimator::reset(std::size_t slots, double flux_scale, bool full_lobes) {
    // The largest arrays first, so that a film too large fails before any memory is filled.
    std::vector<FullLobe> full(full_lobes ? slots : 0);
    auto flux = std::make_unique<FluxAccumulator>(slots, flux_scale);
    std::vector<GatherPoint> gather(slots);
    std::vector<HitPoint> hit_points(slots, HitPoint{});
    flux_ = std::move(flux);
    gather_ = std::move(gather);
    full_ = std::move(full);
    hit_points_ = std::move(hit_points);
    present_ = 0;
}

void DensityEstimator::store(std::uint32_t slot, const VisiblePoint &vp, double r2) {
    if (!vp.valid) {
        hit_points_[slot] = HitPoint{};
        return;
    }
    hit_points_[slot] = {vp.p, r2};
    const double side = vp.wo_local.z >= 0 ? 1.0 : -1.0;
    const Vec3 shading_normal = vp.frame.n * side;
    GatherPoint &g = gather_[slot];
    // A shading normal that is the geometric one up to rounding is stored as that one, so that
    // shading_is_geometric() holds for it and no correction is made (shading/shading_normals.h).
    const bool same = std::fabs(dot(vp.frame.n, vp.normal)) >= 1.0 - kShadingNormalTolerance;
    for (int a = 0; a < 3; ++a) {
        g.normal[a] = static_cast<float>(vp.normal[a]);
        g.shading_normal[a] = same ? g.normal[a] : static_cast<float>(shading_normal[a]);
    }
    g.lobe = vp.bsdf.fixed_wo(vp.wo_local, vp.weight);
    if (g.lobe.needs_full_eval()) {
        if (slot >= full_.size()) fail(PPM_ERROR_INTERNAL, "a rough visible point without room for its lobe");
        full_[slot] = {vp.frame, vp.wo_local, vp.bsdf};
    }
}

void DensityEstimator::build(Context &context, RenderSettings::Search search,
                             const std::optional<HitPointBounds> &measured) {
    search_ = search;
    HitPointBounds bounds;
    context.run([&] { bounds = measured ? *measured : measure_hit_points(hit_points_.data(), hit_points_.size()); });
    present_ = bounds.present;
    gather_bounds_ = bounds.box;
    const double pad = std::sqrt(bounds.max_r2) * (1 + 1e-9) + 1e-12 * gather_bounds_.diagonal();
    gather_bounds_.lower -= Vec3{pad, pad, pad};
    gather_bounds_.upper += Vec3{pad, pad, pad};
    // In the context's arena: the structures build on the context's workers.
    context.run([&] {
        if (search_ == RenderSettings::Search::Grid)
            grid_.build(hit_points_.data(), hit_points_.size(), bounds);
        else
            tree_.build(hit_points_.data(), hit_points_.size());
    });
}

bool DensityEstimator::may_gather(const Vec3 &p) const {
    const Box3 &box = gather_bounds_;
    return p.x >= box.lower.x && p.x <= box.upper.x && p.y >= box.lower.y && p.y <= box.upper.y && p.z >= box.lower.z &&
           p.z <= box.upper.z;
}

void DensityEstimator::deposit(const PhotonHit &photon) {
    const auto visit = [&](std::uint32_t index, double) {
        const GatherPoint &g = gather_[index];
        // A photon arriving from behind the visible point's surface (the far side of a thin
        // wall, the inside of a closed object) does not light it.
        const double cos_geometric = -GatherPoint::dot(g.normal, photon.direction);
        if (!(cos_geometric > 0)) return;
        // Flux per geometric area where the photon landed, read with the shading normal's
        // cosine where the visible point has one (shading/shading_normals.h).
        const double cos_shading = -GatherPoint::dot(g.shading_normal, photon.direction);
        const double shading_factor = GatherPoint::shading_is_geometric(g) ? 1.0
                                      : photon.cos_landing > 0             ? std::fabs(cos_shading) / photon.cos_landing
                                                                           : 0.0;
        if (g.lobe.needs_full_eval()) {
            // A rough lobe: the whole BSDF at the photon's direction, wi = -direction.
            const FullLobe &f = full_[index];
            flux_->add(index, photon.flux * g.lobe.weight() *
                                  f.bsdf.eval(f.wo_local, f.frame.to_local(-photon.direction)) * shading_factor);
            return;
        }
        flux_->add(index, photon.flux * g.lobe.at(cos_shading) * shading_factor);
    };
    if (search_ == RenderSettings::Search::Grid)
        grid_.query(photon.position, visit);
    else
        tree_.query(photon.position, visit);
}

void DensityEstimator::discard_photons() {
    for (std::size_t slot = 0; slot < hit_points_.size(); ++slot) flux_->take(slot);
}

} // namespace ppm
