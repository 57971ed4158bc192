// Hashed uniform grid over the hit points of one pass: the alternative to HitPointTree, with
// the same interface, kept for the benchmark that chooses between them.
//
// Cells are cubes as wide as the largest radius, so every hit point containing a photon lies
// in a cell touched by the cube [photon - R, photon + R]: at most 3 cells per axis, usually 2
// (8 cells rather than the classic 3x3x3). Cells are hashed into a power-of-two table of one
// to two buckets per hit point; the hit points are stored sorted by bucket (a counting sort),
// packed with their radii, so a query reads a few short contiguous runs.
#pragma once

#include "photon/hit_point.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace ppm {

class HitPointGrid {
public:
    // Rebuilds the grid over points[0, count), count < 2^32. Positions and radii are copied,
    // so the array may change or go away afterwards; visitors receive indices into it. Not
    // thread-safe.
    void build(const HitPoint *points, std::size_t count);

    std::size_t size() const { return index_.size(); }
    double max_r2() const { return max_r2_; }

    // Calls visit(index, dist2) once for every hit point with distance2(photon, position)
    // <= its r2, in no particular order. Thread-safe between builds.
    void query(const Vec3 &photon, HitPointVisitor visit) const;
    template <class F>
    void query(const Vec3 &photon, F &&visit) const {
        query(photon, HitPointVisitor::of(visit));
    }

private:
    struct Entry {
        Vec3 position;
        double r2;
    };

    std::uint64_t bucket(std::int64_t i, std::int64_t j, std::int64_t k) const;
    std::int64_t cell(double x, int axis) const;

    std::vector<Entry> entries_;            // sorted by bucket
    std::vector<std::uint32_t> index_;      // entries_[e] is hit point index_[e]
    std::vector<std::uint32_t> bucket_start_; // bucket b holds entries [start[b], start[b+1])
    std::uint64_t bucket_mask_ = 0;
    Vec3 origin_;                           // lower corner of the hit points' bounds
    double inv_cell_ = 0;
    std::int64_t cells_[3] = {0, 0, 0};     // cells per axis
    double max_r2_ = 0;
    double search_r_ = 0;
};

} // namespace ppm
