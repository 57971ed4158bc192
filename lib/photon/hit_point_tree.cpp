#include "photon/hit_point_tree.h"

#include <nanoflann.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>
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

// nanoflann's dataset interface over the packed entries.
struct EntryCloud {
    std::vector<Entry> entries;

    std::size_t kdtree_get_point_count() const { return entries.size(); }
    double kdtree_get_pt(std::uint32_t i, std::size_t dim) const { return entries[i].p[dim]; }
    template <class BBox>
    bool kdtree_get_bbox(BBox &) const { return false; }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<
    nanoflann::L2_Simple_Adaptor<double, EntryCloud, double, std::uint32_t>, EntryCloud, 3,
    std::uint32_t>;

// Queries reach many points (the ball of the largest radius), so big leaves pay: 20-40 were
// fastest in tests/bench_hit_points, nanoflann's default of 10 about 25% slower.
constexpr std::size_t kLeafSize = 32;

// nanoflann's result-set interface. The tree hands over every point with its own (L2)
// dist2 < worstDist(); addPoint applies each point's radius and calls the visitor at once.
class VisitWithinRadius {
public:
    VisitWithinRadius(const Entry *entries, const Vec3 &photon, double search_r2,
                      HitPointVisitor visit)
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

// Reorders order[begin, end) into `parts` ranges of about equal size, each on one side of the
// median of the range's longest axis; appends the ranges' ends to `ends`.
void split(const HitPoint *points, std::uint32_t *order, std::size_t begin, std::size_t end, int parts,
           std::vector<std::size_t> &ends) {
    if (parts == 1) {
        ends.push_back(end);
        return;
    }
    Box3 box;
    for (std::size_t k = begin; k < end; ++k) box.extend(points[order[k]].position);
    const Vec3 extent = box.upper - box.lower;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::size_t middle = begin + (end - begin) / 2;
    std::nth_element(order + begin, order + middle, order + end, [&](std::uint32_t a, std::uint32_t b) {
        return points[a].position[axis] < points[b].position[axis];
    });
    split(points, order, begin, middle, parts / 2, ends);
    split(points, order, middle, end, parts / 2, ends);
}

} // namespace

struct HitPointTree::Impl {
    std::vector<std::unique_ptr<Part>> parts;
    std::vector<std::uint32_t> order; // reused between builds
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
    for (std::size_t i = 0; i < count; ++i) m.max_r2 = std::max(m.max_r2, points[i].r2);

    const int parts = part_count(count);
    m.order.resize(count);
    std::iota(m.order.begin(), m.order.end(), std::uint32_t{0});
    std::vector<std::size_t> ends;
    split(points, m.order.data(), 0, count, parts, ends);
    m.parts.resize(ends.size());
    for (auto &part : m.parts)
        if (!part) part = std::make_unique<Part>();
    tbb::parallel_for(std::size_t{0}, ends.size(), [&](std::size_t k) {
        Part &part = *m.parts[k];
        const std::size_t begin = k == 0 ? 0 : ends[k - 1], end = ends[k];
        part.cloud.entries.resize(end - begin);
        Box3 box;
        double max_r2 = 0;
        for (std::size_t i = begin; i < end; ++i) {
            const HitPoint &h = points[m.order[i]];
            part.cloud.entries[i - begin] = {{h.position.x, h.position.y, h.position.z}, h.r2, m.order[i]};
            box.extend(h.position);
            max_r2 = std::max(max_r2, h.r2);
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
        if (part->cloud.entries.empty()) continue;
        // Outside the part's box by more than the search radius: nothing there can hold it.
        double outside2 = 0;
        for (int axis = 0; axis < 3; ++axis) {
            const double d = std::max({part->lower[axis] - p[axis], p[axis] - part->upper[axis], 0.0});
            outside2 += d * d;
        }
        if (outside2 > part->search_r2) continue;
        VisitWithinRadius result(part->cloud.entries.data(), photon, part->search_r2, visit);
        part->tree.findNeighbors(result, p, nanoflann::SearchParams());
    }
}

} // namespace ppm
