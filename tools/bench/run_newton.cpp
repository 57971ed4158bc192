// SPDX-License-Identifier: Apache-2.0
// The naive methods of the original course project, kept to show where they fail: every
// patch whose control-point box the ray crosses is searched by plain Newton iteration on
// F(u, v, t) = S(u, v) - o - t d = 0 from a few fixed starting points, and the closest root
// with (u, v) in [0, 1]^2 and t in (tnear, tfar] wins. No subdivision, no interval test, no
// acceleration structure beyond the per-patch boxes, which are tested one after the other.
#include "method.h"
#include "rng.h"

#include <algorithm>
#include <cmath>

namespace bench {

namespace {

struct Box {
    double lower[3], upper[3];
};

void bernstein(double t, double b[4], double d[4]) {
    const double s = 1.0 - t;
    b[0] = s * s * s;
    b[1] = 3.0 * t * s * s;
    b[2] = 3.0 * t * t * s;
    b[3] = t * t * t;
    d[0] = -3.0 * s * s;
    d[1] = 3.0 * s * s - 6.0 * t * s;
    d[2] = 6.0 * t * s - 3.0 * t * t;
    d[3] = 3.0 * t * t;
}

// S(u, v), dS/du, dS/dv of the patch with control points P (48 doubles).
void evaluate(const double *P, double u, double v, double s[3], double su[3], double sv[3]) {
    double bu[4], du[4], bv[4], dv[4];
    bernstein(u, bu, du);
    bernstein(v, bv, dv);
    for (int c = 0; c < 3; ++c) s[c] = su[c] = sv[c] = 0;
    for (int i = 0; i < 4; ++i) {
        double row[3] = {0, 0, 0}, row_u[3] = {0, 0, 0};
        for (int j = 0; j < 4; ++j)
            for (int c = 0; c < 3; ++c) {
                row[c] += bu[j] * P[(i * 4 + j) * 3 + c];
                row_u[c] += du[j] * P[(i * 4 + j) * 3 + c];
            }
        for (int c = 0; c < 3; ++c) {
            s[c] += bv[i] * row[c];
            su[c] += bv[i] * row_u[c];
            sv[c] += dv[i] * row[c];
        }
    }
}

bool box_hit(const Box &b, const ppm_ray &r) {
    double t0 = r.tnear, t1 = r.tfar;
    for (int c = 0; c < 3; ++c) {
        if (r.dir[c] == 0) {
            // Parallel to the slab: inside it or not at all (0 * inf would give NaN).
            if (r.org[c] < b.lower[c] || r.org[c] > b.upper[c]) return false;
            continue;
        }
        const double inv = 1.0 / r.dir[c];
        double a = (b.lower[c] - r.org[c]) * inv, z = (b.upper[c] - r.org[c]) * inv;
        if (a > z) std::swap(a, z);
        t0 = std::max(t0, a);
        t1 = std::min(t1, z);
    }
    return t0 <= t1;
}

double det3(const double a[3], const double b[3], const double c[3]) {
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

class NewtonMethod final : public Method {
public:
    NewtonMethod(const std::vector<double> &control_points, NewtonStarts starts, int count)
        : control_points_(control_points), starts_(starts), count_(count) {
        info_.family = "newton";
        info_.parameter = "starts";
        switch (starts) {
        case NewtonStarts::center:
            info_.name = "newton-center";
            info_.value = 1;
            break;
        case NewtonStarts::subpatch_centers:
            info_.name = "newton-" + std::to_string(count) + "x" + std::to_string(count);
            info_.value = count * count;
            break;
        case NewtonStarts::random:
            info_.name = "newton-r" + std::to_string(count);
            info_.value = count;
            break;
        }
        info_.primitives = control_points.size() / 48;
        double lower[3] = {INFINITY, INFINITY, INFINITY}, upper[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t k = 0; k < control_points.size(); ++k) {
            lower[k % 3] = std::min(lower[k % 3], control_points[k]);
            upper[k % 3] = std::max(upper[k % 3], control_points[k]);
        }
        double d2 = 0;
        for (int c = 0; c < 3; ++c) d2 += (upper[c] - lower[c]) * (upper[c] - lower[c]);
        converged_ = 1e-11 * std::sqrt(d2);
    }

    const MethodInfo &info() const override { return info_; }

    BuildMemory build(int) override {
        boxes_.clear();
        for (size_t p = 0; p < info_.primitives; ++p) {
            Box b{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
            for (int k = 0; k < 48; ++k) {
                const double x = control_points_[p * 48 + k];
                b.lower[k % 3] = std::min(b.lower[k % 3], x);
                b.upper[k % 3] = std::max(b.upper[k % 3], x);
            }
            boxes_.push_back(b);
        }
        BuildMemory m;
        m.array_bytes = control_points_.size() * sizeof(double);
        m.structure_bytes = boxes_.size() * sizeof(Box);
        return m;
    }

    void release() override { boxes_.clear(); }

    void trace(const std::vector<ppm_ray> &rays, size_t begin, size_t end, Trace &out) const override {
        for (size_t i = begin; i < end; ++i) {
            const ppm_ray &r = rays[i];
            double best_t = INFINITY, best_u = 0, best_v = 0;
            uint32_t best_patch = 0;
            for (size_t p = 0; p < boxes_.size(); ++p) {
                if (!box_hit(boxes_[p], r)) continue;
                SplitMix64 rng(derive_seed(i, p));
                const int n = starts_ == NewtonStarts::center             ? 1
                              : starts_ == NewtonStarts::subpatch_centers ? count_ * count_
                                                                          : count_;
                for (int k = 0; k < n; ++k) {
                    double u, v;
                    if (starts_ == NewtonStarts::center) {
                        u = v = 0.5;
                    } else if (starts_ == NewtonStarts::subpatch_centers) {
                        u = (k % count_ + 0.5) / count_;
                        v = (k / count_ + 0.5) / count_;
                    } else {
                        u = rng.uniform();
                        v = rng.uniform();
                    }
                    double t;
                    if (newton(&control_points_[p * 48], r, u, v, t) && t < best_t) {
                        best_t = t;
                        best_u = u;
                        best_v = v;
                        best_patch = uint32_t(p);
                    }
                }
            }
            if (!std::isfinite(best_t)) continue;
            double s[3], su[3], sv[3];
            evaluate(&control_points_[best_patch * 48], best_u, best_v, s, su, sv);
            const double n[3] = {su[1] * sv[2] - su[2] * sv[1], su[2] * sv[0] - su[0] * sv[2],
                                 su[0] * sv[1] - su[1] * sv[0]};
            const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            out.t[i] = best_t;
            out.patch[i] = best_patch;
            for (int c = 0; c < 3; ++c) out.ng[3 * i + c] = out.ns[3 * i + c] = l > 0 ? float(n[c] / l) : 0.0f;
        }
    }

private:
    // Newton from (u, v) with t the projection of S(u, v) on the ray. On success (u, v, t)
    // is a root with (u, v) in [0, 1]^2 (a rounding slack is clamped away) and t in
    // (tnear, tfar].
    bool newton(const double *P, const ppm_ray &r, double &u, double &v, double &t) const {
        double s[3], su[3], sv[3];
        evaluate(P, u, v, s, su, sv);
        t = (s[0] - r.org[0]) * r.dir[0] + (s[1] - r.org[1]) * r.dir[1] + (s[2] - r.org[2]) * r.dir[2];
        const double md[3] = {-r.dir[0], -r.dir[1], -r.dir[2]};
        int polish = -1;
        for (int iteration = 0; iteration < 32; ++iteration) {
            double f[3];
            for (int c = 0; c < 3; ++c) f[c] = s[c] - r.org[c] - t * r.dir[c];
            const double residual = std::max({std::fabs(f[0]), std::fabs(f[1]), std::fabs(f[2])});
            if (!std::isfinite(residual)) return false;
            if (residual <= converged_ && polish < 0) polish = 1; // one more step to rounding level
            if (polish == 0) break;
            if (polish > 0) --polish;
            // Cramer's rule for [su sv -d] (du, dv, dt) = -f.
            const double det = det3(su, sv, md);
            if (!(std::fabs(det) > 0)) return false;
            const double mf[3] = {-f[0], -f[1], -f[2]};
            u += det3(mf, sv, md) / det;
            v += det3(su, mf, md) / det;
            t += det3(su, sv, mf) / det;
            if (!(u > -1.0 && u < 2.0 && v > -1.0 && v < 2.0)) return false; // diverged
            evaluate(P, u, v, s, su, sv);
        }
        if (polish != 0) return false;
        constexpr double slack = 1e-9;
        if (!(u >= -slack && u <= 1 + slack && v >= -slack && v <= 1 + slack)) return false;
        u = std::clamp(u, 0.0, 1.0);
        v = std::clamp(v, 0.0, 1.0);
        return t > r.tnear && t <= r.tfar;
    }

    std::vector<double> control_points_;
    NewtonStarts starts_;
    int count_;
    MethodInfo info_;
    double converged_ = 0;
    std::vector<Box> boxes_;
};

} // namespace

std::unique_ptr<Method> make_newton_method(const std::vector<double> &control_points, NewtonStarts starts, int count) {
    return std::make_unique<NewtonMethod>(control_points, starts, count);
}

} // namespace bench
