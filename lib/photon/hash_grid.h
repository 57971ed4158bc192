// SPDX-License-Identifier: Apache-2.0
// Hashed uniform grid over the hit points of one pass, with the same interface as
// HitPointTree; the renderer's hit_point_search setting picks one of them.
//
// Every hit point is listed in each cell its ball overlaps (pbrt-v3's SPPM grid), so a photon
// reads exactly one cell: the hit points that may contain it, and few others. That suits the
// photon pass, whose queries (millions) far outnumber the hit points' cell entries (a few per
// point): a KD-tree searches the ball of the LARGEST radius around every photon, which, with
// radii that differ across the image, reads many points no ball reaches.
//
// Cells are 12 mean radii wide (hash_grid.cpp says why; a little more along an axis, so that
// the faces of the hit points' box, where walls are, lie mid-cell), so a typical point is
// listed in 1 to 8 cells (fewer than 2 on average in the benchmark), and a ball spans at most
// 5 per axis.
// Cells are hashed into a power-of-two table; each bucket is a run of entries holding the
// point's index and a copy of its position and radius, so a photon tests the candidates of
// its bucket from one contiguous array (reading each point from the caller's array, in image
// order, missed the cache at nearly every candidate). Entries within a bucket are in no
// particular order (placed by several threads): callers must not depend on the visiting order
// (the renderer sums flux in fixed point).
#pragma once

#include "photon/hit_point.h"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace ppm {

class HitPointGrid {
public:
    // Rebuilds the grid over the present points of points[0, count), count < 2^32, on the
    // calling task arena's threads. Positions and radii are copied, so the array may change or
    // go away afterwards; visitors receive indices into it. Not thread-safe.
    void build(const HitPoint *points, std::size_t count);
    // The same with the points' bounds already measured (measure_hit_points()).
    void build(const HitPoint *points, std::size_t count, const HitPointBounds &bounds);

    std::size_t size() const { return size_; } // points given to build(), present or not
    double max_r2() const { return max_r2_; }
    // Hit point entries over all cells (a point is listed once per cell its ball overlaps).
    std::size_t cell_entries() const { return bucket_start_.empty() ? 0 : bucket_start_.back(); }

    // Calls visit(index, dist2) once for every hit point with distance2(photon, position)
    // <= its r2, in no particular order. Thread-safe between builds.
    void query(const Vec3 &photon, HitPointVisitor visit) const;
    template <class F> void query(const Vec3 &photon, F &&visit) const { query(photon, HitPointVisitor::of(visit)); }

private:
    struct CellRange {
        std::int64_t lo[3], hi[3];
    };

    // One bucket's entries in a chunk of points during the build.
    struct BucketRun {
        std::uint64_t bucket;
        std::uint32_t count; // entries
        std::uint32_t next;  // where the next one goes in entries_
    };
    // Scratch of one chunk of points, kept between builds so its memory is reused.
    struct Chunk {
        std::vector<std::uint64_t> entries; // run index << 32 | point index
        std::vector<BucketRun> runs;
        std::vector<std::uint32_t> table; // open addressing: bucket -> run index
    };
    void list_chunk(const HitPoint *points, std::size_t begin, std::size_t end, Chunk &chunk) const;

    std::uint64_t bucket(std::int64_t i, std::int64_t j, std::int64_t k) const;
    std::int64_t cell(double x, int axis) const;
    CellRange cells_of(const HitPoint &p) const;
    // Calls f(bucket) once for each distinct bucket of the cells the point's ball overlaps.
    template <class F> void for_each_bucket(const HitPoint &p, F &&f) const;

    std::size_t size_ = 0;
    // A point listed in a cell: its copy and its index in the caller's array.
    // Plain doubles: `new Entry[n]` then leaves the memory as it is (a Vec3 would be zeroed).
    struct Entry {
        double position[3];
        double r2;
        std::uint32_t index;
    };
    std::unique_ptr<Entry[]> entries_; // bucket by bucket (stale beyond the last bucket's end)
    std::size_t entries_capacity_ = 0;
    std::vector<std::uint32_t> bucket_start_; // bucket b lists entries_[start[b], start[b+1]); empty: no point
    std::uint64_t bucket_mask_ = 0;
    Vec3 origin_;                       // lower corner of the balls' bounds
    double inv_cell_[3] = {0, 0, 0};    // 1 / cell width per axis
    std::int64_t cells_[3] = {0, 0, 0}; // cells per axis
    double max_r2_ = 0;
    double pad_ = 0; // added to every radius against rounding
    // Build scratch, reused: per-chunk entry lists and the buckets' counters.
    std::vector<Chunk> chunks_;
    std::unique_ptr<std::atomic<std::uint32_t>[]> cursor_;
    std::uint64_t cursor_capacity_ = 0;
};

} // namespace ppm
