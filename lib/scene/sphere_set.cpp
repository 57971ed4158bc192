// SPDX-License-Identifier: Apache-2.0
#include "scene/sphere_set.h"

#include "core/error.h"

#ifdef __AVX__
#include <immintrin.h>
#endif

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

namespace ppm {

namespace {

// Four lanes of doubles and their comparison masks (GCC/Clang vector extensions: AVX2 under
// -march=native, two SSE2 halves otherwise). The compiler left the scalar loops unvectorised.
typedef double Lanes4 __attribute__((vector_size(32)));
typedef long long Mask4 __attribute__((vector_size(32)));

Lanes4 load4(const double *p) {
    Lanes4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
void store4(double *p, Lanes4 v) { std::memcpy(p, &v, sizeof v); }
Lanes4 select4(Mask4 m, Lanes4 yes, Lanes4 no) { return (Lanes4)((m & (Mask4)yes) | (~m & (Mask4)no)); }
Lanes4 sqrt4(Lanes4 v) {
#ifdef __AVX__
    return reinterpret_cast<Lanes4>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(v)));
#else
    return Lanes4{std::sqrt(v[0]), std::sqrt(v[1]), std::sqrt(v[2]), std::sqrt(v[3])};
#endif
}
// |magnitude| with the sign of `sign`, lane by lane (std::copysign).
Lanes4 copysign4(Lanes4 magnitude, Lanes4 sign) {
    const Mask4 sign_bit = {INT64_MIN, INT64_MIN, INT64_MIN, INT64_MIN};
    return (Lanes4)(((Mask4)magnitude & ~sign_bit) | ((Mask4)sign & sign_bit));
}

bool none_set(Mask4 m) {
#ifdef __AVX__
    return _mm256_testz_si256(reinterpret_cast<__m256i>(m), reinterpret_cast<__m256i>(m));
#else
    return (m[0] | m[1] | m[2] | m[3]) == 0;
#endif
}

constexpr double kNoHit = INFINITY;

} // namespace

void SphereSet::add(const Vec3 &center, double radius) {
    if (count_ == kCapacity)
        fail(PPM_ERROR_INVALID_OPERATION, "a sphere set holds at most " + std::to_string(kCapacity) + " spheres");
    cx_[count_] = center.x;
    cy_[count_] = center.y;
    cz_[count_] = center.z;
    radius2_[count_] = radius * radius;
    ++count_;
    used_lanes_ = (count_ + 3) / 4 * 4;
}

// The roots of |org + t dir - c|^2 = r^2 in the cancellation-free form of "Precision
// Improvements for Ray/Sphere Intersection" (Haines et al., Ray Tracing Gems, ch. 7), exactly
// as SphereGeometry's test computes them for one sphere, here for four at once: a group pays for
// a square root and a division unless the line misses all its spheres, but no lane waits for
// another's test. (An estimate of the nearest sphere, a SIMD exclusion test and scalar exact
// tests of the survivors cost more: docs/bench/code-history.md.)
void SphereSet::nearest_roots(const RayQuery &query, double *t) const {
    const double ox = query.org.x, oy = query.org.y, oz = query.org.z;
    const double dx = query.dir.x, dy = query.dir.y, dz = query.dir.z;
    const double a = query.dir_length2, inv_a = query.inv_dir_length2, tnear = query.tnear, tfar = query.hit.t;
    const Lanes4 none = {kNoHit, kNoHit, kNoHit, kNoHit};
    for (int i = 0; i < used_lanes_; i += 4) {
        const Lanes4 fx = ox - load4(cx_ + i), fy = oy - load4(cy_ + i), fz = oz - load4(cz_ + i);
        const Lanes4 r2 = load4(radius2_ + i);
        const Lanes4 b = fx * dx + fy * dy + fz * dz;
        const Lanes4 c = (fx * fx + fy * fy + fz * fz) - r2;
        const Lanes4 s = b * inv_a, lx = fx - dx * s, ly = fy - dy * s, lz = fz - dz * s;
        const Lanes4 disc = a * (r2 - (lx * lx + ly * ly + lz * lz));
        const Mask4 crosses = (disc >= 0) & (r2 >= 0); // unused lanes: r2 < 0
        if (none_set(crosses)) {                       // the line misses them all (small spheres, mostly)
            store4(t + i, none);
            continue;
        }
        const Lanes4 q = -(b + copysign4(sqrt4(select4(crosses, disc, Lanes4{})), b));
        const Lanes4 t0 = q * inv_a;
        const Lanes4 t1 = select4(q != 0, c / q, t0);
        const Mask4 swap = t0 > t1;
        const Lanes4 lo = select4(swap, t1, t0), hi = select4(swap, t0, t1);
        const Mask4 lo_in = (lo >= tnear) & (lo <= tfar), hi_in = (hi >= tnear) & (hi <= tfar);
        store4(t + i, select4(crosses, select4(lo_in, lo, select4(hi_in, hi, none)), none));
    }
}

int SphereSet::intersect(RayQuery &query) const {
    if (count_ == 0) return -1;
    alignas(64) double t[kCapacity];
    nearest_roots(query, t);
    int nearest = -1;
    double t_nearest = kNoHit;
    for (int i = 0; i < count_; ++i)
        if (t[i] < t_nearest) {
            t_nearest = t[i];
            nearest = i;
        }
    if (nearest >= 0) query.record(t_nearest, 0, 0, 0);
    return nearest;
}

bool SphereSet::occluded(RayQuery &query) const {
    if (count_ == 0) return false;
    alignas(64) double t[kCapacity];
    nearest_roots(query, t);
    for (int i = 0; i < count_; ++i)
        if (t[i] < kNoHit) {
            query.record(t[i], 0, 0, 0);
            return true;
        }
    return false;
}

} // namespace ppm
