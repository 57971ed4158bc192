// SPDX-License-Identifier: Apache-2.0
// KD-tree over the hit points of one pass, answering "which hit points contain this photon?".
// nanoflann 1.4.3 builds and walks the tree; this header keeps it out of the rest of the
// library (it is a large header, and its pre-1.5 API differs from later releases). Large sets
// are cut into up to 8 parts by median planes, one nanoflann tree each, built in parallel on
// the calling task arena's threads.
//
// Each hit point has its own radius, so a query searches the ball of the LARGEST radius and
// then keeps the hit points whose own r2 contains the photon. Hit points are found through a
// result set that calls the visitor directly: a query allocates nothing.
#pragma once

#include "photon/hit_point.h"

#include <cstddef>
#include <memory>

namespace ppm {

class HitPointTree {
public:
    HitPointTree();
    ~HitPointTree();
    HitPointTree(HitPointTree &&) noexcept;
    HitPointTree &operator=(HitPointTree &&) noexcept;

    // Rebuilds the tree over the present points of points[0, count), count < 2^32. Positions
    // and radii are copied, so the array may change or go away afterwards; visitors receive
    // indices into it. Not thread-safe.
    void build(const HitPoint *points, std::size_t count);

    std::size_t size() const;
    double max_r2() const;

    // Calls visit(index, dist2) once for every hit point with distance2(photon, position)
    // <= its r2, in no particular order. Thread-safe between builds.
    void query(const Vec3 &photon, HitPointVisitor visit) const;
    template <class F> void query(const Vec3 &photon, F &&visit) const { query(photon, HitPointVisitor::of(visit)); }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace ppm
