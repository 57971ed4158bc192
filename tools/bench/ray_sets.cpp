// SPDX-License-Identifier: Apache-2.0
#include "ray_sets.h"

#include "common/status.h"
#include "patch_topology.h"
#include "rng.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace bench {

namespace {

constexpr double pi = 3.14159265358979323846;
using ref::cross;
using ref::normalize;
using ref::real;

struct Vec {
    double x, y, z;
};
Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec operator*(Vec a, double s) { return {a.x * s, a.y * s, a.z * s}; }
Vec cross(Vec a, Vec b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec normalized(Vec a) { return a * (1.0 / std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z)); }

ppm_ray make_ray(Vec org, Vec dir) {
    const Vec d = normalized(dir);
    return ppm_ray{{org.x, org.y, org.z}, 0.0, {d.x, d.y, d.z}, INFINITY};
}

// Long-double helpers for rays built through known surface points.

// A ray whose (rounded) line passes through `point` at distance `length` from its origin.
ppm_ray ray_through(const real point[3], real dir[3], real length) {
    normalize(dir);
    ppm_ray r{{0, 0, 0}, 0.0, {0, 0, 0}, INFINITY};
    for (int c = 0; c < 3; ++c) {
        r.dir[c] = static_cast<double>(dir[c]);
        r.org[c] = static_cast<double>(point[c] - length * dir[c]);
    }
    return r;
}

void random_direction(SplitMix64 &rng, real d[3]) {
    const double z = 2 * rng.uniform() - 1, phi = 2 * pi * rng.uniform();
    const double s = std::sqrt(std::max(0.0, 1 - z * z));
    d[0] = s * std::cos(phi);
    d[1] = s * std::sin(phi);
    d[2] = z;
}

// Unit normal where it is regular (derivatives not small, not nearly parallel).
bool regular_normal(const ref::Patch &patch, real u, real v, real s[3], real n[3], real su[3]) {
    real sv[3];
    ref::evaluate(patch, u, v, s, su, sv);
    cross(su, sv, n);
    const real l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const real lu = std::sqrt(su[0] * su[0] + su[1] * su[1] + su[2] * su[2]);
    const real lv = std::sqrt(sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2]);
    if (!(l > 1e-3L * lu * lv) || !(lu > 1e-6L) || !(lv > 1e-6L)) return false;
    for (int c = 0; c < 3; ++c) n[c] /= l;
    return true;
}

} // namespace

double Bounds::diagonal() const {
    double sum = 0;
    for (int k = 0; k < 3; ++k) sum += (upper[k] - lower[k]) * (upper[k] - lower[k]);
    return std::sqrt(sum);
}

Bounds control_point_bounds(const std::vector<double> &control_points) {
    Bounds box{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    for (size_t i = 0; i < control_points.size(); ++i) {
        box.lower[i % 3] = std::min(box.lower[i % 3], control_points[i]);
        box.upper[i % 3] = std::max(box.upper[i % 3], control_points[i]);
    }
    return box;
}

const RayBatch &RaySet::batch(double spawn_tolerance) const {
    for (const auto &variant : variants)
        if (variant.first == spawn_tolerance) return variant.second;
    return base;
}

std::string format_number(double x) {
    char text[32];
    const double e = std::round(std::log10(x));
    if (x > 0 && std::fabs(x - std::pow(10.0, e)) <= 1e-12 * x)
        std::snprintf(text, sizeof text, "1e%d", int(e));
    else
        std::snprintf(text, sizeof text, "%g", x);
    return text;
}

RaySet random_rays(const Bounds &box, size_t count, uint64_t seed) {
    SplitMix64 rng(seed);
    const Vec center{box.center(0), box.center(1), box.center(2)};
    const double radius = box.diagonal();
    RaySet set;
    set.name = "random";
    set.description = "origins uniform on the sphere of radius = diagonal around the box centre, "
                      "aimed at points uniform in the box";
    set.base.rays.reserve(count);
    while (set.base.rays.size() < count) {
        const double z = 2.0 * rng.uniform() - 1.0, phi = 2.0 * pi * rng.uniform();
        const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
        const Vec org = center + Vec{s * std::cos(phi), s * std::sin(phi), z} * radius;
        Vec target;
        target.x = box.lower[0] + (box.upper[0] - box.lower[0]) * rng.uniform();
        target.y = box.lower[1] + (box.upper[1] - box.lower[1]) * rng.uniform();
        target.z = box.lower[2] + (box.upper[2] - box.lower[2]) * rng.uniform();
        set.base.rays.push_back(make_ray(org, target - org));
    }
    return set;
}

RaySet camera_rays(const Bounds &box, int width, int height) {
    const double fov_y = 40.0 * pi / 180.0;
    const Vec center{box.center(0), box.center(1), box.center(2)};
    const Vec forward = normalized(Vec{-1.0, 1.6, -1.0});
    const Vec right = normalized(cross(forward, Vec{0, 0, 1}));
    const Vec up = cross(right, forward);
    const double half_h = std::tan(0.5 * fov_y), half_w = half_h * width / height;
    // The closest eye from which every box corner projects inside 95% of the image.
    double distance = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec c{corner & 1 ? box.upper[0] : box.lower[0], corner & 2 ? box.upper[1] : box.lower[1],
                    corner & 4 ? box.upper[2] : box.lower[2]};
        const Vec r = c - center;
        const double depth = dot(r, forward);
        distance = std::max({distance, std::fabs(dot(r, right)) / (0.95 * half_w) - depth,
                             std::fabs(dot(r, up)) / (0.95 * half_h) - depth});
    }
    const Vec eye = center - forward * distance;

    RaySet set;
    set.name = "camera";
    set.description = std::to_string(width) + " x " + std::to_string(height) +
                      " pinhole camera, 40 degree field of view, the model filling 95% of the image";
    set.base.rays.reserve(size_t(width) * height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double sx = (2.0 * (x + 0.5) / width - 1.0) * half_w;
            const double sy = (1.0 - 2.0 * (y + 0.5) / height) * half_h;
            set.base.rays.push_back(make_ray(eye, forward + right * sx + up * sy));
        }
    }
    return set;
}

RaySet grazing_rays(const ref::Intersector &reference, double angle, size_t count, uint64_t seed) {
    SplitMix64 rng(seed);
    const auto &patches = reference.patches();
    const real diagonal = reference.diagonal();
    RaySet set;
    set.name = "grazing-" + format_number(angle);
    set.description =
        "at " + format_number(angle) + " rad to the tangent plane at random surface points, from either side";
    set.base.rays.reserve(count);
    size_t attempts = 0;
    while (set.base.rays.size() < count) {
        if (++attempts > 100 * count + 1000)
            throw std::runtime_error("grazing rays: no surface point with a regular normal found");
        const size_t p = std::min(patches.size() - 1, size_t(rng.uniform() * patches.size()));
        const real u = 0.01L + 0.98L * rng.uniform(), v = 0.01L + 0.98L * rng.uniform();
        real s[3], n[3], e1[3], e2[3];
        if (!regular_normal(patches[p], u, v, s, n, e1)) continue;
        normalize(e1);
        cross(n, e1, e2);
        const real phi = 2 * real(pi) * rng.uniform(), side = rng.uniform() < 0.5 ? -1 : 1;
        real dir[3];
        for (int c = 0; c < 3; ++c)
            dir[c] = std::cos(real(angle)) * (std::cos(phi) * e1[c] + std::sin(phi) * e2[c]) +
                     side * std::sin(real(angle)) * n[c];
        const real length = (0.06L + 0.3L * rng.uniform()) * diagonal;
        set.base.rays.push_back(ray_through(s, dir, length));
    }
    return set;
}

RaySet seam_rays(const ref::Intersector &reference, size_t count, uint64_t seed) {
    SplitMix64 rng(seed);
    const auto &patches = reference.patches();
    const real diagonal = reference.diagonal();
    const std::vector<Seam> seams = find_seams(patches);
    const std::vector<Corner> corners = find_corners(patches, 3);
    RaySet set;
    set.name = "seams";
    set.description = "through points of " + std::to_string(seams.size()) + " shared edges and " +
                      std::to_string(corners.size()) + " corners of >= 3 patches";
    if (seams.empty() && corners.empty()) return set;
    set.base.rays.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        real point[3], normal[3] = {0, 0, 0};
        bool has_normal = false;
        const bool corner = seams.empty() || (!corners.empty() && i % 3 == 2);
        if (!corner) {
            const Seam &seam = seams[std::min(seams.size() - 1, size_t(rng.uniform() * seams.size()))];
            const real along = 0.02L + 0.96L * rng.uniform();
            real u, v, su[3];
            edge_parameter(seam.edge_a, along, u, v);
            // Normals on a patch edge are evaluated a hair inside: regular_normal rejects the
            // collapsed ones.
            has_normal = regular_normal(patches[seam.patch_a], u, v, point, normal, su);
            if (!has_normal) ref::evaluate(patches[seam.patch_a], u, v, point);
        } else {
            const Corner &c = corners[std::min(corners.size() - 1, size_t(rng.uniform() * corners.size()))];
            for (int k = 0; k < 3; ++k) point[k] = c.point[k];
            has_normal = c.has_normal;
            for (int k = 0; k < 3; ++k) normal[k] = c.normal[k];
        }
        real dir[3];
        const double pick = rng.uniform();
        if (has_normal && pick < 1.0 / 3) {
            const real sign = pick < 1.0 / 6 ? 1 : -1;
            for (int k = 0; k < 3; ++k) dir[k] = sign * normal[k];
        } else {
            random_direction(rng, dir);
        }
        const real length = (0.05L + 0.25L * rng.uniform()) * diagonal;
        set.base.rays.push_back(ray_through(point, dir, length));
    }
    return set;
}

RaySet pole_rays(const ref::Intersector &reference, size_t count, uint64_t seed) {
    SplitMix64 rng(seed);
    const real diagonal = reference.diagonal();
    const std::vector<CollapsedPoint> poles = find_collapsed_points(reference.patches());
    RaySet set;
    set.name = "poles";
    std::string where;
    for (const CollapsedPoint &p : poles) {
        char text[96];
        std::snprintf(text, sizeof text, "%s(%.6Lg, %.6Lg, %.6Lg)", where.empty() ? "" : ", ", p.point[0], p.point[1],
                      p.point[2]);
        where += text;
    }
    set.description = "through or within 1e-9..1e-3 diagonals of the collapsed edges " + where;
    if (poles.empty()) return set;
    set.base.rays.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        const CollapsedPoint &pole = poles[i % poles.size()];
        real dir[3];
        random_direction(rng, dir);
        real point[3] = {pole.point[0], pole.point[1], pole.point[2]};
        if (i % 4 >= 2) {
            // Pass beside the point: offset perpendicular to the ray by a log-uniform distance.
            real side[3], e[3];
            random_direction(rng, e);
            cross(dir, e, side);
            normalize(side);
            const real offset = std::pow(10.0L, -9 + 6 * real(rng.uniform())) * diagonal;
            for (int k = 0; k < 3; ++k) point[k] += offset * side[k];
        }
        const real length = (0.05L + 0.25L * rng.uniform()) * diagonal;
        set.base.rays.push_back(ray_through(point, dir, length));
    }
    return set;
}

RaySet leaving_rays(const ref::Intersector &reference, const Bounds &box, size_t count, uint64_t seed,
                    const std::vector<double> &spawn_tolerances, int threads) {
    RaySet set;
    set.name = "leaving";
    set.description = "from reference hits of random rays, cosine-distributed on both sides, "
                      "origin offset by ppm_hit_spawn_ray";
    if (count == 0) return set;
    // Primary rays: enough that `count` of them hit (about half of them do).
    const RaySet primary = random_rays(box, 3 * count + 64, derive_seed(seed, 1));
    const Truth truth = compute_truth(reference, primary.base.rays, threads);
    const double diagonal = double(reference.diagonal());
    SplitMix64 rng(derive_seed(seed, 2));

    struct Sample {
        double p[3], n[3], dir[3];
    };
    std::vector<Sample> samples;
    for (size_t i = 0; i < primary.size() && samples.size() < count; ++i) {
        if (truth.kind[i] != TruthKind::hit) continue;
        const TruthRoot &root = *truth.robust(i);
        const ppm_ray &r = primary.base.rays[i];
        Sample s;
        real n[3] = {root.normal[0], root.normal[1], root.normal[2]};
        if (!(n[0] != 0 || n[1] != 0 || n[2] != 0)) continue;
        normalize(n);
        for (int c = 0; c < 3; ++c) {
            s.p[c] = static_cast<double>(r.org[c] + static_cast<real>(root.t) * r.dir[c]);
            s.n[c] = static_cast<double>(n[c]);
        }
        // Cosine-distributed about +n for even samples, -n for odd ones.
        real t1[3], t2[3], a[3] = {1, 0, 0};
        if (std::fabs(n[0]) > 0.6L) a[0] = 0, a[1] = 1;
        cross(n, a, t1);
        normalize(t1);
        cross(n, t1, t2);
        const real r1 = rng.uniform(), phi = 2 * real(pi) * rng.uniform();
        const real sin_t = std::sqrt(r1), cos_t = std::sqrt(1 - r1);
        const real side = samples.size() % 2 == 0 ? 1 : -1;
        real dir[3];
        for (int c = 0; c < 3; ++c)
            dir[c] = sin_t * (std::cos(phi) * t1[c] + std::sin(phi) * t2[c]) + side * cos_t * n[c];
        normalize(dir);
        for (int c = 0; c < 3; ++c) s.dir[c] = static_cast<double>(dir[c]);
        samples.push_back(s);
    }

    auto spawn = [&](double tolerance) {
        RayBatch batch;
        batch.rays.reserve(samples.size());
        for (const Sample &s : samples) {
            ppm_hit hit{};
            hit.t = 1;
            for (int c = 0; c < 3; ++c) {
                hit.p[c] = s.p[c];
                hit.ng[c] = hit.ns[c] = s.n[c];
            }
            hit.p_error = tolerance * diagonal;
            ppm_ray ray;
            ppm_tools::check(ppm_hit_spawn_ray(&hit, s.dir, &ray), "ppm_hit_spawn_ray");
            batch.rays.push_back(ray);
        }
        return batch;
    };
    set.base = spawn(default_tolerance);
    for (double tolerance : spawn_tolerances)
        if (tolerance != default_tolerance) set.variants.emplace_back(tolerance, spawn(tolerance));
    return set;
}

} // namespace bench
