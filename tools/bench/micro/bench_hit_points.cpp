// SPDX-License-Identifier: Apache-2.0
// Micro-benchmark of the photon-pass search structures: nanoflann KD-tree (HitPointTree)
// against the hashed grid (HitPointGrid), on the hit points of a 1024x768 view into the
// smallppm Cornell box, with per-pixel radii like a render's, and 1M photons landing on its
// walls. Prints build times and queries per second; not a test (timings are not checked).
//
//     bench_hit_points [photons]
#include "photon/hash_grid.h"
#include "photon/hit_point_tree.h"
#include "photon/random.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

using namespace ppm;

namespace {

constexpr int kWidth = 1024, kHeight = 768;

// smallppm's box: walls at x = 1 and 99, y = 0 and 81.6, z = 0 and 170, and two spheres.
struct Sphere {
    Vec3 center;
    double radius;
};
const Sphere kSpheres[] = {{{27, 16.5, 47}, 16.5}, {{73, 16.5, 88}, 16.5}};
const Vec3 kBoxLower{1, 0, 0}, kBoxUpper{99, 81.6, 170};

// Nearest hit of a ray from inside the box: its walls or a sphere.
bool trace(const Vec3 &o, const Vec3 &d, Vec3 &hit, Vec3 &normal) {
    double t_best = INFINITY;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) continue;
        const double wall = d[a] > 0 ? kBoxUpper[a] : kBoxLower[a];
        const double t = (wall - o[a]) / d[a];
        if (t > 1e-9 && t < t_best) {
            t_best = t;
            normal = Vec3{};
            normal[a] = d[a] > 0 ? -1 : 1;
        }
    }
    for (const Sphere &s : kSpheres) {
        const Vec3 oc = o - s.center;
        const double b = dot(oc, d), c = dot(oc, oc) - s.radius * s.radius, disc = b * b - c;
        if (disc < 0) continue;
        const double t = -b - std::sqrt(disc);
        if (t > 1e-9 && t < t_best) {
            t_best = t;
            normal = normalize(o + d * t - s.center);
        }
    }
    if (!std::isfinite(t_best)) return false;
    hit = o + d * t_best;
    return true;
}

// One jittered camera ray per pixel (smallpt's camera). The radius is `footprint_scale` pixel
// footprints at the hit, times a per-pixel factor in [shrink_min, 1] standing for how far each
// pixel's radius has shrunk so far.
std::vector<HitPoint> camera_hit_points(double footprint_scale, double shrink_min, std::uint32_t pass) {
    const Vec3 eye{50, 52, 295.6}, dir = normalize(Vec3{0, -0.042612, -1});
    const Vec3 cx{kWidth * 0.5135 / kHeight, 0, 0}, cy = normalize(cross(cx, dir)) * 0.5135;
    const double pixel_angle = 0.5135 / kHeight; // radians per pixel, near the axis
    std::vector<HitPoint> points;
    points.reserve(static_cast<std::size_t>(kWidth) * kHeight);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const std::uint32_t pixel = static_cast<std::uint32_t>(y * kWidth + x);
            CounterRng rng(1, 0, pass, pixel);
            const double sx = (x + rng.uniform()) / kWidth - 0.5, sy = (y + rng.uniform()) / kHeight - 0.5;
            const Vec3 d = normalize(cx * sx + cy * sy + dir);
            const Vec3 o = eye + d * 140; // start inside the box, as smallpt does
            HitPoint h;
            Vec3 normal;
            if (!trace(o, d, h.position, normal)) continue;
            const double distance = length(h.position - eye);
            // The footprint's area grows as 1 / cos, its mean width as 1 / sqrt(cos).
            const double cosine = std::max(std::fabs(dot(normal, d)), 0.05);
            const double r = footprint_scale * distance * pixel_angle / std::sqrt(cosine) *
                             (shrink_min + (1 - shrink_min) * rng.uniform());
            h.r2 = r * r;
            points.push_back(h);
        }
    return points;
}

// Photons land on every surface in proportion to area (walls facing away from the camera
// included, as diffuse interreflection does).
std::vector<Vec3> photon_hits(std::size_t count) {
    const Vec3 e = kBoxUpper - kBoxLower;
    const double wall_area[3] = {e.y * e.z, e.x * e.z, e.x * e.y};
    double sphere_area = 0;
    for (const Sphere &s : kSpheres) sphere_area += 4 * M_PI * s.radius * s.radius;
    const double total = 2 * (wall_area[0] + wall_area[1] + wall_area[2]) + sphere_area;
    std::vector<Vec3> photons;
    photons.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        CounterRng rng(2, 1, 0, i);
        double pick = rng.uniform() * total;
        const double u = rng.uniform(), v = rng.uniform();
        Vec3 p;
        if (pick < sphere_area) {
            const Sphere &s = kSpheres[pick < sphere_area / 2 ? 0 : 1];
            const double z = 1 - 2 * u, rxy = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * M_PI * v;
            p = s.center + Vec3{rxy * std::cos(phi), rxy * std::sin(phi), z} * s.radius;
        } else {
            pick -= sphere_area;
            int a = 0;
            while (a < 2 && pick >= 2 * wall_area[a]) pick -= 2 * wall_area[a++];
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            p[a] = pick < wall_area[a] ? kBoxLower[a] : kBoxUpper[a];
            p[b] = kBoxLower[b] + u * e[b];
            p[c] = kBoxLower[c] + v * e[c];
        }
        photons.push_back(p);
    }
    return photons;
}

// Spreads the low 10 bits of v to every third bit.
std::uint32_t spread_bits(std::uint32_t v) {
    v &= 0x3FF;
    v = (v | v << 16) & 0x030000FF;
    v = (v | v << 8) & 0x0300F00F;
    v = (v | v << 4) & 0x030C30C3;
    v = (v | v << 2) & 0x09249249;
    return v;
}

// The photons in Morton order over the box (about 0.1-unit cells): what a renderer gains by
// sorting a batch of photon hits before gathering, which the order-independent flux sums
// allow without losing determinism.
std::vector<Vec3> morton_sorted(std::vector<Vec3> photons) {
    const Vec3 e = kBoxUpper - kBoxLower;
    const auto key = [&e](const Vec3 &p) {
        std::uint32_t k = 0;
        for (int a = 0; a < 3; ++a) {
            const double t = std::clamp((p[a] - kBoxLower[a]) / e[a], 0.0, 1.0);
            k |= spread_bits(static_cast<std::uint32_t>(t * 1023)) << a;
        }
        return k;
    };
    std::sort(photons.begin(), photons.end(), [&key](const Vec3 &a, const Vec3 &b) { return key(a) < key(b); });
    return photons;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct QueryResult {
    double seconds;
    std::size_t found;
};

template <class Structure> QueryResult run_queries(const Structure &s, const std::vector<Vec3> &photons, int threads) {
    std::vector<std::size_t> found(threads, 0);
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> workers;
    for (int t = 0; t < threads; ++t)
        workers.emplace_back([&, t] {
            std::size_t n = 0;
            const auto visit = [&n](std::uint32_t, double) { ++n; };
            const std::size_t begin = photons.size() * t / threads, end = photons.size() * (t + 1) / threads;
            for (std::size_t i = begin; i < end; ++i) s.query(photons[i], visit);
            found[t] = n;
        });
    for (std::thread &w : workers) w.join();
    QueryResult r{seconds_since(start), 0};
    for (std::size_t n : found) r.found += n;
    return r;
}

template <class Structure>
void measure(const char *name, const std::vector<HitPoint> &points, const std::vector<Vec3> &photons) {
    Structure s;
    double build = INFINITY;
    for (int i = 0; i < 3; ++i) {
        const auto start = std::chrono::steady_clock::now();
        s.build(points.data(), points.size());
        build = std::min(build, seconds_since(start));
    }
    QueryResult best1{INFINITY, 0}, best2{INFINITY, 0};
    for (int i = 0; i < 2; ++i) {
        const QueryResult r1 = run_queries(s, photons, 1);
        if (r1.seconds < best1.seconds) best1 = r1;
        const QueryResult r2 = run_queries(s, photons, 2);
        if (r2.seconds < best2.seconds) best2 = r2;
    }
    const double n = static_cast<double>(photons.size());
    std::printf("  %-9s build %7.1f ms   1 thread %6.2f M queries/s   2 threads %6.2f M queries/s   "
                "found %zu (%.2f per photon)\n",
                name, build * 1e3, n / best1.seconds * 1e-6, n / best2.seconds * 1e-6, best1.found,
                static_cast<double>(best1.found) / n);
    if (best1.found != best2.found) {
        std::fprintf(stderr, "bench_hit_points: thread counts disagree\n");
        std::exit(2);
    }
}

} // namespace

int main(int argc, char **argv) {
    const std::size_t photon_count = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
    const std::vector<Vec3> photons = photon_hits(photon_count), sorted = morton_sorted(photons);
    const struct {
        const char *name;
        double footprint_scale, shrink_min;
    } scenarios[] = {
        {"first pass: R = 2 pixel footprints", 2.0, 1.0},
        {"later pass: R = 2 footprints x U[0.3, 1]", 2.0, 0.3},
        {"late pass:  R = 0.5 footprints x U[0.2, 1]", 0.5, 0.2},
    };
    for (const auto &sc : scenarios) {
        const std::vector<HitPoint> points = camera_hit_points(sc.footprint_scale, sc.shrink_min, 0);
        double max_r2 = 0, mean_r = 0;
        for (const HitPoint &h : points) {
            max_r2 = std::max(max_r2, h.r2);
            mean_r += std::sqrt(h.r2);
        }
        mean_r /= static_cast<double>(points.size());
        std::printf("%s: %zu hit points, radius mean %.3f max %.3f, %zu photons\n", sc.name, points.size(), mean_r,
                    std::sqrt(max_r2), photons.size());
        std::printf(" photons in random order\n");
        measure<HitPointTree>("kd-tree", points, photons);
        measure<HitPointGrid>("hash grid", points, photons);
        std::printf(" photons sorted along a Morton curve\n");
        measure<HitPointTree>("kd-tree", points, sorted);
        measure<HitPointGrid>("hash grid", points, sorted);
    }
    return 0;
}
