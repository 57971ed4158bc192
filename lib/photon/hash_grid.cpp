// SPDX-License-Identifier: Apache-2.0
#include "photon/hash_grid.h"

#include "core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <string>

namespace ppm {

namespace {

// A ball overlaps at most this many cells per axis (cells are at least half as wide as the
// largest padded radius), so at most kMaxAcross^3 in all.
constexpr int kMaxAcross = 5;
// The typical radius is the mean over an evenly spaced sample of this many hit points.
constexpr std::size_t kRadiusSamples = 4096;
// Cells are this many typical radii wide. Wide cells list each hit point in fewer cells (a
// cheaper build) and a photon reads more candidates, but they are contiguous: the balance
// was measured (docs/bench/code-history.md).
constexpr double kCellWidthInRadii = 12;
// The build lists entries and claims room in buckets by chunks of this many points.
constexpr std::size_t kChunkPoints = 4096;

} // namespace

// Blocks of 4 x 4 x 4 cells are hashed; the 64 cells of a block take 64 consecutive buckets.
// Neighbouring cells then share cache lines of the tables, so a build that walks the hit
// points in image order, and a photon pass in Morton order, mostly hit the cache (a hash per
// cell misses the cache at nearly every entry).
std::uint64_t HitPointGrid::bucket(std::int64_t i, std::int64_t j, std::int64_t k) const {
    const auto bi = static_cast<std::uint64_t>(i), bj = static_cast<std::uint64_t>(j),
               bk = static_cast<std::uint64_t>(k);
    std::uint64_t h =
        (bi >> 2) * 0x9E3779B97F4A7C15ull ^ (bj >> 2) * 0xC2B2AE3D27D4EB4Full ^ (bk >> 2) * 0x165667B19E3779F9ull;
    h ^= h >> 29;
    return (h << 6 | (bi & 3) << 4 | (bj & 3) << 2 | (bk & 3)) & bucket_mask_;
}

// Inlined, as are cells_of and for_each_bucket: the listing calls them per point, and out of
// line their ranges would be read back from memory.
// Cell coordinate of x along an axis, clamped to the grid (the balls lie inside it by
// construction; the clamp only guards against rounding at its faces).
[[gnu::always_inline]] inline std::int64_t HitPointGrid::cell(double x, int axis) const {
    const double t = std::floor((x - origin_[axis]) * inv_cell_[axis]);
    return static_cast<std::int64_t>(std::clamp(t, 0.0, static_cast<double>(cells_[axis] - 1)));
}

// The cells overlapped by the cube around the point's ball, its radius padded so that a
// photon the final test accepts (computed dist2 <= r2) always lies in one of them.
[[gnu::always_inline]] inline HitPointGrid::CellRange HitPointGrid::cells_of(const HitPoint &p) const {
    const double r = std::sqrt(p.r2) * (1.0 + 1e-9) + pad_;
    CellRange range;
    for (int a = 0; a < 3; ++a) {
        range.lo[a] = cell(p.position[a] - r, a);
        range.hi[a] = cell(p.position[a] + r, a);
    }
    return range;
}

template <class F> [[gnu::always_inline]] inline void HitPointGrid::for_each_bucket(const HitPoint &p, F &&f) const {
    const CellRange range = cells_of(p);
    // Most balls lie within one cell (cells are many radii wide).
    if (range.lo[0] == range.hi[0] && range.lo[1] == range.hi[1] && range.lo[2] == range.hi[2]) {
        f(bucket(range.lo[0], range.lo[1], range.lo[2]));
        return;
    }
    // Distinct cells may share a bucket; a point is listed there once, or a photon would
    // count it twice.
    // One more per axis than the widths allow, should rounding stretch a range by a cell.
    std::uint64_t seen[(kMaxAcross + 1) * (kMaxAcross + 1) * (kMaxAcross + 1)];
    int seen_count = 0;
    for (std::int64_t i = range.lo[0]; i <= range.hi[0]; ++i)
        for (std::int64_t j = range.lo[1]; j <= range.hi[1]; ++j)
            for (std::int64_t k = range.lo[2]; k <= range.hi[2]; ++k) {
                const std::uint64_t b = bucket(i, j, k);
                if (std::find(seen, seen + seen_count, b) != seen + seen_count) continue;
                seen[seen_count++] = b;
                f(b);
            }
}

void HitPointGrid::build(const HitPoint *points, std::size_t count) {
    build(points, count, measure_hit_points(points, count));
}

void HitPointGrid::build(const HitPoint *points, std::size_t count, const HitPointBounds &bounds) {
    // Empty until built: a build that throws leaves a grid that finds nothing.
    size_ = 0;
    bucket_start_.clear();
    max_r2_ = 0;
    if (count == 0) return;
    if (count > UINT32_MAX)
        fail(PPM_ERROR_OUT_OF_MEMORY, "the hit point grid takes at most 2^32 - 1 points, not " + std::to_string(count));
    size_ = count;

    max_r2_ = bounds.max_r2;
    if (bounds.box.empty()) return; // every point absent

    // Rounding: cells_of() pads each radius by a relative 1e-9 (for the rounding of dist2)
    // and by a few ulps of the coordinates' magnitude (for p +- r).
    const double magnitude = std::max(max_abs_component(bounds.box.lower), max_abs_component(bounds.box.upper));
    // The floor covers photons whose dist2 underflows to 0 (differences below ~1e-162).
    pad_ = std::max(4.0 * DBL_EPSILON * magnitude, 0x1p-530);
    const double max_r = std::sqrt(max_r2_) * (1.0 + 1e-9) + pad_;
    const std::size_t step = std::max<std::size_t>(1, count / kRadiusSamples);
    double sum_r = 0;
    std::size_t samples = 0;
    for (std::size_t i = 0; i < count; i += step)
        if (points[i].present()) {
            sum_r += std::sqrt(points[i].r2);
            ++samples;
        }
    if (samples == 0) samples = 1; // the sample missed the few present points: width from max_r
    // Cells several typical radii wide, but never so narrow that a ball spans more than
    // kMaxAcross cells per axis, nor so narrow that cell coordinates pass 2^30.
    const Vec3 lower = bounds.box.lower - Vec3{max_r, max_r, max_r};
    const Vec3 upper = bounds.box.upper + Vec3{max_r, max_r, max_r};
    const double extent = max_abs_component(upper - lower);
    if (!std::isfinite(extent)) {
        size_ = 0;
        invalid_argument("hit point coordinates or radii too large for the grid (extent " + std::to_string(extent) +
                         ")");
    }
    // The largest ball spans 4 widths, a hair less with the margin, so rounding cannot push it
    // over 5 cells; the last floor keeps 1 / width finite.
    const double width = std::max(
        {kCellWidthInRadii * sum_r / samples, 2.0 * max_r / (kMaxAcross - 1) * (1 + 1e-6), extent * 0x1p-30, 0x1p-500});
    // Hit points crowd on walls, and the walls bounding a scene are the faces of the points'
    // box. A face lying near a cell face would put every ball on that wall into two cells. So
    // each axis gets its own width, at least `width`, fitting a whole number of cells between
    // the box's two faces, which then lie in the middle of cells.
    for (int a = 0; a < 3; ++a) {
        const double span = bounds.box.upper[a] - bounds.box.lower[a];
        const double across = std::floor(span / width);
        const double axis_width = across >= 1 ? span / across : width;
        // Half a cell beyond the lower face, then whole cells until the padded box is inside.
        const double below = (std::ceil(max_r / axis_width) + 0.5) * axis_width;
        inv_cell_[a] = 1.0 / axis_width;
        origin_[a] = std::min(bounds.box.lower[a] - below, lower[a]);
        cells_[a] = static_cast<std::int64_t>(std::floor((upper[a] - origin_[a]) * inv_cell_[a])) + 1;
    }

    // A bucket per 4 points: cells 12 radii wide hold many points each (a radius spans a pixel
    // or more), so occupied cells stay well below the buckets even as radii shrink, while the
    // build's counters, zeroing and serial prefix sum cost a quarter of a bucket per point's.
    std::uint64_t buckets = 1;
    while (buckets < count / 4 || buckets < 64) buckets <<= 1;
    bucket_mask_ = buckets - 1;

    // Each chunk of points lists its entries once, grouped by bucket locally, so that a
    // bucket's count and its room are claimed with one atomic per chunk, not per entry (a
    // locked add per entry waited for every scattered store before it). Entries are placed in
    // an order that depends on scheduling.
    const std::size_t chunk_count = (count + kChunkPoints - 1) / kChunkPoints;
    if (chunks_.size() < chunk_count) chunks_.resize(chunk_count);
    if (cursor_capacity_ < buckets) {
        cursor_.reset(new std::atomic<std::uint32_t>[buckets]);
        cursor_capacity_ = buckets;
    }
    std::atomic<std::uint32_t> *const cursor = cursor_.get();
    tbb::parallel_for(std::uint64_t(0), buckets, std::uint64_t(65536), [&](std::uint64_t begin) {
        for (std::uint64_t b = begin, end = std::min(buckets, begin + 65536); b < end; ++b)
            cursor[b].store(0, std::memory_order_relaxed);
    });
    tbb::parallel_for(std::size_t(0), chunk_count, [&](std::size_t c) {
        Chunk &chunk = chunks_[c];
        list_chunk(points, c * kChunkPoints, std::min(count, (c + 1) * kChunkPoints), chunk);
        for (const BucketRun &run : chunk.runs) cursor[run.bucket].fetch_add(run.count, std::memory_order_relaxed);
    });
    bucket_start_.resize(buckets + 1);
    std::uint64_t total = 0;
    for (std::uint64_t b = 0; b < buckets; ++b) {
        bucket_start_[b] = static_cast<std::uint32_t>(total); // checked below: total < 2^32
        total += cursor[b].load(std::memory_order_relaxed);
        cursor[b].store(bucket_start_[b], std::memory_order_relaxed);
    }
    if (total > UINT32_MAX) {
        size_ = 0;
        bucket_start_.clear();
        fail(PPM_ERROR_OUT_OF_MEMORY,
             "the hit point grid would need " + std::to_string(total) + " cell entries, more than 2^32");
    }
    bucket_start_[buckets] = static_cast<std::uint32_t>(total);
    // Kept between builds, replaced (not copied: the old entries are stale) when too small,
    // and never filled with defaults: a vector's resize would copy and zero the whole table
    // (tens of MB) on one thread. An eighth more than asked: the count varies by a few
    // thousand between passes, and a new buffer's first touch costs a build about its time
    // again. Entries past `total` are stale and never read.
    if (entries_capacity_ < total) {
        entries_.reset(); // first: the old and the new buffer are never held at once
        entries_capacity_ = 0;
        const std::uint64_t capacity = total + total / 8;
        allocate_or_fail("the hit point grid's " + std::to_string(capacity) + " cell entries", capacity * sizeof(Entry),
                         [&] {
                             try {
                                 entries_.reset(new Entry[capacity]);
                             } catch (...) {
                                 size_ = 0; // empty, as the build promises when it throws
                                 bucket_start_.clear();
                                 throw;
                             }
                         });
        entries_capacity_ = capacity;
    }
    tbb::parallel_for(std::size_t(0), chunk_count, [&](std::size_t c) {
        Chunk &chunk = chunks_[c];
        for (BucketRun &run : chunk.runs) run.next = cursor[run.bucket].fetch_add(run.count, std::memory_order_relaxed);
        for (const std::uint64_t entry : chunk.entries) {
            const auto point = static_cast<std::uint32_t>(entry);
            const Vec3 &p = points[point].position;
            entries_[chunk.runs[entry >> 32].next++] = {{p.x, p.y, p.z}, points[point].r2, point};
        }
    });
}

// Lists the entries of points [begin, end) as (run << 32 | point), a run being one bucket's
// entries in the chunk, found through a small open-addressing table of the chunk's buckets.
void HitPointGrid::list_chunk(const HitPoint *points, std::size_t begin, std::size_t end, Chunk &chunk) const {
    chunk.entries.clear();
    chunk.runs.clear();
    for (std::size_t i = begin; i < end; ++i)
        if (points[i].present())
            for_each_bucket(points[i], [&](std::uint64_t b) { chunk.entries.push_back(b << 32 | i); });
    std::size_t slots = 16;
    while (slots < 2 * chunk.entries.size()) slots <<= 1;
    chunk.table.assign(slots, UINT32_MAX);
    for (std::uint64_t &entry : chunk.entries) {
        const std::uint64_t b = entry >> 32;
        std::size_t slot = (b * 0x9E3779B97F4A7C15ull) >> 40 & (slots - 1);
        while (chunk.table[slot] != UINT32_MAX && chunk.runs[chunk.table[slot]].bucket != b)
            slot = (slot + 1) & (slots - 1);
        if (chunk.table[slot] == UINT32_MAX) {
            chunk.table[slot] = static_cast<std::uint32_t>(chunk.runs.size());
            chunk.runs.push_back({b, 0, 0});
        }
        ++chunk.runs[chunk.table[slot]].count;
        entry = static_cast<std::uint64_t>(chunk.table[slot]) << 32 | (entry & 0xFFFFFFFFu);
    }
}

void HitPointGrid::query(const Vec3 &photon, HitPointVisitor visit) const {
    if (bucket_start_.empty()) return;
    std::int64_t c[3];
    for (int a = 0; a < 3; ++a) {
        const double t = std::floor((photon[a] - origin_[a]) * inv_cell_[a]);
        if (!(t >= 0 && t < static_cast<double>(cells_[a]))) return; // outside every ball (or NaN)
        c[a] = static_cast<std::int64_t>(t);
    }
    const std::uint64_t b = bucket(c[0], c[1], c[2]);
    for (std::uint32_t e = bucket_start_[b], end = bucket_start_[b + 1]; e < end; ++e) {
        const Entry &entry = entries_[e];
        const double dist2 = distance2(photon, Vec3{entry.position[0], entry.position[1], entry.position[2]});
        if (within_radius(dist2, entry.r2)) visit(entry.index, dist2);
    }
}

} // namespace ppm
