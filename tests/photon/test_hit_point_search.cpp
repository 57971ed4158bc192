// SPDX-License-Identifier: Apache-2.0
// The photon-pass search structures (nanoflann KD-tree and hashed grid) against brute force:
// random points with random radii, photons exactly at a hit point's radius, flat and
// degenerate sets, empty and one-point sets, duplicates, rebuilds, and no allocation per query.
#include "photon/hash_grid.h"
#include "photon/hit_point_tree.h"

#include "test_support.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <tbb/task_arena.h>
#include <utility>
#include <vector>

using namespace ppm;

// Every operator new in this executable goes through here, so a query that allocates (say
// through a std::vector of results) shows up in the count.
namespace {
std::atomic<long> g_allocations{0};
}

void *operator new(std::size_t size) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    if (void *p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void *operator new[](std::size_t size) { return operator new(size); }
void operator delete(void *p) noexcept { std::free(p); }
void operator delete[](void *p) noexcept { std::free(p); }
void operator delete(void *p, std::size_t) noexcept { std::free(p); }
void operator delete[](void *p, std::size_t) noexcept { std::free(p); }

namespace {

using Found = std::vector<std::pair<std::uint32_t, double>>; // (index, dist2), sorted

Found brute_force(const std::vector<HitPoint> &points, const Vec3 &photon) {
    Found found;
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        const double dist2 = distance2(photon, points[i].position);
        if (within_radius(dist2, points[i].r2)) found.emplace_back(i, dist2);
    }
    return found;
}

template <class Structure> Found search(const Structure &s, const Vec3 &photon) {
    Found found;
    s.query(photon, [&](std::uint32_t index, double dist2) { found.emplace_back(index, dist2); });
    std::sort(found.begin(), found.end());
    return found;
}

void assert_same(const Found &expected, const Found &actual) {
    if (expected == actual) return;
    print_error("expected %zu hit points, found %zu\n", expected.size(), actual.size());
    for (const auto &f : expected)
        if (std::find(actual.begin(), actual.end(), f) == actual.end())
            print_error("  missing %u (dist2 %.17g)\n", f.first, f.second);
    for (const auto &f : actual)
        if (std::find(expected.begin(), expected.end(), f) == expected.end())
            print_error("  extra %u (dist2 %.17g)\n", f.first, f.second);
    fail();
}

// Builds both structures over `points` and checks every photon against brute force.
// Returns the number of (photon, hit point) pairs found, so callers can check the test
// exercised something.
std::size_t check_against_brute_force(const std::vector<HitPoint> &points, const std::vector<Vec3> &photons) {
    HitPointTree tree;
    HitPointGrid grid;
    tree.build(points.data(), points.size());
    grid.build(points.data(), points.size());
    assert_int_equal(tree.size(), points.size());
    assert_int_equal(grid.size(), points.size());
    std::size_t pairs = 0;
    for (const Vec3 &photon : photons) {
        const Found expected = brute_force(points, photon);
        assert_same(expected, search(tree, photon));
        assert_same(expected, search(grid, photon));
        pairs += expected.size();
    }
    return pairs;
}

Vec3 random_in_box(test_rng &rng, const Vec3 &lower, const Vec3 &upper) {
    return {lower.x + (upper.x - lower.x) * test_rng_uniform(&rng),
            lower.y + (upper.y - lower.y) * test_rng_uniform(&rng),
            lower.z + (upper.z - lower.z) * test_rng_uniform(&rng)};
}

HitPoint hit_point(const Vec3 &position, double r2) {
    HitPoint h;
    h.position = position;
    h.r2 = r2;
    return h;
}

void random_points_with_random_radii_match_brute_force(void **) {
    test_rng rng{11};
    // Off the origin, radii varying by a factor 12, photons reaching past the points' bounds.
    const Vec3 lower{97, -53, 17}, upper{103, -47, 23};
    std::vector<HitPoint> points;
    for (int i = 0; i < 3000; ++i) {
        const double r = 0.05 + 0.55 * test_rng_uniform(&rng);
        points.push_back(hit_point(random_in_box(rng, lower, upper), r * r));
    }
    std::vector<Vec3> photons;
    for (int i = 0; i < 3000; ++i) photons.push_back(random_in_box(rng, lower - Vec3{1, 1, 1}, upper + Vec3{1, 1, 1}));
    for (int i = 0; i < 100; ++i) photons.push_back(points[i * 7].position); // dist2 = 0
    const std::size_t pairs = check_against_brute_force(points, photons);
    print_message("%zu (photon, hit point) pairs\n", pairs);
    assert_true(pairs > 3000);
}

// Visible points lie on surfaces: a plane (zero extent along z) and a thin curved shell.
void points_on_surfaces_match_brute_force(void **) {
    test_rng rng{12};
    std::vector<HitPoint> points;
    for (int i = 0; i < 1500; ++i) {
        const double r = 0.02 + 0.1 * test_rng_uniform(&rng);
        points.push_back(hit_point({4 * test_rng_uniform(&rng), 3 * test_rng_uniform(&rng), 0}, r * r));
    }
    for (int i = 0; i < 1500; ++i) {
        const double theta = 3 * test_rng_uniform(&rng), phi = 6.2 * test_rng_uniform(&rng);
        const double r = 0.02 + 0.1 * test_rng_uniform(&rng);
        points.push_back(hit_point(
            Vec3{2 + std::sin(theta) * std::cos(phi), 1.5 + std::sin(theta) * std::sin(phi), 0.5 + std::cos(theta)},
            r * r));
    }
    std::vector<Vec3> photons;
    for (int i = 0; i < 1500; ++i)
        photons.push_back({4 * test_rng_uniform(&rng), 3 * test_rng_uniform(&rng),
                           i % 3 == 0 ? 0.0 : 0.05 * (test_rng_uniform(&rng) - 0.5)});
    for (int i = 0; i < 1500; ++i) photons.push_back(points[1500 + i].position + Vec3{0.01, -0.02, 0.03});
    const std::size_t pairs = check_against_brute_force(points, photons);
    assert_true(pairs > 3000);
}

// Points on the floor and ceiling of a box (as in a Cornell box), one radius each time: the
// box's faces lie in the middle of grid cells, so a ball on them is listed in two cells along
// z only if it is wider than half a cell, never because the face fell on a cell face. With
// cells 12 radii wide, a ball overlaps (1 + 2/12)^2 = 1.36 cells on average in the plane; the
// grid used to list twice as many entries for one radius in a few (the ceiling's balls all
// straddling a cell face). Queries stay exact.
void walls_are_listed_once_across(void **) {
    test_rng rng{14};
    for (int k = 0; k < 24; ++k) {
        const double r = 0.004 + 0.0005 * k;
        std::vector<HitPoint> points;
        for (int i = 0; i < 4000; ++i)
            points.push_back(
                hit_point({test_rng_uniform(&rng), test_rng_uniform(&rng), i % 2 == 0 ? 0.0 : 1.0}, r * r));
        HitPointGrid grid;
        grid.build(points.data(), points.size());
        const double per_point = double(grid.cell_entries()) / points.size();
        assert_true(per_point > 1.2 && per_point < 1.5);
        std::vector<Vec3> photons;
        for (int i = 0; i < 200; ++i) photons.push_back(points[i].position + Vec3{0.5 * r, -0.3 * r, 0.2 * r});
        assert_true(check_against_brute_force(points, photons) >= 200);
    }
}

// A photon at exactly a hit point's radius counts; one ulp inside the radius it does not. The
// largest radius is among the exact ones, which is where nanoflann's strict "dist < radius"
// would lose it.
void photons_exactly_at_the_radius_count(void **) {
    test_rng rng{13};
    std::vector<HitPoint> points;
    std::vector<Vec3> photons;
    std::vector<bool> inside;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 p = random_in_box(rng, {-1, -1, -1}, {1, 1, 1});
        const Vec3 offset =
            Vec3{test_rng_uniform(&rng) - 0.5, test_rng_uniform(&rng) - 0.5, test_rng_uniform(&rng) - 0.5} * 0.3;
        const Vec3 q = p + offset;
        const double dist2 = distance2(q, p);
        inside.push_back(i % 2 == 0);
        points.push_back(hit_point(p, inside.back() ? dist2 : std::nextafter(dist2, 0.0)));
        photons.push_back(q);
    }
    // The largest radius, exactly at its photon.
    points.push_back(hit_point({0.25, 0.5, -0.125}, 0.5 * 0.5));
    photons.push_back({0.75, 0.5, -0.125});
    inside.push_back(true);
    points.push_back(hit_point({0.25, 0.5, 0.5}, 0.5 * 0.5));
    photons.push_back({std::nextafter(0.75, 1.0), 0.5, 0.5});
    inside.push_back(false);

    check_against_brute_force(points, photons);

    HitPointTree tree;
    HitPointGrid grid;
    tree.build(points.data(), points.size());
    grid.build(points.data(), points.size());
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        const auto has_i = [i](const Found &f) {
            return std::any_of(f.begin(), f.end(), [i](const auto &e) { return e.first == i; });
        };
        assert_int_equal(has_i(search(tree, photons[i])), inside[i]);
        assert_int_equal(has_i(search(grid, photons[i])), inside[i]);
    }
}

// The same far from the origin with radii below single precision's resolution there (a float
// ulp at 3e4 is 0.002): the grid's single-precision screening must not reject any of them.
void photons_exactly_at_the_radius_far_from_the_origin(void **) {
    test_rng rng{14};
    const Vec3 centre{1e4, -3e4, 2e4};
    std::vector<HitPoint> points;
    std::vector<Vec3> photons;
    std::vector<bool> inside;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 p = centre + random_in_box(rng, {-1, -1, -1}, {1, 1, 1});
        const Vec3 offset =
            Vec3{test_rng_uniform(&rng) - 0.5, test_rng_uniform(&rng) - 0.5, test_rng_uniform(&rng) - 0.5} * 1e-3;
        const Vec3 q = p + offset;
        const double dist2 = distance2(q, p);
        inside.push_back(i % 2 == 0);
        points.push_back(hit_point(p, inside.back() ? dist2 : std::nextafter(dist2, 0.0)));
        photons.push_back(q);
    }
    check_against_brute_force(points, photons);
    HitPointGrid grid;
    grid.build(points.data(), points.size());
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        const Found found = search(grid, photons[i]);
        const bool has_i = std::any_of(found.begin(), found.end(), [i](const auto &e) { return e.first == i; });
        assert_int_equal(has_i, inside[i]);
    }
}

void empty_structures_find_nothing(void **) {
    HitPointTree tree;
    HitPointGrid grid;
    const Vec3 photon{0, 0, 0};
    assert_true(search(tree, photon).empty()); // never built
    assert_true(search(grid, photon).empty());
    tree.build(nullptr, 0);
    grid.build(nullptr, 0);
    assert_int_equal(tree.size(), 0);
    assert_int_equal(grid.size(), 0);
    assert_true(search(tree, photon).empty());
    assert_true(search(grid, photon).empty());
    // Emptied by a rebuild.
    const HitPoint h = hit_point({0, 0, 0}, 1);
    tree.build(&h, 1);
    grid.build(&h, 1);
    assert_int_equal(search(tree, photon).size(), 1);
    tree.build(nullptr, 0);
    grid.build(nullptr, 0);
    assert_true(search(tree, photon).empty());
    assert_true(search(grid, photon).empty());
}

void one_point(void **) {
    const std::vector<HitPoint> points = {hit_point({1, 2, 3}, 0.25)};
    const std::vector<Vec3> photons = {{1, 2, 3},    {1.5, 2, 3},    {1, 2.5, 3}, {1, 2, 2.5},  {1.3, 2.3, 3.1},
                                       {1.51, 2, 3}, {1, 2, 3.5001}, {-40, 7, 3}, {1e300, 0, 0}};
    assert_int_equal(check_against_brute_force(points, photons), 5);
    // Zero radius: only a photon at the very position counts.
    const std::vector<HitPoint> point = {hit_point({1, 2, 3}, 0)};
    assert_int_equal(check_against_brute_force(point, {{1, 2, 3}, {1, 2, std::nextafter(3.0, 4.0)}}), 1);
}

void duplicates_are_each_found_once(void **) {
    test_rng rng{14};
    std::vector<HitPoint> points;
    for (int i = 0; i < 60; ++i) points.push_back(hit_point({0.5, 0.5, 0.5}, 0.01 + 0.2 * test_rng_uniform(&rng)));
    for (int i = 0; i < 60; ++i) points.push_back(hit_point({0.9, 0.5, 0.5}, 0.01 + 0.2 * test_rng_uniform(&rng)));
    std::vector<Vec3> photons;
    for (int i = 0; i < 500; ++i) photons.push_back(random_in_box(rng, {0, 0, 0}, {1.4, 1, 1}));
    photons.push_back({0.5, 0.5, 0.5});
    photons.push_back({0.7, 0.5, 0.5});
    assert_true(check_against_brute_force(points, photons) > 1000);

    // All at one position with zero radii: the grid has no extent and no radius to size cells.
    std::vector<HitPoint> same(100, hit_point({-3, 4, 5}, 0));
    assert_int_equal(check_against_brute_force(same, {{-3, 4, 5}, {-3, 4, 5.0000001}}), 100);

    // Spread out with zero radii: cells as small as the extent allows (2^-30 of it).
    std::vector<HitPoint> spread;
    std::vector<Vec3> at_points;
    for (int i = 0; i < 200; ++i) {
        spread.push_back(hit_point(random_in_box(rng, {-1e3, -1e3, -1e3}, {1e3, 1e3, 1e3}), 0));
        at_points.push_back(spread.back().position);
        at_points.push_back(spread.back().position + Vec3{1e-9, 0, 0});
    }
    spread.push_back(spread[17]);
    assert_int_equal(check_against_brute_force(spread, at_points), 201);
}

// Enough points for the tree to cut them into parts (4 here, of 64k points or more), built on
// the two threads of an arena: photons near and across the median planes find the points of
// every part they reach.
void tree_in_parts_matches_brute_force(void **) {
    test_rng rng{16};
    std::vector<HitPoint> points;
    for (int i = 0; i < 300000; ++i) {
        const double r = 0.01 + 0.04 * test_rng_uniform(&rng);
        points.push_back(hit_point(random_in_box(rng, {-1, -1, -1}, {1, 1, 1}), r * r));
    }
    std::vector<Vec3> photons;
    for (int i = 0; i < 400; ++i) photons.push_back(random_in_box(rng, {-1.05, -1.05, -1.05}, {1.05, 1.05, 1.05}));
    for (int i = 0; i < 200; ++i) photons.push_back(random_in_box(rng, {-0.03, -1, -1}, {0.03, 1, 1})); // x median
    for (int i = 0; i < 200; ++i) photons.push_back(points[i * 997].position);
    tbb::task_arena arena(2);
    std::size_t pairs = 0;
    arena.execute([&] {
        HitPointTree tree;
        tree.build(points.data(), points.size());
        assert_int_equal(tree.size(), points.size());
        // The grid builds in parallel too (atomic counts and placement).
        HitPointGrid grid;
        grid.build(points.data(), points.size());
        assert_int_equal(grid.size(), points.size());
        assert_true(grid.cell_entries() >= points.size());
        for (const Vec3 &photon : photons) {
            const Found expected = brute_force(points, photon);
            assert_same(expected, search(tree, photon));
            assert_same(expected, search(grid, photon));
            pairs += expected.size();
        }
    });
    print_message("%zu (photon, hit point) pairs\n", pairs);
    assert_true(pairs > 1000);
}

// A few balls far larger than the rest: the grid's cells then follow the largest radius (a
// ball spans at most 5 cells per axis) and the big balls are listed in up to 125 cells, each
// found once by any photon inside them.
void few_huge_radii_among_small_ones(void **) {
    test_rng rng{18};
    std::vector<HitPoint> points;
    for (int i = 0; i < 4000; ++i) points.push_back(hit_point(random_in_box(rng, {-4, -4, -4}, {4, 4, 4}), 1e-4));
    for (int i = 0; i < 3; ++i) points.push_back(hit_point(random_in_box(rng, {-2, -2, -2}, {2, 2, 2}), 4.0));
    std::vector<Vec3> photons;
    for (int i = 0; i < 3000; ++i) photons.push_back(random_in_box(rng, {-6, -6, -6}, {6, 6, 6}));
    for (int i = 0; i < 300; ++i) photons.push_back(points[i * 13].position);
    assert_true(check_against_brute_force(points, photons) > 500);
}

// The renderer passes one hit point per pixel, absent (r2 < 0) where the camera path found no
// surface to gather on: the structures skip those, and a set of only absent points finds nothing.
void absent_points_are_never_found(void **) {
    test_rng rng{19};
    std::vector<HitPoint> points;
    for (int i = 0; i < 3000; ++i) {
        const double r = 0.05 + 0.2 * test_rng_uniform(&rng);
        points.push_back(hit_point(random_in_box(rng, {0, 0, 0}, {4, 4, 4}), i % 3 == 0 ? -1.0 : r * r));
    }
    points.push_back(hit_point({1e6, 1e6, 1e6}, -1.0)); // far away: must not stretch the bounds
    std::vector<Vec3> photons;
    for (int i = 0; i < 2000; ++i) photons.push_back(random_in_box(rng, {-0.5, -0.5, -0.5}, {4.5, 4.5, 4.5}));
    for (int i = 0; i < 300; ++i) photons.push_back(points[i * 3].position); // at absent points
    const std::size_t pairs = check_against_brute_force(points, photons);
    print_message("%zu (photon, hit point) pairs\n", pairs);
    assert_true(pairs > 300);

    const std::vector<HitPoint> none(50, hit_point({1, 2, 3}, -1.0));
    assert_int_equal(check_against_brute_force(none, {{1, 2, 3}, {0, 0, 0}}), 0);
}

void rebuild_replaces_the_points(void **) {
    const std::vector<HitPoint> first = {hit_point({0, 0, 0}, 1), hit_point({5, 0, 0}, 1)};
    const std::vector<HitPoint> second = {hit_point({10, 0, 0}, 4)};
    HitPointTree tree;
    HitPointGrid grid;
    tree.build(first.data(), first.size());
    grid.build(first.data(), first.size());
    assert_int_equal(search(tree, {0, 0, 0}).size(), 1);
    assert_int_equal(search(grid, {5, 0, 0}).size(), 1);
    assert_close(tree.max_r2(), 1, 0);
    tree.build(second.data(), second.size());
    grid.build(second.data(), second.size());
    assert_true(search(tree, {0, 0, 0}).empty());
    assert_true(search(grid, {5, 0, 0}).empty());
    assert_true(search(tree, {11.5, 0, 0}) == (Found{{0, 2.25}}));
    assert_true(search(grid, {11.5, 0, 0}) == (Found{{0, 2.25}}));
    assert_close(tree.max_r2(), 4, 0);
    assert_close(grid.max_r2(), 4, 0);
}

// One grid rebuilt over more points, then fewer, then more again: its entry array is
// replaced when too small and keeps stale entries past the last bucket otherwise, and every
// build must still find exactly what brute force finds.
void rebuilds_that_grow_and_shrink_match_brute_force(void **) {
    test_rng rng{77};
    HitPointGrid grid;
    std::size_t found_pairs = 0;
    for (const std::size_t count : {std::size_t(500), std::size_t(20000), std::size_t(300), std::size_t(40000)}) {
        std::vector<HitPoint> points;
        for (std::size_t i = 0; i < count; ++i) {
            const double r = 0.002 + 0.02 * test_rng_uniform(&rng);
            points.push_back(hit_point(random_in_box(rng, {-1, -1, -1}, {1, 1, 1}), r * r));
        }
        grid.build(points.data(), points.size());
        for (int k = 0; k < 3000; ++k) {
            // Photons near random hit points, so that most find some.
            const Vec3 photon = points[std::size_t(test_rng_uniform(&rng) * count)].position +
                                random_in_box(rng, {-0.01, -0.01, -0.01}, {0.01, 0.01, 0.01});
            const Found expected = brute_force(points, photon);
            assert_same(expected, search(grid, photon));
            found_pairs += expected.size();
        }
    }
    print_message("%zu (photon, hit point) pairs\n", found_pairs);
    assert_true(found_pairs > 4000);
}

void non_finite_photons_find_nothing(void **) {
    const std::vector<HitPoint> points = {hit_point({0, 0, 0}, 1), hit_point({0.5, 0, 0}, 1)};
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    assert_int_equal(check_against_brute_force(points, {{nan, 0, 0}, {0, inf, 0}, {0, 0, -inf}}), 0);
}

template <class Structure>
void assert_queries_do_not_allocate(const std::vector<HitPoint> &points, const std::vector<Vec3> &photons) {
    Structure s;
    s.build(points.data(), points.size());
    std::size_t found = 0;
    double sum = 0;
    const auto visit = [&](std::uint32_t index, double dist2) {
        found += 1;
        sum += index * dist2;
    };
    const long before = g_allocations.load();
    for (const Vec3 &photon : photons) s.query(photon, visit);
    assert_int_equal(g_allocations.load() - before, 0);
    assert_true(found > photons.size());
    assert_true(sum > 0);
}

void queries_do_not_allocate(void **) {
    test_rng rng{15};
    std::vector<HitPoint> points;
    for (int i = 0; i < 20000; ++i) points.push_back(hit_point(random_in_box(rng, {0, 0, 0}, {1, 1, 1}), 0.002));
    std::vector<Vec3> photons;
    for (int i = 0; i < 20000; ++i) photons.push_back(random_in_box(rng, {0, 0, 0}, {1, 1, 1}));
    const long before = g_allocations.load();
    { std::vector<int> probe(3); } // the counter itself works
    assert_int_equal(g_allocations.load() - before, 1);
    assert_queries_do_not_allocate<HitPointTree>(points, photons);
    assert_queries_do_not_allocate<HitPointGrid>(points, photons);
}

} // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(random_points_with_random_radii_match_brute_force),
        cmocka_unit_test(points_on_surfaces_match_brute_force),
        cmocka_unit_test(walls_are_listed_once_across),
        cmocka_unit_test(photons_exactly_at_the_radius_count),
        cmocka_unit_test(photons_exactly_at_the_radius_far_from_the_origin),
        cmocka_unit_test(empty_structures_find_nothing),
        cmocka_unit_test(one_point),
        cmocka_unit_test(duplicates_are_each_found_once),
        cmocka_unit_test(tree_in_parts_matches_brute_force),
        cmocka_unit_test(few_huge_radii_among_small_ones),
        cmocka_unit_test(absent_points_are_never_found),
        cmocka_unit_test(rebuild_replaces_the_points),
        cmocka_unit_test(rebuilds_that_grow_and_shrink_match_brute_force),
        cmocka_unit_test(non_finite_photons_find_nothing),
        cmocka_unit_test(queries_do_not_allocate),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
