#include "ray_sets.h"

#include <algorithm>
#include <cmath>

namespace bench {

namespace {

constexpr double pi = 3.14159265358979323846;

struct Vec {
    double x, y, z;
};
Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec operator*(Vec a, double s) { return {a.x * s, a.y * s, a.z * s}; }
Vec cross(Vec a, Vec b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec normalized(Vec a) { return a * (1.0 / std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z)); }

class SplitMix64 {
public:
    explicit SplitMix64(uint64_t seed) : state_(seed) {}
    uint64_t next() {
        uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, 1) with 53 random bits.
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }

private:
    uint64_t state_;
};

ppm_ray make_ray(Vec org, Vec dir) {
    const Vec d = normalized(dir);
    return ppm_ray{{org.x, org.y, org.z}, 0.0, {d.x, d.y, d.z}, INFINITY};
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

RaySet random_rays(const Bounds &box, size_t count, uint64_t seed) {
    SplitMix64 rng(seed);
    const Vec center{box.center(0), box.center(1), box.center(2)};
    const double radius = box.diagonal();
    RaySet set{"random", {}};
    set.rays.reserve(count);
    while (set.rays.size() < count) {
        const double z = 2.0 * rng.uniform() - 1.0, phi = 2.0 * pi * rng.uniform();
        const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
        const Vec org = center + Vec{s * std::cos(phi), s * std::sin(phi), z} * radius;
        Vec target;
        target.x = box.lower[0] + (box.upper[0] - box.lower[0]) * rng.uniform();
        target.y = box.lower[1] + (box.upper[1] - box.lower[1]) * rng.uniform();
        target.z = box.lower[2] + (box.upper[2] - box.lower[2]) * rng.uniform();
        set.rays.push_back(make_ray(org, target - org));
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

    RaySet set{"camera", {}};
    set.rays.reserve(size_t(width) * height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double sx = (2.0 * (x + 0.5) / width - 1.0) * half_w;
            const double sy = (1.0 - 2.0 * (y + 0.5) / height) * half_h;
            set.rays.push_back(make_ray(eye, forward + right * sx + up * sy));
        }
    }
    return set;
}

} // namespace bench
