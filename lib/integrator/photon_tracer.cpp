// SPDX-License-Identifier: Apache-2.0
#include "integrator/photon_tracer.h"

#include "photon/random.h"

#include "scene/scene.h"
#include "scene/spawn.h"
#include "shading/shading_normals.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>

namespace ppm {

namespace {

constexpr std::uint8_t kPhotonStream = 1;
constexpr std::uint64_t kBatchPhotons = std::uint64_t(1) << 18;
constexpr std::size_t kPrefetchAhead = 8;

// Spreads the low 21 bits of v to every third bit.
std::uint64_t spread_bits(std::uint64_t v) {
    v &= 0x1FFFFF;
    v = (v | v << 32) & 0x1F00000000FFFFull;
    v = (v | v << 16) & 0x1F0000FF0000FFull;
    v = (v | v << 8) & 0x100F00F00F00F00Full;
    v = (v | v << 4) & 0x10C30C30C30C30C3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

// Morton code of p in the box with `bits` (<= 21) bits per axis.
std::uint64_t morton_key(const Vec3 &p, const Box3 &box, int bits) {
    const double cells = static_cast<double>((std::uint64_t(1) << bits) - 1);
    std::uint64_t key = 0;
    for (int a = 0; a < 3; ++a) {
        const double extent = box.upper[a] - box.lower[a];
        const double t = extent > 0 ? (p[a] - box.lower[a]) / extent : 0.0;
        const auto q = static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * cells);
        key |= spread_bits(q) << a;
    }
    return key;
}

} // namespace

void PhotonTracer::trace_photon(const RenderScene &scene, const RenderSettings &settings,
                                const DensityEstimator &estimator, std::uint64_t index, std::uint32_t pass,
                                std::vector<PhotonHit> &hits) {
    CounterRng rng(settings.seed, kPhotonStream, pass, index);
    double light_probability = 0;
    const Light &light = scene.lights()[scene.pick_light(rng.uniform(), &light_probability)];
    const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform(), u4 = rng.uniform();
    const EmittedPhoton emitted = light.emit(u1, u2, u3, u4);
    Rgb flux = emitted.flux / light_probability;
    if (flux.is_black()) return;
    ppm_ray ray;
    emitted.origin.store(ray.org);
    emitted.direction.store(ray.dir);
    ray.tnear = 0;
    ray.tfar = INFINITY;
    SurfacePoint sp;
    const ppm_hit *leaving = nullptr; // photons start at a light, not at a hit
    for (int depth = 0; depth < settings.max_depth; ++depth) {
        if (!scene.intersect(ray, sp, leaving, &rng)) return;
        const Vec3 direction = Vec3::from(ray.dir);
        // Depth 0 is direct light, which the eye pass estimates by itself (unless told not to).
        if ((depth > 0 || !settings.direct_lighting) && sp.bsdf.gathers(settings.glossy_gather_alpha) &&
            estimator.may_gather(sp.p))
            hits.push_back({sp.p, direction, flux, static_cast<float>(std::fabs(dot(direction, sp.ng)))});
        const double u_lobe = rng.uniform(), v1 = rng.uniform(), v2 = rng.uniform();
        const BsdfSample s = sp.bsdf.sample(sp.wo_local, u_lobe, v1, v2, TransportMode::Importance);
        if (!s.valid()) return;
        const Rgb scattered = flux * s.weight * light_path_shading_correction(sp, sp.wo_local, s.wi);
        // Russian roulette on the throughput's drop (pbrt-v3 SPPM): paths that lose power
        // end more often and survivors carry the difference, so the estimate stays unbiased.
        const double survive = std::min(1.0, scattered.max() / flux.max());
        if (!(survive > 0) || rng.uniform() >= survive) return;
        flux = scattered / survive;
        ray = spawn_ray(sp.hit, sp.frame.to_world(s.wi));
        leaving = &sp.hit;
    }
}

void PhotonTracer::gather_sorted(DensityEstimator &estimator, const std::atomic<bool> &cancel) {
    // The photons stay in the threads' buffers and an index runs through them in turn. Kept
    // because it pays: one copied list would raise ppm-bench render's peak memory by about
    // 20 % at 1M photons per pass (docs/bench/code-history.md).
    batch_parts_.clear();
    batch_part_starts_.clear();
    std::size_t total = 0;
    for (std::vector<PhotonHit> &hits : thread_hits_) {
        if (hits.empty()) continue;
        batch_parts_.push_back(&hits);
        batch_part_starts_.push_back(total);
        total += hits.size();
    }
    const auto photon_at = [&](std::size_t index) -> const PhotonHit & {
        const std::size_t part = std::upper_bound(batch_part_starts_.begin(), batch_part_starts_.end(), index) -
                                 batch_part_starts_.begin() - 1;
        return (*batch_parts_[part])[index - batch_part_starts_[part]];
    };
    // One 64-bit word per photon, its Morton code above its index: plain integers sort faster
    // than pairs. Up to 21 bits per axis: a coarser code orders the searches less closely.
    // The deposits' order does not change the image: flux is summed in fixed point.
    int index_bits = 1;
    while ((std::uint64_t(1) << index_bits) < total) ++index_bits;
    const int axis_bits = std::min(21, (64 - index_bits) / 3);
    batch_order_.resize(total);
    for (std::size_t part = 0; part < batch_parts_.size(); ++part) {
        const std::vector<PhotonHit> &hits = *batch_parts_[part];
        const std::size_t first = batch_part_starts_[part];
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, hits.size(), 4096), [&](const auto &range) {
            for (std::size_t i = range.begin(); i < range.end(); ++i)
                batch_order_[first + i] =
                    morton_key(hits[i].position, estimator.gather_bounds(), axis_bits) << index_bits | (first + i);
        });
    }
    tbb::parallel_sort(batch_order_.begin(), batch_order_.end());
    const std::uint64_t index_mask = (std::uint64_t(1) << index_bits) - 1;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, batch_order_.size(), 1024), [&](const auto &range) {
        if (cancel.load(std::memory_order_relaxed)) return;
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
            // The photons lie in path order, so their records are read at random: fetch
            // a few ahead, or each search waits for its photon.
            if (i + kPrefetchAhead < range.end())
                __builtin_prefetch(&photon_at(batch_order_[i + kPrefetchAhead] & index_mask));
            estimator.deposit(photon_at(batch_order_[i] & index_mask));
        }
    });
    for (std::vector<PhotonHit> *hits : batch_parts_) hits->clear();
}

void PhotonTracer::trace_pass(Context &context, const RenderScene &scene, const RenderSettings &settings,
                              std::uint32_t pass, DensityEstimator &estimator, const std::atomic<bool> &cancel) {
    if (scene.lights().empty() || scene.total_power().is_black() || estimator.present() == 0) return;
    const auto cancelled = [&] { return cancel.load(std::memory_order_relaxed); };
    const std::uint64_t count = settings.photons_per_pass;
    context.run([&] {
        for (std::uint64_t begin = 0; begin < count && !cancelled(); begin += kBatchPhotons) {
            const std::uint64_t end = std::min(count, begin + kBatchPhotons);
            tbb::parallel_for(tbb::blocked_range<std::uint64_t>(begin, end, 1024), [&](const auto &range) {
                if (cancelled()) return;
                std::vector<PhotonHit> &hits = thread_hits_.local();
                for (std::uint64_t i = range.begin(); i < range.end(); ++i)
                    trace_photon(scene, settings, estimator, i, pass, hits);
            });
            gather_sorted(estimator, cancel);
        }
    });
}

} // namespace ppm
