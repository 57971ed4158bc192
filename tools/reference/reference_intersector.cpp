// SPDX-License-Identifier: Apache-2.0
// Reference ray / Bezier patch intersection by world-space subdivision and long-double
// Newton; see reference_intersector.h for what it is and why it is independent of libppm.
#include "reference_intersector.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>

namespace ref {

namespace {

void bernstein(real t, real b[4]) {
    const real s = 1 - t;
    b[0] = s * s * s;
    b[1] = 3 * t * s * s;
    b[2] = 3 * t * t * s;
    b[3] = t * t * t;
}

void bernstein_derivative(real t, real b[4]) {
    const real s = 1 - t;
    b[0] = -3 * s * s;
    b[1] = 3 * s * s - 6 * t * s;
    b[2] = 6 * t * s - 3 * t * t;
    b[3] = 3 * t * t;
}

real dot3(const real a[3], const real b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

real norm3(const real a[3]) { return std::sqrt(dot3(a, a)); }

void cross3(const real a[3], const real b[3], real c[3]) {
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

// A sub-patch: its own control net and its parameter rectangle in the input patch.
struct Node {
    real cp[16][3];
    real u0, u1, v0, v1;
};

void lerp3(const real a[3], const real b[3], real t, real out[3]) {
    for (int c = 0; c < 3; ++c) out[c] = a[c] + t * (b[c] - a[c]);
}

// De Casteljau at 1/2 of the cubic q[0], q[s], q[2s], q[3s] into left and right halves.
void split_curve(const real (*q)[3], int stride, real (*left)[3], real (*right)[3]) {
    const real *p0 = q[0], *p1 = q[stride], *p2 = q[2 * stride], *p3 = q[3 * stride];
    real a[3], b[3], c[3], ab[3], bc[3], abc[3];
    lerp3(p0, p1, 0.5L, a);
    lerp3(p1, p2, 0.5L, b);
    lerp3(p2, p3, 0.5L, c);
    lerp3(a, b, 0.5L, ab);
    lerp3(b, c, 0.5L, bc);
    lerp3(ab, bc, 0.5L, abc);
    for (int k = 0; k < 3; ++k) {
        left[0][k] = p0[k];
        left[stride][k] = a[k];
        left[2 * stride][k] = ab[k];
        left[3 * stride][k] = abc[k];
        right[0][k] = abc[k];
        right[stride][k] = bc[k];
        right[2 * stride][k] = c[k];
        right[3 * stride][k] = p3[k];
    }
}

void split_u(const Node &n, Node &left, Node &right) {
    for (int i = 0; i < 4; ++i) split_curve(&n.cp[i * 4], 1, &left.cp[i * 4], &right.cp[i * 4]);
    const real mid = 0.5L * (n.u0 + n.u1);
    left.u0 = n.u0;
    left.u1 = mid;
    right.u0 = mid;
    right.u1 = n.u1;
    left.v0 = right.v0 = n.v0;
    left.v1 = right.v1 = n.v1;
}

void split_v(const Node &n, Node &left, Node &right) {
    for (int j = 0; j < 4; ++j) split_curve(&n.cp[j], 4, &left.cp[j], &right.cp[j]);
    const real mid = 0.5L * (n.v0 + n.v1);
    left.v0 = n.v0;
    left.v1 = mid;
    right.v0 = mid;
    right.v1 = n.v1;
    left.u0 = right.u0 = n.u0;
    left.u1 = right.u1 = n.u1;
}

// Length of the control polygon along u (max over rows) and along v (max over columns).
void net_lengths(const Node &n, real &along_u, real &along_v) {
    along_u = along_v = 0;
    for (int i = 0; i < 4; ++i) {
        real lu = 0, lv = 0;
        for (int j = 0; j < 3; ++j) {
            real du[3], dv[3];
            for (int c = 0; c < 3; ++c) {
                du[c] = n.cp[i * 4 + j + 1][c] - n.cp[i * 4 + j][c];
                dv[c] = n.cp[(j + 1) * 4 + i][c] - n.cp[j * 4 + i][c];
            }
            lu += norm3(du);
            lv += norm3(dv);
        }
        along_u = std::max(along_u, lu);
        along_v = std::max(along_v, lv);
    }
}

// Solves the 3x3 system A x = b (columns a0, a1, a2) by Gaussian elimination with partial
// pivoting. Returns false when singular or not finite.
bool solve3(const real a0[3], const real a1[3], const real a2[3], const real b[3], real x[3]) {
    real m[3][4];
    for (int r = 0; r < 3; ++r) {
        m[r][0] = a0[r];
        m[r][1] = a1[r];
        m[r][2] = a2[r];
        m[r][3] = b[r];
    }
    for (int c = 0; c < 3; ++c) {
        int pivot = c;
        for (int r = c + 1; r < 3; ++r)
            if (std::fabs(m[r][c]) > std::fabs(m[pivot][c])) pivot = r;
        if (!(std::fabs(m[pivot][c]) > 0)) return false;
        if (pivot != c)
            for (int k = 0; k < 4; ++k) std::swap(m[c][k], m[pivot][k]);
        for (int r = c + 1; r < 3; ++r) {
            const real f = m[r][c] / m[c][c];
            for (int k = c; k < 4; ++k) m[r][k] -= f * m[c][k];
        }
    }
    for (int r = 2; r >= 0; --r) {
        real s = m[r][3];
        for (int k = r + 1; k < 3; ++k) s -= m[r][k] * x[k];
        x[r] = s / m[r][r];
        if (!std::isfinite(x[r])) return false;
    }
    return true;
}

// The ray and everything constant while one patch is searched.
struct Query {
    const Patch &patch;
    const real *o, *d;
    real dd;   // |d|^2
    real dlen; // |d|
    real tnear, tfar;
    real scale; // magnitude of the coordinates involved: sets the rounding level
};

// Whether the normal n = S_u x S_v is unreliable: a derivative nearly vanishes (within 1e-8
// of the other: next to a collapsed edge, where the vanishing derivative is dominated by
// rounding) or the two are nearly parallel.
bool degenerate(const real su[3], const real sv[3], const real n[3]) {
    const real lu = norm3(su), lv = norm3(sv), ln = norm3(n);
    return !(ln > 1e-8L * lu * lv) || !(std::min(lu, lv) > 1e-8L * std::max(lu, lv));
}

void bernstein_second_derivative(real t, real b[4]) {
    b[0] = 6 * (1 - t);
    b[1] = 18 * t - 12;
    b[2] = 6 - 18 * t;
    b[3] = 6 * t;
}

// Second derivatives S_uu, S_uv, S_vv at (u, v).
void evaluate_second(const Patch &patch, real u, real v, real suu[3], real suv[3], real svv[3]) {
    real bu[4], bv[4], du[4], dv[4], ddu[4], ddv[4];
    bernstein(u, bu);
    bernstein(v, bv);
    bernstein_derivative(u, du);
    bernstein_derivative(v, dv);
    bernstein_second_derivative(u, ddu);
    bernstein_second_derivative(v, ddv);
    for (int c = 0; c < 3; ++c) {
        suu[c] = suv[c] = svv[c] = 0;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                const real p = patch.p[i * 4 + j][c];
                suu[c] += bv[i] * ddu[j] * p;
                suv[c] += dv[i] * du[j] * p;
                svv[c] += ddv[i] * bu[j] * p;
            }
    }
}

// Fills sin_angle, dip and degenerate_normal of a root from the surface's first and second
// fundamental forms at (u, v): the ray leaves the tangent plane at angle theta while the
// surface bends away from it with normal curvature kappa along the ray's direction, so the
// ray is on one side of the surface over a stretch whose largest depth is
// tan^2(theta) / (2 kappa).
void describe_root(const Query &q, Root &r) {
    real s[3], su[3], sv[3], suu[3], suv[3], svv[3], n[3];
    evaluate(q.patch, r.u, r.v, s, su, sv);
    evaluate_second(q.patch, r.u, r.v, suu, suv, svv);
    cross3(su, sv, n);
    const real nl = norm3(n);
    if (degenerate(su, sv, n)) {
        r.sin_angle = 0;
        r.dip = INFINITY;
        r.degenerate_normal = true;
        return;
    }
    for (real &x : n) x /= nl;
    const real dhat[3] = {q.d[0] / q.dlen, q.d[1] / q.dlen, q.d[2] / q.dlen};
    const real sin_angle = std::fabs(dot3(n, dhat));
    r.sin_angle = sin_angle;
    // The ray's direction in the tangent plane, w = a S_u + b S_v.
    const real e = dot3(su, su), f = dot3(su, sv), g = dot3(sv, sv);
    const real pu = dot3(dhat, su), pv = dot3(dhat, sv), det = e * g - f * f;
    const real a = (pu * g - pv * f) / det, b = (pv * e - pu * f) / det;
    const real first = e * a * a + 2 * f * a * b + g * b * b; // |w|^2 = cos^2(theta)
    const real second = dot3(suu, n) * a * a + 2 * dot3(suv, n) * a * b + dot3(svv, n) * b * b;
    const real kappa = first > 0 ? std::fabs(second) / first : 0;
    const real cos2 = std::max<real>(first, 0);
    r.dip = kappa > 0 && cos2 > 0 ? sin_angle * sin_angle / cos2 / (2 * kappa) : INFINITY;
}

// Newton on F(u, v, t) = S(u, v) - o - t d, starting at (u, v) with t the projection of
// S(u, v) on the ray; (u, v) may roam over `domain` (u0, u1, v0, v1). Returns true with the
// root on convergence to rounding level.
bool newton(const Query &q, const real domain[4], real &u, real &v, real &t, real &residual) {
    real s[3], su[3], sv[3];
    evaluate(q.patch, u, v, s);
    {
        real w[3] = {s[0] - q.o[0], s[1] - q.o[1], s[2] - q.o[2]};
        t = dot3(w, q.d) / q.dd;
    }
    const real converged = 64 * LDBL_EPSILON * q.scale;
    real best[4] = {INFINITY, u, v, t}; // residual, u, v, t
    auto finish = [&](bool ok) {
        ok = ok && best[0] <= 4 * converged;
        if (ok) {
            residual = best[0];
            u = best[1];
            v = best[2];
            t = best[3];
        }
        return ok;
    };
    real previous = INFINITY;
    int polish = -1; // steps still taken after convergence, to reach the rounding floor
    for (int iteration = 0; iteration < 80; ++iteration) {
        evaluate(q.patch, u, v, s, su, sv);
        real f[3], minus_f[3], md[3];
        for (int c = 0; c < 3; ++c) {
            f[c] = s[c] - q.o[c] - t * q.d[c];
            minus_f[c] = -f[c];
            md[c] = -q.d[c];
        }
        const real r = std::max({std::fabs(f[0]), std::fabs(f[1]), std::fabs(f[2])});
        if (!std::isfinite(r)) return finish(false);
        if (r < best[0]) {
            best[0] = r;
            best[1] = u;
            best[2] = v;
            best[3] = t;
        }
        if (r <= converged && polish < 0) polish = 2;
        if (polish == 0) return finish(true);
        if (polish > 0) --polish;
        // Stalled just above the threshold at the limit of the arithmetic: also converged.
        if (iteration > 8 && r >= previous && best[0] <= 4 * converged) return finish(true);
        previous = std::min(previous, r);
        real step[3];
        if (!solve3(su, sv, md, minus_f, step)) return finish(polish >= 0);
        u += step[0];
        v += step[1];
        t += step[2];
        if (!(u >= domain[0] && u <= domain[1] && v >= domain[2] && v <= domain[3])) return finish(polish >= 0);
    }
    return finish(polish >= 0);
}

// Damped Gauss-Newton minimisation over `domain` of the distance between S(u, v) and the
// (infinite) line o + t d, from (u, v). Returns the distance; t is the foot on the line.
real closest_approach(const Query &q, const real domain[4], real &u, real &v, real &t) {
    real dhat[3] = {q.d[0] / q.dlen, q.d[1] / q.dlen, q.d[2] / q.dlen};
    auto perpendicular = [&](const real w[3], real out[3]) {
        const real k = dot3(w, dhat);
        for (int c = 0; c < 3; ++c) out[c] = w[c] - k * dhat[c];
    };
    auto distance_at = [&](real uu, real vv, real r[3], real a[3], real b[3]) {
        real s[3], su[3], sv[3];
        evaluate(q.patch, uu, vv, s, su, sv);
        real w[3] = {s[0] - q.o[0], s[1] - q.o[1], s[2] - q.o[2]};
        perpendicular(w, r);
        perpendicular(su, a);
        perpendicular(sv, b);
        return norm3(r);
    };
    real r[3], a[3], b[3];
    real best = distance_at(u, v, r, a, b);
    real lambda = -1;
    for (int iteration = 0; iteration < 60 && best > 0; ++iteration) {
        const real aa = dot3(a, a), ab = dot3(a, b), bb = dot3(b, b);
        const real ar = dot3(a, r), br = dot3(b, r);
        if (lambda < 0) lambda = 1e-12L * (aa + bb);
        bool improved = false;
        for (int attempt = 0; attempt < 12 && !improved; ++attempt) {
            const real m00 = aa + lambda, m11 = bb + lambda, det = m00 * m11 - ab * ab;
            if (!(std::fabs(det) > 0)) {
                lambda = lambda * 10 + LDBL_MIN;
                continue;
            }
            const real du = (-ar * m11 + br * ab) / det, dv = (-br * m00 + ar * ab) / det;
            const real nu = std::clamp(u + du, domain[0], domain[1]);
            const real nv = std::clamp(v + dv, domain[2], domain[3]);
            real nr[3], na[3], nb[3];
            const real dist = distance_at(nu, nv, nr, na, nb);
            if (dist < best) {
                best = dist;
                u = nu;
                v = nv;
                std::copy(nr, nr + 3, r);
                std::copy(na, na + 3, a);
                std::copy(nb, nb + 3, b);
                lambda *= 0.25L;
                improved = true;
            } else {
                lambda *= 8;
            }
        }
        if (!improved) break;
    }
    real s[3];
    evaluate(q.patch, u, v, s);
    real w[3] = {s[0] - q.o[0], s[1] - q.o[1], s[2] - q.o[2]};
    t = dot3(w, q.d) / q.dd;
    return best;
}

enum class Transversality {
    unique,     // the ray crosses the sub-patch at most once
    not_proven, // the ray is within the spread of the sub-patch's normals of a tangent plane
    degenerate  // a normal vanishes (collapsed edge)
};

// Normals at the centre and the four corners of a small sub-patch. Over a sub-patch whose
// normals stay within a hemisphere, the surface is a graph over the centre's tangent plane,
// and along the ray the graph minus the ray's height has derivative proportional to -n.d:
// where n.d keeps one sign the difference is monotone and the ray crosses at most once.
// n.d is sampled at the five points; on a sub-patch of ~1e-6 of the model it is linear to
// far better than the margin (the sampled values must stay away from zero by more than their
// own spread), so the samples stand for the whole sub-patch.
Transversality transversality(const Query &q, const Node &n) {
    const real at[5][2] = {{0.5L, 0.5L}, {0, 0}, {1, 0}, {0, 1}, {1, 1}};
    real normal[5][3];
    for (int k = 0; k < 5; ++k) {
        real s[3], su[3], sv[3];
        evaluate(q.patch, n.u0 + at[k][0] * (n.u1 - n.u0), n.v0 + at[k][1] * (n.v1 - n.v0), s, su, sv);
        cross3(su, sv, normal[k]);
        const real l = norm3(normal[k]);
        if (degenerate(su, sv, normal[k])) return Transversality::degenerate;
        for (int c = 0; c < 3; ++c) normal[k][c] /= l;
    }
    const real side = dot3(normal[0], q.d) >= 0 ? 1 : -1;
    real lowest = INFINITY, highest = -INFINITY;
    for (int k = 0; k < 5; ++k) {
        if (dot3(normal[0], normal[k]) < 0.5L) return Transversality::not_proven;
        const real x = side * dot3(normal[k], q.d) / q.dlen;
        lowest = std::min(lowest, x);
        highest = std::max(highest, x);
    }
    return lowest > 0 && lowest > highest - lowest ? Transversality::unique : Transversality::not_proven;
}

bool box_hit(const Node &n, const Query &q, real pad) {
    real lo[3], hi[3];
    for (int c = 0; c < 3; ++c) {
        lo[c] = hi[c] = n.cp[0][c];
        for (int k = 1; k < 16; ++k) {
            lo[c] = std::min(lo[c], n.cp[k][c]);
            hi[c] = std::max(hi[c], n.cp[k][c]);
        }
    }
    real t0 = q.tnear - pad / q.dlen, t1 = q.tfar + pad / q.dlen;
    for (int c = 0; c < 3; ++c) {
        const real l = lo[c] - pad, h = hi[c] + pad;
        if (q.d[c] == 0) {
            if (q.o[c] < l || q.o[c] > h) return false;
            continue;
        }
        real a = (l - q.o[c]) / q.d[c], b = (h - q.o[c]) / q.d[c];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
        if (t0 > t1) return false;
    }
    // A second slab, normal to the sub-patch's diagonals: a small sub-patch is nearly flat,
    // and a ray close to tangent crosses this thin slab over a much shorter stretch than it
    // runs through the box.
    real diag1[3], diag2[3], normal[3];
    for (int c = 0; c < 3; ++c) {
        diag1[c] = n.cp[15][c] - n.cp[0][c];
        diag2[c] = n.cp[12][c] - n.cp[3][c];
    }
    cross3(diag1, diag2, normal);
    const real length = norm3(normal);
    if (!(length > 0)) return true;
    for (real &x : normal) x /= length;
    real lo_n = dot3(normal, n.cp[0]), hi_n = lo_n;
    for (int k = 1; k < 16; ++k) {
        const real x = dot3(normal, n.cp[k]);
        lo_n = std::min(lo_n, x);
        hi_n = std::max(hi_n, x);
    }
    lo_n -= pad;
    hi_n += pad;
    const real on = dot3(normal, q.o), dn = dot3(normal, q.d);
    if (dn == 0) return on >= lo_n && on <= hi_n;
    real a = (lo_n - on) / dn, b = (hi_n - on) / dn;
    if (a > b) std::swap(a, b);
    return std::max(t0, a) <= std::min(t1, b);
}

real box_extent(const Node &n) {
    real extent = 0;
    for (int c = 0; c < 3; ++c) {
        real lo = n.cp[0][c], hi = n.cp[0][c];
        for (int k = 1; k < 16; ++k) {
            lo = std::min(lo, n.cp[k][c]);
            hi = std::max(hi, n.cp[k][c]);
        }
        extent = std::max(extent, hi - lo);
    }
    return extent;
}

} // namespace

bool load_bpt(const std::string &path, std::vector<Patch> &patches, std::string &error) {
    std::ifstream in(path);
    if (!in) {
        error = "cannot open " + path;
        return false;
    }
    std::vector<std::string> tokens{std::istream_iterator<std::string>(in), std::istream_iterator<std::string>()};
    size_t k = 0;
    auto number = [&](double &x) {
        if (k >= tokens.size()) return false;
        char *end = nullptr;
        x = std::strtod(tokens[k].c_str(), &end);
        if (end == tokens[k].c_str() || *end != '\0' || !std::isfinite(x)) return false;
        ++k;
        return true;
    };
    double count = 0;
    if (!number(count) || count < 1 || count != std::floor(count)) {
        error = "bad patch count";
        return false;
    }
    patches.assign(static_cast<size_t>(count), Patch{});
    for (Patch &p : patches) {
        double du = 0, dv = 0;
        if (!number(du) || !number(dv) || du != 3 || dv != 3) {
            error = "bad degree line";
            return false;
        }
        for (int i = 0; i < 16; ++i)
            for (int c = 0; c < 3; ++c) {
                double x = 0;
                if (!number(x)) {
                    error = "bad coordinate";
                    return false;
                }
                p.p[i][c] = x; // parsed as double: the precision libppm intersects
            }
    }
    if (k != tokens.size()) {
        error = "trailing content";
        return false;
    }
    return true;
}

void evaluate(const Patch &patch, real u, real v, real s[3], real su[3], real sv[3]) {
    real bu[4], bv[4], du[4], dv[4];
    bernstein(u, bu);
    bernstein(v, bv);
    bernstein_derivative(u, du);
    bernstein_derivative(v, dv);
    for (int c = 0; c < 3; ++c) {
        real value = 0, d_u = 0, d_v = 0;
        for (int i = 0; i < 4; ++i) {
            real row = 0, row_u = 0;
            for (int j = 0; j < 4; ++j) {
                row += bu[j] * patch.p[i * 4 + j][c];
                row_u += du[j] * patch.p[i * 4 + j][c];
            }
            value += bv[i] * row;
            d_u += bv[i] * row_u;
            d_v += dv[i] * row;
        }
        s[c] = value;
        if (su) su[c] = d_u;
        if (sv) sv[c] = d_v;
    }
}

Intersector::Intersector(std::vector<Patch> patches, Options options)
    : patches_(std::move(patches)), options_(options) {
    for (int c = 0; c < 3; ++c) {
        lower_[c] = INFINITY;
        upper_[c] = -INFINITY;
    }
    for (const Patch &p : patches_)
        for (const auto &q : p.p)
            for (int c = 0; c < 3; ++c) {
                lower_[c] = std::min(lower_[c], q[c]);
                upper_[c] = std::max(upper_[c], q[c]);
            }
    real e[3] = {upper_[0] - lower_[0], upper_[1] - lower_[1], upper_[2] - lower_[2]};
    diagonal_ = norm3(e);
    if (options_.leaf_size <= 0) options_.leaf_size = 1e-6L * diagonal_;
    if (options_.near_distance <= 0) options_.near_distance = 2e-9L * diagonal_;
}

void Intersector::bounds(real lower[3], real upper[3]) const {
    std::copy(lower_, lower_ + 3, lower);
    std::copy(upper_, upper_ + 3, upper);
}

Result Intersector::intersect(const real o[3], const real d[3], real tnear, real tfar) const {
    Result result;
    for (int index = 0; index < static_cast<int>(patches_.size()) && result.decided; ++index)
        intersect_patch(index, o, d, tnear, tfar, result);
    std::sort(result.roots.begin(), result.roots.end(),
              [](const Root &a, const Root &b) { return a.t != b.t ? a.t < b.t : a.patch < b.patch; });
    return result;
}

void Intersector::intersect_patch(int index, const real o[3], const real d[3], real tnear, real tfar,
                                  Result &result) const {
    const Patch &patch = patches_[index];
    real scale = std::max({std::fabs(o[0]), std::fabs(o[1]), std::fabs(o[2])});
    for (const auto &q : patch.p) scale = std::max({scale, std::fabs(q[0]), std::fabs(q[1]), std::fabs(q[2])});
    const Query q{patch, o, d, dot3(d, d), norm3(d), tnear, tfar, scale};
    // Boxes are exact hulls; the pad covers rounding and finds near misses for the caller.
    const real pad = options_.near_distance + 64 * LDBL_EPSILON * scale;
    // Long-double evaluation rounds at about 1e-19 of the coordinates.
    const real exact_distance = 16 * LDBL_EPSILON * scale;
    const real merge_distance = 1e-12L * diagonal_;
    const real fine_leaf = 1e-9L * diagonal_;

    std::vector<Root> found;
    std::vector<Node> stack(1);
    Node &first = stack[0];
    for (int k = 0; k < 16; ++k)
        for (int c = 0; c < 3; ++c) first.cp[k][c] = patch.p[k][c];
    first.u0 = first.v0 = 0;
    first.u1 = first.v1 = 1;

    while (!stack.empty()) {
        if (++result.nodes > options_.max_nodes) {
            result.decided = false;
            return;
        }
        const Node n = stack.back();
        stack.pop_back();
        if (!box_hit(n, q, pad)) continue;
        const real wu = n.u1 - n.u0, wv = n.v1 - n.v0;
        const bool tiny_domain = wu <= 1e-17L && wv <= 1e-17L;
        const real extent = box_extent(n);
        // A leaf-sized sub-patch is subdivided further (down to fine_leaf) while the ray is
        // too close to tangent for it to prove at most one root there.
        Transversality shape = Transversality::degenerate;
        if (extent <= options_.leaf_size && !tiny_domain) shape = transversality(q, n);
        const bool refine = shape == Transversality::not_proven && extent > fine_leaf;
        if ((extent > options_.leaf_size || refine) && !tiny_domain) {
            real along_u, along_v;
            net_lengths(n, along_u, along_v);
            Node a, b;
            if ((along_u >= along_v && wu > 1e-17L) || wv <= 1e-17L)
                split_u(n, a, b);
            else
                split_v(n, a, b);
            stack.push_back(a);
            stack.push_back(b);
            continue;
        }

        // Leaf. Newton may roam one leaf width around it; roots count only inside the leaf
        // (with a rounding margin), the neighbours find the others.
        ++result.leaves;
        const real domain[4] = {std::max<real>(0, n.u0 - wu), std::min<real>(1, n.u1 + wu),
                                std::max<real>(0, n.v0 - wv), std::min<real>(1, n.v1 + wv)};
        // Newton may cross the patch's edges on its way (the polynomial extends beyond
        // them); a root a hair outside [0, 1] is clamped onto the edge.
        const real roam[4] = {n.u0 - wu, n.u1 + wu, n.v0 - wv, n.v1 + wv};
        const real mu = 1e-6L * wu + 4 * LDBL_EPSILON, mv = 1e-6L * wv + 4 * LDBL_EPSILON;
        auto inside = [&](real u, real v) {
            return u >= n.u0 - mu && u <= n.u1 + mu && v >= n.v0 - mv && v <= n.v1 + mv;
        };
        const real starts[5][2] = {{0.5L, 0.5L}, {0.25L, 0.25L}, {0.75L, 0.25L}, {0.25L, 0.75L}, {0.75L, 0.75L}};
        bool any = false;
        for (int s = 0; s < 5; ++s) {
            real u = n.u0 + starts[s][0] * wu, v = n.v0 + starts[s][1] * wv, t, residual;
            bool converged = newton(q, roam, u, v, t, residual);
            if (converged) {
                const real edge = 1e-14L; // parameter slack at the patch's edges
                converged = u >= -edge && u <= 1 + edge && v >= -edge && v <= 1 + edge;
                u = std::clamp<real>(u, 0, 1);
                v = std::clamp<real>(v, 0, 1);
            }
            if (converged && inside(u, v) && t >= tnear && t <= tfar) {
                Root r;
                r.patch = index;
                r.u = u;
                r.v = v;
                r.t = t;
                r.distance = residual;
                r.kind = RootKind::proper;
                describe_root(q, r);
                found.push_back(r);
                any = true;
            }
            // Where the ray provably crosses the leaf at most once, a converged centre start
            // decides. Otherwise (tangent within the finest leaves, collapsed edges) try the
            // other starts as well.
            if (s == 0 && converged && shape == Transversality::unique) break;
        }
        // A leaf the ray crosses transversally holds no tangent touch (the ray is parallel to
        // the tangent plane there) and no collapsed edge (its normals are all defined): what
        // Newton did not find in it is not there.
        if (any || shape == Transversality::unique) continue;

        real u = n.u0 + 0.5L * wu, v = n.v0 + 0.5L * wv, t;
        const real distance = closest_approach(q, domain, u, v, t);
        if (!(distance <= options_.near_distance) || !inside(u, v) || !(t >= tnear && t <= tfar)) continue;
        Root r;
        r.patch = index;
        r.u = u;
        r.v = v;
        r.t = t;
        r.distance = distance;
        describe_root(q, r);
        r.kind = distance <= exact_distance ? RootKind::singular : RootKind::tangent;
        found.push_back(r);
    }

    // Deduplicate: the same point found from several leaves of this patch. Real roots
    // (proper, singular) merge when their points along the ray coincide to merge_distance;
    // tangent candidates merge within a few leaf sizes of each other, keeping the closest.
    std::sort(found.begin(), found.end(), [](const Root &a, const Root &b) { return a.t < b.t; });
    std::vector<Root> real_roots, tangents;
    for (const Root &r : found) {
        if (r.kind != RootKind::tangent) {
            if (!real_roots.empty() && (r.t - real_roots.back().t) * q.dlen <= merge_distance) {
                Root &kept = real_roots.back();
                const bool better = (r.kind == RootKind::proper && kept.kind != RootKind::proper) ||
                                    (r.kind == kept.kind && r.distance < kept.distance);
                if (better) kept = r;
                continue;
            }
            real_roots.push_back(r);
        } else {
            if (!tangents.empty() && (r.t - tangents.back().t) * q.dlen <= 4 * options_.leaf_size) {
                if (r.distance < tangents.back().distance) tangents.back() = r;
                continue;
            }
            tangents.push_back(r);
        }
    }
    result.roots.insert(result.roots.end(), tangents.begin(), tangents.end());
    result.roots.insert(result.roots.end(), real_roots.begin(), real_roots.end());
}

} // namespace ref
