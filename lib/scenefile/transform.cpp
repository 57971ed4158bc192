// SPDX-License-Identifier: Apache-2.0
#include "scenefile/transform.h"

#include "core/error.h"
#include "math/limits.h"

#include <cmath>

namespace ppm {

namespace {

constexpr double kPi = 3.14159265358979323846;

Affine from_columns(const Vec3 &x, const Vec3 &y, const Vec3 &z, const Vec3 &t) {
    Affine a;
    const Vec3 columns[4] = {x, y, z, t};
    for (int c = 0; c < 4; ++c) {
        a.m[0][c] = columns[c].x;
        a.m[1][c] = columns[c].y;
        a.m[2][c] = columns[c].z;
    }
    return a;
}

Vec3 to_vec3(const std::array<double, 3> &a) { return {a[0], a[1], a[2]}; }

// Mitsuba 3's Transform4f::look_at: +z towards the target, +x = left, +y = the up vector
// made perpendicular.
Affine look_at(const JsonNode &node) {
    node.allow_only({"origin", "target", "up"});
    const Vec3 origin = to_vec3(node.at("origin").vec3());
    const Vec3 target = to_vec3(node.at("target").vec3());
    const Vec3 up = to_vec3(node.vec3_or("up", {0, 1, 0}));
    const Vec3 forward_raw = target - origin;
    if (length(forward_raw) == 0) node.fail("origin and target are the same point");
    const Vec3 forward = normalize(forward_raw);
    const Vec3 left_raw = cross(up, forward);
    if (!(length(left_raw) > 1e-12 * length(up))) node.fail("up is zero or parallel to the view direction");
    const Vec3 left = normalize(left_raw);
    return from_columns(left, cross(forward, left), forward, origin);
}

Affine parse_operation(const JsonNode &node) {
    node.require_object();
    if (node.value().size() != 1)
        node.fail("a transform operation has exactly one key: translate, scale, rotate, matrix or look_at");
    node.allow_only({"translate", "scale", "rotate", "matrix", "look_at"});
    Affine a;
    if (node.has("translate")) {
        const Vec3 t = to_vec3(node.at("translate").vec3());
        a.m[0][3] = t.x, a.m[1][3] = t.y, a.m[2][3] = t.z;
    } else if (node.has("scale")) {
        const JsonNode s = node.at("scale");
        const Vec3 k = s.is_number() ? Vec3{s.number(), s.number(), s.number()} : to_vec3(s.vec3());
        if (k.x == 0 || k.y == 0 || k.z == 0) s.fail("a scale must not be zero");
        a.m[0][0] = k.x, a.m[1][1] = k.y, a.m[2][2] = k.z;
    } else if (node.has("rotate")) {
        const JsonNode r = node.at("rotate");
        r.allow_only({"axis", "angle"});
        const Vec3 axis_raw = to_vec3(r.at("axis").vec3());
        if (length(axis_raw) == 0) r.at("axis").fail("the rotation axis must not be zero");
        const Vec3 k = normalize(axis_raw);
        const double angle = r.at("angle").number() * kPi / 180;
        const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
        // Rodrigues' formula: right-handed rotation about k.
        const double rot[3][3] = {{t * k.x * k.x + c, t * k.x * k.y - s * k.z, t * k.x * k.z + s * k.y},
                                  {t * k.x * k.y + s * k.z, t * k.y * k.y + c, t * k.y * k.z - s * k.x},
                                  {t * k.x * k.z - s * k.y, t * k.y * k.z + s * k.x, t * k.z * k.z + c}};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) a.m[i][j] = rot[i][j];
    } else if (node.has("matrix")) {
        const JsonNode m = node.at("matrix");
        m.require_array();
        if (m.size() != 16) m.fail("expected 16 numbers (a row-major 4x4 matrix)");
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) a.m[i][j] = m[static_cast<std::size_t>(4 * i + j)].number();
        for (int j = 0; j < 4; ++j)
            if (m[static_cast<std::size_t>(12 + j)].number() != (j == 3 ? 1.0 : 0.0))
                m.fail("the last row must be 0 0 0 1 (an affine transform)");
    } else {
        a = look_at(node.at("look_at"));
    }
    return a;
}

} // namespace

bool is_identity(const Affine &a) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j)
            if (a.m[i][j] != (i == j ? 1.0 : 0.0)) return false;
    return true;
}

std::array<double, 16> matrix16(const Affine &a) {
    std::array<double, 16> out{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) out[static_cast<std::size_t>(4 * i + j)] = a.m[i][j];
    out[15] = 1;
    return out;
}

Affine then(const Affine &a, const Affine &b) {
    Affine r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
            double sum = j == 3 ? b.m[i][3] : 0;
            for (int k = 0; k < 3; ++k) sum += b.m[i][k] * a.m[k][j];
            r.m[i][j] = sum;
        }
    return r;
}

Affine parse_transform(const JsonNode &node) {
    Affine result;
    if (node.is_array()) {
        for (std::size_t i = 0; i < node.size(); ++i) result = then(result, parse_operation(node[i]));
    } else {
        result = parse_operation(node);
    }
    const double det = result.determinant();
    if (!(std::fabs(det) > 1e-300) || !std::isfinite(det)) node.fail("the transform is singular or not finite");
    for (int row = 0; row < 3; ++row)
        if (!within(result.m[row][3], kCoordinateLimit))
            node.fail("the transform moves the origin to " + format_number(result.m[row][3]) + ", beyond +-" +
                      format_number(kCoordinateLimit) + " (the limit of scene coordinates)");
    return result;
}

} // namespace ppm
