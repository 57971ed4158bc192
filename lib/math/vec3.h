// SPDX-License-Identifier: Apache-2.0
// Double-precision 3-vector and the few operations the geometry code needs.
#pragma once

#include <algorithm>
#include <cmath>

namespace ppm {

struct Vec3 {
    double x = 0, y = 0, z = 0;

    constexpr Vec3() = default;
    constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    static Vec3 from(const double *p) { return {p[0], p[1], p[2]}; }
    void store(double *p) const {
        p[0] = x;
        p[1] = y;
        p[2] = z;
    }

    double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    double &operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    Vec3 operator+(const Vec3 &b) const { return {x + b.x, y + b.y, z + b.z}; }
    Vec3 operator-(const Vec3 &b) const { return {x - b.x, y - b.y, z - b.z}; }
    Vec3 operator-() const { return {-x, -y, -z}; }
    Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
    Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
    Vec3 &operator+=(const Vec3 &b) {
        x += b.x;
        y += b.y;
        z += b.z;
        return *this;
    }
    Vec3 &operator-=(const Vec3 &b) {
        x -= b.x;
        y -= b.y;
        z -= b.z;
        return *this;
    }
    Vec3 &operator*=(double s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
};

inline Vec3 operator*(double s, const Vec3 &v) { return v * s; }
inline double dot(const Vec3 &a, const Vec3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3 &a, const Vec3 &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length2(const Vec3 &v) { return dot(v, v); }
inline double length(const Vec3 &v) { return std::sqrt(dot(v, v)); }
// Whether |v|^2 = l2 = 1 + d is so near 1 (|d| < 1e-8) that first-order terms are exact to
// rounding: 1 / l2 = 1 - d, |v| = 1 + d / 2, 1 / |v| = 1 - d / 2, with errors of d^2, d^2 / 8
// and 3 d^2 / 8, all below half an ulp. The renderer's directions are unit vectors, and these
// spare a square root and divisions on every ray's critical path.
inline bool nearly_unit(double l2) { return std::fabs(l2 - 1) < 1e-8; }

// v / |v|; a nearly unit v (a direction spawned from a unit one, a sphere's offset scaled by
// 1 / r) without a square root or division.
inline Vec3 normalize(const Vec3 &v) {
    const double l2 = dot(v, v);
    if (nearly_unit(l2)) return v * (1 - 0.5 * (l2 - 1));
    return v / std::sqrt(l2);
}
// std::min/max rather than fmin/fmax: these inline to single instructions, and coordinates
// are checked to be finite where they enter the library.
inline Vec3 vmin(const Vec3 &a, const Vec3 &b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
inline Vec3 vmax(const Vec3 &a, const Vec3 &b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
inline double max_abs_component(const Vec3 &v) {
    return std::max(std::fabs(v.x), std::max(std::fabs(v.y), std::fabs(v.z)));
}
inline bool is_finite(const Vec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Orthonormal basis around a unit vector (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited"): branch-free and accurate for every direction.
inline void orthonormal_basis(const Vec3 &n, Vec3 &b1, Vec3 &b2) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    b1 = {1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
    b2 = {b, sign + n.y * n.y * a, -n.y};
}

struct Box3 {
    Vec3 lower{INFINITY, INFINITY, INFINITY};
    Vec3 upper{-INFINITY, -INFINITY, -INFINITY};

    void extend(const Vec3 &p) {
        lower = vmin(lower, p);
        upper = vmax(upper, p);
    }
    void extend(const Box3 &b) {
        lower = vmin(lower, b.lower);
        upper = vmax(upper, b.upper);
    }
    bool empty() const { return !(lower.x <= upper.x && lower.y <= upper.y && lower.z <= upper.z); }
    Vec3 center() const { return (lower + upper) * 0.5; }
    double diagonal() const { return length(upper - lower); }
};

// Affine map stored as the top three rows of a row-major 4x4 matrix.
struct Affine {
    double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

    Vec3 point(const Vec3 &p) const {
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
    }
    Vec3 vector(const Vec3 &v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    double determinant() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
    // Normals transform with the inverse transpose, which is the cofactor matrix divided by
    // the determinant; only the determinant's sign matters once the result is normalised.
    Vec3 normal(const Vec3 &n) const {
        const Vec3 c0{m[1][1] * m[2][2] - m[1][2] * m[2][1], m[1][2] * m[2][0] - m[1][0] * m[2][2],
                      m[1][0] * m[2][1] - m[1][1] * m[2][0]};
        const Vec3 c1{m[0][2] * m[2][1] - m[0][1] * m[2][2], m[0][0] * m[2][2] - m[0][2] * m[2][0],
                      m[0][1] * m[2][0] - m[0][0] * m[2][1]};
        const Vec3 c2{m[0][1] * m[1][2] - m[0][2] * m[1][1], m[0][2] * m[1][0] - m[0][0] * m[1][2],
                      m[0][0] * m[1][1] - m[0][1] * m[1][0]};
        return Vec3{dot(c0, n), dot(c1, n), dot(c2, n)} * std::copysign(1.0, determinant());
    }
};

} // namespace ppm
