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
    VisitWithinRadius(const Entry *entries, const std::uint32_t *original, const Vec3 &photon, double search_r2,
                      HitPointVisitor visit)
        : entries_(entries), original_(original), photon_(photon), search_r2_(search_r2), visit_(visit) {}

    double worstDist() const { return search_r2_; }
    bool full() const { return true; }
    bool addPoint(double, std::uint32_t i) {
        const Entry &e = entries_[i];
        // Recomputed with the shared definition rather than taking nanoflann's value, so the
        // tree agrees with the grid and brute force at the boundary.
        const double dist2 = distance2(photon_, {e.p[0], e.p[1], e.p[2]});
        if (within_radius(dist2, e.r2)) visit_(original_[i], dist2);
        return true;
    }

private:
    const Entry *entries_;
    const std::uint32_t *original_; // entry index -> the caller's index
    Vec3 photon_;
    double search_r2_;
    HitPointVisitor visit_;
};

} // namespace

// One KD-tree over a subset of the hit points, searched with the largest radius of that subset.
struct Level {
    EntryCloud cloud;
    std::vector<std::uint32_t> original; // index in the caller's array of each entry
    // The index keeps a reference to `cloud`, so a Level never moves (Impl holds it in place).
    Tree tree{3, cloud,
              nanoflann::KDTreeSingleIndexAdaptorParams(
                  kLeafSize, nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex)};
    double max_r2 = 0;
    // nanoflann keeps points with dist2 < search_r2 (strictly) and prunes subtrees with a
    // lower bound that is updated incrementally and may round up by a few ulps. Searching a
    // hair beyond the largest r2 keeps every point at exactly its radius; the final test is
    // within_radius() against each point's own r2.
    double search_r2 = 0;

    void build() {
        max_r2 = 0;
        for (const Entry &e : cloud.entries) max_r2 = std::max(max_r2, e.r2);
        search_r2 = std::nextafter(max_r2 * (1.0 + 1e-9), std::numeric_limits<double>::infinity());
        tree.buildIndex();
    }

    void query(const Vec3 &photon, HitPointVisitor visit) const {
        if (cloud.entries.empty()) return;
        VisitWithinRadius result(cloud.entries.data(), original.data(), photon, search_r2, visit);
        const double p[3] = {photon.x, photon.y, photon.z};
        tree.findNeighbors(result, p, nanoflann::SearchParams());
    }
};

// The hit points in two trees split by radius. A query must search the ball of the largest
// radius of its tree, and a few hit points (seen through glass or at grazing angles) have
// radii 2-3 times the typical one: searched with theirs, every query would scan 8-27 times
// the volume it needs. So the hit points up to the 99th percentile of r2 form one tree,
// searched with that radius, and the few beyond it a second, small one.
struct HitPointTree::Impl {
    Level common, large;
    double max_r2 = 0;
};

HitPointTree::HitPointTree() : impl_(std::make_unique<Impl>()) {}
HitPointTree::~HitPointTree() = default;
HitPointTree::HitPointTree(HitPointTree &&) noexcept = default;
HitPointTree &HitPointTree::operator=(HitPointTree &&) noexcept = default;

void HitPointTree::build(const HitPoint *points, std::size_t count) {
    Impl &m = *impl_;
    // The split radius: the 99th percentile of r2.
    double split_r2 = 0;
    if (count > 0) {
        std::vector<double> r2s(count);
        for (std::size_t i = 0; i < count; ++i) r2s[i] = points[i].r2;
        const auto percentile = r2s.begin() + static_cast<std::ptrdiff_t>(count * 99 / 100);
        std::nth_element(r2s.begin(), percentile, r2s.end());
        split_r2 = *percentile;
    }
    for (Level *level : {&m.common, &m.large}) {
        level->cloud.entries.clear();
        level->original.clear();
    }
    m.common.cloud.entries.reserve(count);
    m.common.original.reserve(count);
    m.max_r2 = 0;
    for (std::size_t i = 0; i < count; ++i) {
        const HitPoint &h = points[i];
        Level &level = h.r2 <= split_r2 ? m.common : m.large;
        level.cloud.entries.push_back({{h.position.x, h.position.y, h.position.z}, h.r2});
        level.original.push_back(static_cast<std::uint32_t>(i));
        m.max_r2 = std::max(m.max_r2, h.r2);
    }
    m.common.build();
    m.large.build();
}

std::size_t HitPointTree::size() const { return impl_->common.cloud.entries.size() + impl_->large.cloud.entries.size(); }

double HitPointTree::max_r2() const { return impl_->max_r2; }

void HitPointTree::query(const Vec3 &photon, HitPointVisitor visit) const {
    if (!is_finite(photon)) return;
    impl_->common.query(photon, visit);
    impl_->large.query(photon, visit);
}

} // namespace ppm
