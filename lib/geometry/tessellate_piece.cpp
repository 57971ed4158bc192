// SPDX-License-Identifier: Apache-2.0
#include "geometry/tessellate_piece.h"

#include <algorithm>

namespace ppm {
namespace tess {

namespace {

class PieceBuilder {
public:
    PieceBuilder(const BezierPatch &patch, Piece &piece)
        : patch_(patch), piece_(piece), scale_(control_bounds(patch).diagonal()) {}

    uint32_t vertex(const Vec3 &p, double u, double v, bool border) {
        const uint32_t id = uint32_t(piece_.uvs.size() / 2);
        p.store(push(piece_.positions, 3));
        geometric_normal(patch_, u, v, scale_).store(push(piece_.normals, 3));
        piece_.uvs.push_back(u);
        piece_.uvs.push_back(v);
        piece_.on_border.push_back(border);
        return id;
    }
    uint32_t vertex(double u, double v) { return vertex(evaluate(patch_, u, v), u, v, false); }

    // Orders the corners counter-clockwise in (u, v), so that the triangle's winding normal
    // agrees with dS/du x dS/dv.
    void triangle(uint32_t a, uint32_t b, uint32_t c) {
        const double *uv = piece_.uvs.data();
        const double area = (uv[2 * b] - uv[2 * a]) * (uv[2 * c + 1] - uv[2 * a + 1]) -
                            (uv[2 * b + 1] - uv[2 * a + 1]) * (uv[2 * c] - uv[2 * a]);
        if (area < 0) std::swap(b, c);
        piece_.indices.insert(piece_.indices.end(), {a, b, c});
    }

    // Two triangles, split along the diagonal whose midpoint lies closer to the surface point
    // at the cell's centre.
    void quad(uint32_t v00, uint32_t v10, uint32_t v11, uint32_t v01, double uc, double vc) {
        const Vec3 centre = evaluate(patch_, uc, vc);
        const double d1 = length2((position(v00) + position(v11)) * 0.5 - centre);
        const double d2 = length2((position(v10) + position(v01)) * 0.5 - centre);
        if (d1 <= d2) {
            triangle(v00, v10, v11);
            triangle(v00, v11, v01);
        } else {
            triangle(v00, v10, v01);
            triangle(v10, v11, v01);
        }
    }

    // Triangulates the strip between the outer sequence (patch border) and the inner one (an
    // outermost row of the inner grid), both ordered by the parameter along the side: always
    // advance on the side whose next segment's midpoint comes first.
    void stitch(const std::vector<uint32_t> &outer, const std::vector<double> &outer_t,
                const std::vector<uint32_t> &inner, const std::vector<double> &inner_t) {
        size_t a = 0, b = 0;
        while (a + 1 < outer.size() || b + 1 < inner.size()) {
            const bool advance_outer =
                b + 1 == inner.size() ||
                (a + 1 < outer.size() && outer_t[a] + outer_t[a + 1] <= inner_t[b] + inner_t[b + 1]);
            if (advance_outer) {
                triangle(outer[a], outer[a + 1], inner[b]);
                ++a;
            } else {
                triangle(outer[a], inner[b + 1], inner[b]);
                ++b;
            }
        }
    }

    Vec3 position(uint32_t id) const { return Vec3::from(&piece_.positions[3 * size_t(id)]); }

private:
    static double *push(std::vector<double> &values, size_t n) {
        values.resize(values.size() + n);
        return values.data() + values.size() - n;
    }

    const BezierPatch &patch_;
    Piece &piece_;
    double scale_;
};

} // namespace

Piece build_grid(const BezierPatch &patch, uint32_t n) {
    Piece piece;
    PieceBuilder builder(patch, piece);
    Edge edges[4];
    std::vector<Vec3> points[4];
    for (int s = 0; s < 4; ++s) {
        edges[s] = patch_edge(patch, s);
        points[s] = edge_points(edges[s], n);
    }
    std::vector<uint32_t> ids(size_t(n + 1) * (n + 1));
    for (uint32_t j = 0; j <= n; ++j)
        for (uint32_t i = 0; i <= n; ++i) {
            const double u = double(i) / n, v = double(j) / n;
            const Vec3 *border = j == 0   ? &side_point(points[side_v0], edges[side_v0], i, n)
                                 : j == n ? &side_point(points[side_v1], edges[side_v1], i, n)
                                 : i == 0 ? &side_point(points[side_u0], edges[side_u0], j, n)
                                 : i == n ? &side_point(points[side_u1], edges[side_u1], j, n)
                                          : nullptr;
            ids[size_t(j) * (n + 1) + i] = border ? builder.vertex(*border, u, v, true) : builder.vertex(u, v);
        }
    piece.indices.reserve(size_t(6) * n * n);
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) {
            const size_t k = size_t(j) * (n + 1) + i;
            builder.quad(ids[k], ids[k + 1], ids[k + n + 2], ids[k + n + 1], (i + 0.5) / n, (j + 0.5) / n);
        }
    return piece;
}

Piece build_adaptive(const BezierPatch &patch, const Edge edges[4], const uint32_t segments[4],
                     const std::vector<double> &us, const std::vector<double> &vs) {
    Piece piece;
    PieceBuilder builder(patch, piece);
    const uint32_t nu = uint32_t(us.size() - 1), nv = uint32_t(vs.size() - 1);
    const auto u_at = [&](uint32_t i) { return us[i]; };
    const auto v_at = [&](uint32_t j) { return vs[j]; };

    const uint32_t c00 = builder.vertex(patch.at(0, 0), 0, 0, true);
    const uint32_t c10 = builder.vertex(patch.at(0, 3), 1, 0, true);
    const uint32_t c11 = builder.vertex(patch.at(3, 3), 1, 1, true);
    const uint32_t c01 = builder.vertex(patch.at(3, 0), 0, 1, true);
    const uint32_t side_start[4] = {c00, c10, c01, c00}, side_end[4] = {c10, c11, c11, c01};

    std::vector<uint32_t> inner((nu - 1) * size_t(nv - 1));
    const auto inner_id = [&](uint32_t i, uint32_t j) -> uint32_t & {
        return inner[(j - 1) * size_t(nu - 1) + (i - 1)];
    };
    for (uint32_t j = 1; j < nv; ++j)
        for (uint32_t i = 1; i < nu; ++i) inner_id(i, j) = builder.vertex(u_at(i), v_at(j));
    for (uint32_t j = 1; j + 1 < nv; ++j)
        for (uint32_t i = 1; i + 1 < nu; ++i)
            builder.quad(inner_id(i, j), inner_id(i + 1, j), inner_id(i + 1, j + 1), inner_id(i, j + 1),
                         (u_at(i) + u_at(i + 1)) / 2, (v_at(j) + v_at(j + 1)) / 2);

    for (int s = 0; s < 4; ++s) {
        const bool along_u = s == side_v0 || s == side_v1;
        const double fixed = s == side_v0 || s == side_u0 ? 0.0 : 1.0;
        // The inner row or column next to this side.
        std::vector<uint32_t> row;
        std::vector<double> row_t;
        if (along_u) {
            const uint32_t j = s == side_v0 ? 1 : nv - 1;
            for (uint32_t i = 1; i < nu; ++i) {
                row.push_back(inner_id(i, j));
                row_t.push_back(u_at(i));
            }
        } else {
            const uint32_t i = s == side_u0 ? 1 : nu - 1;
            for (uint32_t j = 1; j < nv; ++j) {
                row.push_back(inner_id(i, j));
                row_t.push_back(v_at(j));
            }
        }
        const Edge &e = edges[s];
        if (e.collapsed) {
            for (size_t k = 0; k + 1 < row.size(); ++k) {
                const double t = (row_t[k] + row_t[k + 1]) / 2;
                const uint32_t apex =
                    along_u ? builder.vertex(e.c[0], t, fixed, true) : builder.vertex(e.c[0], fixed, t, true);
                builder.triangle(apex, row[k], row[k + 1]);
            }
            continue;
        }
        const uint32_t n = segments[s];
        const std::vector<Vec3> points = edge_points(e, n);
        std::vector<uint32_t> outer{side_start[s]};
        std::vector<double> outer_t{0.0};
        for (uint32_t m = 1; m < n; ++m) {
            const double t = double(m) / n;
            outer.push_back(along_u ? builder.vertex(side_point(points, e, m, n), t, fixed, true)
                                    : builder.vertex(side_point(points, e, m, n), fixed, t, true));
            outer_t.push_back(t);
        }
        outer.push_back(side_end[s]);
        outer_t.push_back(1.0);
        builder.stitch(outer, outer_t, row, row_t);
    }
    return piece;
}

} // namespace tess
} // namespace ppm
