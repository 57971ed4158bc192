#include "photon/hit_point_tree.h"

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace ppm {

namespace {

// Position and radius, packed: leaves read these, so 32 bytes a point keeps them in cache.
struct Entry {
    double p[3];
    double r2;
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
        if (within_radius(dist2, e.r2)) visit_(i, dist2);
        return true;
    }

private:
    const Entry *entries_;
    Vec3 photon_;
    double search_r2_;
    HitPointVisitor visit_;
};

} // namespace

struct HitPointTree::Impl {
    EntryCloud cloud;
    // The index keeps a reference to `cloud`, so Impl never moves (it lives behind a pointer).
    Tree tree{3, cloud,
              nanoflann::KDTreeSingleIndexAdaptorParams(
                  kLeafSize, nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex)};
    double max_r2 = 0;
    // nanoflann keeps points with dist2 < search_r2 (strictly) and prunes subtrees with a
    // lower bound that is updated incrementally and may round up by a few ulps. Searching a
    // hair beyond the largest r2 keeps every point at exactly its radius; the final test is
    // within_radius() against each point's own r2.
    double search_r2 = 0;
};

HitPointTree::HitPointTree() : impl_(std::make_unique<Impl>()) {}
HitPointTree::~HitPointTree() = default;
HitPointTree::HitPointTree(HitPointTree &&) noexcept = default;
HitPointTree &HitPointTree::operator=(HitPointTree &&) noexcept = default;

void HitPointTree::build(const HitPoint *points, std::size_t count) {
    Impl &m = *impl_;
    m.cloud.entries.resize(count);
    m.max_r2 = 0;
    for (std::size_t i = 0; i < count; ++i) {
        const HitPoint &h = points[i];
        m.cloud.entries[i] = {{h.position.x, h.position.y, h.position.z}, h.r2};
        m.max_r2 = std::max(m.max_r2, h.r2);
    }
    m.search_r2 = std::nextafter(m.max_r2 * (1.0 + 1e-9), std::numeric_limits<double>::infinity());
    m.tree.buildIndex();
}

std::size_t HitPointTree::size() const { return impl_->cloud.entries.size(); }

double HitPointTree::max_r2() const { return impl_->max_r2; }

void HitPointTree::query(const Vec3 &photon, HitPointVisitor visit) const {
    const Impl &m = *impl_;
    if (m.cloud.entries.empty() || !is_finite(photon)) return;
    VisitWithinRadius result(m.cloud.entries.data(), photon, m.search_r2, visit);
    const double p[3] = {photon.x, photon.y, photon.z};
    m.tree.findNeighbors(result, p, nanoflann::SearchParams());
}

} // namespace ppm
