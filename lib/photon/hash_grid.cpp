#include "photon/hash_grid.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace ppm {

std::uint64_t HitPointGrid::bucket(std::int64_t i, std::int64_t j, std::int64_t k) const {
    std::uint64_t h = static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull ^
                      static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4Full ^
                      static_cast<std::uint64_t>(k) * 0x165667B19E3779F9ull;
    h ^= h >> 29;
    return h & bucket_mask_;
}

// Cell coordinate of x along an axis, clamped to the grid. Points of the grid are inside it by
// construction; the clamp matters for query cubes reaching past the bounds.
std::int64_t HitPointGrid::cell(double x, int axis) const {
    const double t = std::floor((x - origin_[axis]) * inv_cell_);
    return static_cast<std::int64_t>(std::clamp(t, 0.0, static_cast<double>(cells_[axis] - 1)));
}

void HitPointGrid::build(const HitPoint *points, std::size_t count) {
    entries_.resize(count);
    index_.resize(count);
    max_r2_ = 0;
    if (count == 0) {
        bucket_start_.clear();
        return;
    }

    Box3 bounds;
    for (std::size_t i = 0; i < count; ++i) {
        bounds.extend(points[i].position);
        max_r2_ = std::max(max_r2_, points[i].r2);
    }
    // The query cube is padded beyond the largest radius to cover rounding: in distance2 (a
    // relative 1e-9 is ample) and in photon +- R (an ulp of the coordinates' magnitude). A
    // hit point at exactly its radius then always lies in a visited cell.
    const double magnitude = std::max(max_abs_component(bounds.lower), max_abs_component(bounds.upper));
    search_r_ = std::sqrt(max_r2_) * (1.0 + 1e-9) + 4.0 * DBL_EPSILON * magnitude;
    // Cells at least as wide as the search radius, so a query touches at most 3 per axis. The
    // floor relative to the extent keeps cell coordinates below 2^30 however small the radii.
    const double extent = max_abs_component(bounds.upper - bounds.lower);
    double width = std::max(search_r_, extent * 0x1p-30);
    if (!(width > 0)) width = 1; // all hit points at one position, with zero radii
    inv_cell_ = 1.0 / width;
    origin_ = bounds.lower;
    for (int a = 0; a < 3; ++a)
        cells_[a] = static_cast<std::int64_t>(std::floor((bounds.upper[a] - origin_[a]) * inv_cell_)) + 1;

    std::uint64_t buckets = 1;
    while (buckets < count) buckets <<= 1;
    bucket_mask_ = buckets - 1;

    // Counting sort by bucket. Filling from the back turns the running ends into starts and
    // keeps each bucket in increasing hit point order.
    std::vector<std::uint32_t> point_bucket(count);
    bucket_start_.assign(buckets + 1, 0);
    for (std::size_t i = 0; i < count; ++i) {
        const Vec3 &p = points[i].position;
        point_bucket[i] = static_cast<std::uint32_t>(bucket(cell(p.x, 0), cell(p.y, 1), cell(p.z, 2)));
        ++bucket_start_[point_bucket[i]];
    }
    for (std::uint64_t b = 1; b < buckets; ++b) bucket_start_[b] += bucket_start_[b - 1];
    bucket_start_[buckets] = static_cast<std::uint32_t>(count);
    for (std::size_t i = count; i-- > 0;) {
        const std::uint32_t e = --bucket_start_[point_bucket[i]];
        entries_[e] = {points[i].position, points[i].r2};
        index_[e] = static_cast<std::uint32_t>(i);
    }
}

void HitPointGrid::query(const Vec3 &photon, HitPointVisitor visit) const {
    if (entries_.empty() || !is_finite(photon)) return;
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        const double low = (photon[a] - search_r_ - origin_[a]) * inv_cell_;
        const double high = (photon[a] + search_r_ - origin_[a]) * inv_cell_;
        if (high < 0 || low >= static_cast<double>(cells_[a])) return; // cube misses the grid
        lo[a] = cell(photon[a] - search_r_, a);
        hi[a] = cell(photon[a] + search_r_, a);
    }
    // Distinct cells can share a bucket; visit each bucket once so no hit point is reported
    // twice. The cube spans at most 3 cells per axis (cells are as wide as search_r_).
    std::uint64_t seen[27];
    int seen_count = 0;
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
            for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
                const std::uint64_t b = bucket(i, j, k);
                if (std::find(seen, seen + seen_count, b) != seen + seen_count) continue;
                seen[seen_count++] = b;
                for (std::uint32_t e = bucket_start_[b], end = bucket_start_[b + 1]; e < end; ++e) {
                    const double dist2 = distance2(photon, entries_[e].position);
                    if (within_radius(dist2, entries_[e].r2)) visit(index_[e], dist2);
                }
            }
}

} // namespace ppm
