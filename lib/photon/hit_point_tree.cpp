// SPDX-License-Identifier: Apache-2.0
#include "photon/hit_point_tree.h"

#include <nanoflann.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace ppm {

namespace {

// Position, radius and the caller's index, packed: leaves read these.
struct Entry {
    double p[3];
    double r2;
    std::uint32_t index; // into the array the tree was built from
};

// nanoflann's dataset interface over a run of packed entries (a part's).
struct EntryCloud {
    const Entry *entries = nullptr;
    std::size_t count = 0;

    std::size_t kdtree_get_point_count() const { return count; }
    double kdtree_get_pt(std::uint32_t i, std::size_t dim) const { return entries[i].p[dim]; }
    template <class BBox> bool kdtree_get_bbox(BBox &) const { return false; }
};

using Tree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, EntryCloud, double, std::uint32_t>,
                                        EntryCloud, 3, std::uint32_t>;

// Queries reach many points (the ball of the largest radius), so leaves bigger than
// nanoflann's default of 10 pay (measured with tests/bench_hit_points: docs/bench/code-history.md).
constexpr std::size_t kLeafSize = 32;

// nanoflann's result-set interface. The tree hands over every point with its own (L2)
// dist2 < worstDist(); addPoint applies each point's radius and calls the visitor at once.
class VisitWithinRadius {
public:
    VisitWithinRadius(const Entry *entries, const Vec3 &photon, double search_r2, HitPointVisitor visit)
        : entries_(entries), photon_(photon), search_r2_(search_r2), visit_(visit) {}

    double worstDist() const { return search_r2_; }
    bool full() const { return true; }
    bool addPoint(double, std::uint32_t i) {
        const Entry &e = entries_[i];
        // Recomputed with the shared definition rather than taking nanoflann's value, so the
        // tree agrees with the grid and brute force at the boundary.
        const double dist2 = distance2(photon_, {e.p[0], e.p[1], e.p[2]});
        if (within_radius(dist2, e.r2)) visit_(e.index, dist2);
        return true;
    }

private:
    const Entry *entries_;
    Vec3 photon_;
    double search_r2_;
    HitPointVisitor visit_;
};

// nanoflann 1.4 builds a tree on one thread, and on a 1024 x 768 view that took a quarter of
// the eye pass. The points are cut into parts by median splits along the longest axis, one
// tree per part, built in parallel; a query visits the parts whose box, grown by the part's
// search radius, holds the photon (mostly one: the cuts are planes through the scene).
constexpr std::size_t kMinPointsPerPart = 1 << 16;
constexpr int kMaxParts = 8;

struct Part {
    EntryCloud cloud;
    // The index keeps a reference to `cloud`, so a Part never moves (it lives behind a pointer).
    Tree tree{3, cloud,
              nanoflann::KDTreeSingleIndexAdaptorParams(
                  kLeafSize, nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex)};
    Vec3 lower, upper; // bounds of the part's points
    double search_r2;  // search_radius2 of the part's largest r2
};

// nanoflann keeps points with dist2 < search_r2 (strictly) and prunes subtrees with a lower
// bound that is updated incrementally and may round up by a few ulps. Searching a hair beyond
// the largest r2 keeps every point at exactly its radius; the final test is within_radius()
// against each point's own r2. Each part searches with its own largest radius: where the
// radii differ across the scene (a glass object magnifies the footprint of what is seen
// through it), most photons search a smaller ball.
double search_radius2(double max_r2) {
    return std::nextafter(max_r2 * (1.0 + 1e-9), std::numeric_limits<double>::infinity());
}

// Parts for `count` points: a power of two, as many as keep kMinPointsPerPart points each, up
// to kMaxParts. Not tied to the thread count, so every thread count searches the same parts
// (a photon finds the same hit points in any case); more parts than threads also give each
// part its own, often smaller, search radius.
int part_count(std::size_t count) {
    int parts = 1;
    while (parts < kMaxParts && count / (2 * parts) >= kMinPointsPerPart) parts *= 2;
    return parts;
}

// Reorders [begin, end) into `parts` runs (parts[0, count)), each on one side of a plane
// across the run's longest axis at about its median; the two sides are cut further in
// parallel. The plane comes from a sample, and one streaming partition moves the entries:
// an exact nth_element took as long as building the trees.
void split(Entry *begin, Entry *end, int count, std::pair<Entry *, Entry *> *parts) {
    if (count == 1) {
        parts[0] = {begin, end};
        return;
    }
    constexpr std::size_t samples = 1024;
    const std::size_t size = static_cast<std::size_t>(end - begin), step = std::max<std::size_t>(1, size / samples);
    Box3 box;
    for (std::size_t k = 0; k < size; k += step) box.extend({begin[k].p[0], begin[k].p[1], begin[k].p[2]});
    const Vec3 extent = box.upper - box.lower;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    std::vector<double> sample;
    for (std::size_t k = 0; k < size; k += step) sample.push_back(begin[k].p[axis]);
    std::nth_element(sample.begin(), sample.begin() + sample.size() / 2, sample.end());
    const double plane = sample[sample.size() / 2];
    Entry *middle = std::partition(begin, end, [&](const Entry &e) { return e.p[axis] < plane; });
    // A plane with (nearly) everything on one side, as when many points share the median
    // coordinate: halve by count instead.
    if (middle - begin < static_cast<std::ptrdiff_t>(size / 8) ||
        end - middle < static_cast<std::ptrdiff_t>(size / 8)) {
        middle = begin + size / 2;
        std::nth_element(begin, middle, end, [&](const Entry &a, const Entry &b) { return a.p[axis] < b.p[axis]; });
    }
    tbb::parallel_invoke([&] { split(begin, middle, count / 2, parts); },
                         [&] { split(middle, end, count / 2, parts + count / 2); });
}

} // namespace

struct HitPointTree::Impl {
    std::vector<std::unique_ptr<Part>> parts;
    std::vector<Entry> entries; // every point, each part's a run of them
    std::size_t size = 0;
    double max_r2 = 0;
};

HitPointTree::HitPointTree() : impl_(std::make_unique<Impl>()) {}
HitPointTree::~HitPointTree() = default;
HitPointTree::HitPointTree(HitPointTree &&) noexcept = default;
HitPointTree &HitPointTree::operator=(HitPointTree &&) noexcept = default;

void HitPointTree::build(const HitPoint *points, std::size_t count) {
    Impl &m = *impl_;
    m.size = count;
    m.max_r2 = 0;
    // The present hit points only: absent ones (r2 < 0) stay out of the tree.
    m.entries.clear();
    for (std::size_t i = 0; i < count; ++i) {
        const HitPoint &h = points[i];
        if (!h.present()) continue;
        m.max_r2 = std::max(m.max_r2, h.r2);
        m.entries.push_back({{h.position.x, h.position.y, h.position.z}, h.r2, static_cast<std::uint32_t>(i)});
    }
    const std::size_t present = m.entries.size();
    const int parts = part_count(present);
    std::vector<std::pair<Entry *, Entry *>> runs(parts);
    split(m.entries.data(), m.entries.data() + present, parts, runs.data());
    m.parts.resize(parts);
    for (auto &part : m.parts)
        if (!part) part = std::make_unique<Part>();
    tbb::parallel_for(0, parts, [&](int k) {
        Part &part = *m.parts[k];
        part.cloud.entries = runs[k].first;
        part.cloud.count = static_cast<std::size_t>(runs[k].second - runs[k].first);
        Box3 box;
        double max_r2 = 0;
        for (const Entry *e = runs[k].first; e != runs[k].second; ++e) {
            box.extend({e->p[0], e->p[1], e->p[2]});
            max_r2 = std::max(max_r2, e->r2);
        }
        part.lower = box.lower;
        part.upper = box.upper;
        part.search_r2 = search_radius2(max_r2);
        part.tree.buildIndex();
    });
}

std::size_t HitPointTree::size() const { return impl_->size; }

double HitPointTree::max_r2() const { return impl_->max_r2; }

void HitPointTree::query(const Vec3 &photon, HitPointVisitor visit) const {
    const Impl &m = *impl_;
    if (m.size == 0 || !is_finite(photon)) return;
    const double p[3] = {photon.x, photon.y, photon.z};
    for (const auto &part : m.parts) {
        if (part->cloud.count == 0) continue;
        // Outside the part's box by more than the search radius: nothing there can hold it.
        double outside2 = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const double d = std::max({part->lower[axis] - p[axis], p[axis] - part->upper[axis], 0.0});
            outside2 += d * d;
        }
        if (outside2 > part->search_r2) continue;
        VisitWithinRadius result(part->cloud.entries, photon, part->search_r2, visit);
        part->tree.findNeighbors(result, p, nanoflann::SearchParams());
    }
}

} // namespace ppm
