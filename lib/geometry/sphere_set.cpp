#include "geometry/sphere_set.h"

#include "core/error.h"
#include "geometry/sphere_test.h"

#ifdef __AVX__
#include <immintrin.h>
#endif

#include <cfloat>
#include <cstdint>
#include <cmath>
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
Lanes4 abs4(Lanes4 v) { return select4(v < 0, -v, v); }
// Bit k set where lane k of the mask is.
std::uint32_t lane_bits(Mask4 m) {
#ifdef __AVX__
    return static_cast<std::uint32_t>(_mm256_movemask_pd(reinterpret_cast<__m256d>(m)));
#else
    return (m[0] != 0) | (m[1] != 0) << 1 | (m[2] != 0) << 2 | (m[3] != 0) << 3;
#endif
}

} // namespace

struct SphereSet::Lanes {
    alignas(64) double fx[kCapacity], fy[kCapacity], fz[kCapacity];
    alignas(64) double b[kCapacity], ff[kCapacity], c[kCapacity];
    // r^2 - (distance of the line from the centre)^2, plus a rounding margin: negative when the
    // line passes the sphere by, where test_sphere_terms() finds a negative discriminant.
    alignas(64) double reach[kCapacity];
};

void SphereSet::add(const Vec3 &center, double radius) {
    if (count_ == kCapacity) fail(PPM_ERROR_INVALID_OPERATION, "a sphere set holds at most " + std::to_string(kCapacity) + " spheres");
    cx_[count_] = center.x;
    cy_[count_] = center.y;
    cz_[count_] = center.z;
    radius2_[count_] = radius * radius;
    ++count_;
    used_lanes_ = (count_ + 3) / 4 * 4;
}

void SphereSet::compute_terms(const RayQuery &query, Lanes &lanes) const {
    const double ox = query.org.x, oy = query.org.y, oz = query.org.z;
    const double dx = query.dir.x, dy = query.dir.y, dz = query.dir.z, inv_a = query.inv_dir_length2;
    for (int i = 0; i < used_lanes_; i += 4) {
        const Lanes4 fx = ox - load4(cx_ + i), fy = oy - load4(cy_ + i), fz = oz - load4(cz_ + i);
        const Lanes4 ff = fx * fx + fy * fy + fz * fz, b = fx * dx + fy * dy + fz * dz, r2 = load4(radius2_ + i);
        store4(lanes.fx + i, fx);
        store4(lanes.fy + i, fy);
        store4(lanes.fz + i, fz);
        store4(lanes.b + i, b);
        store4(lanes.ff + i, ff);
        store4(lanes.c + i, ff - r2);
        // As test_sphere_terms() computes it; the margin covers other rounding (FMA contraction).
        const Lanes4 s = b * inv_a, lx = fx - dx * s, ly = fy - dy * s, lz = fz - dz * s;
        const Lanes4 ll = lx * lx + ly * ly + lz * lz;
        store4(lanes.reach + i, (r2 - ll) + 1e-12 * (r2 + ll));
    }
}

std::uint32_t SphereSet::may_hit(const RayQuery &query, const Lanes &lanes) const {
    const double a = query.dir_length2, tnear = query.tnear, t_far = query.hit.t;
    std::uint32_t bits = 0;
    for (int i = 0; i < used_lanes_; i += 4) {
        const Lanes4 b = load4(lanes.b + i), r2 = load4(radius2_ + i);
        const Mask4 m = ~sphere_ruled_out(b, abs4(b), load4(lanes.ff + i), r2, load4(lanes.c + i), a, tnear, t_far) &
                        (r2 >= 0) & (load4(lanes.reach + i) >= 0);
        bits |= lane_bits(m) << i;
    }
    return bits;
}

bool SphereSet::test_lane(const Lanes &lanes, int i, RayQuery &query) const {
    if (radius2_[i] < 0) return false;
    const SphereTerms terms{{lanes.fx[i], lanes.fy[i], lanes.fz[i]}, lanes.b[i], lanes.ff[i], radius2_[i], lanes.c[i]};
    return test_sphere_terms(terms, query);
}

int SphereSet::intersect(RayQuery &query) const {
    if (count_ == 0) return -1;
    Lanes lanes;
    compute_terms(query, lanes);
    // Test first the sphere likely nearest: the smallest estimate of where it is hit, seen from
    // the ray's start org + tnear dir, where the quadratic's terms are b' = b + a tnear and
    // c' = f(tnear): |c'| / 2|b'| past the start, exact for plane-like spheres: the entry from
    // outside when moving towards the centre (b' < 0), the exit from inside when moving away
    // from it (b' > 0). Exits towards the centre lie beyond it, and outside spheres left behind
    // have no hit, so neither is chosen. (From the origin instead, a camera ray clipped past a
    // wall it starts behind would choose that wall and find its far side.) Its hit shortens
    // the ray, and sphere_ruled_out() then rules out most others.
    const double a = query.dir_length2, tnear = query.tnear;
    alignas(64) double estimate[kCapacity];
    for (int i = 0; i < used_lanes_; i += 4) {
        const Lanes4 b = load4(lanes.b + i), c = load4(lanes.c + i), r2 = load4(radius2_ + i);
        const Lanes4 b_start = b + a * tnear, c_start = (a * tnear + 2 * b) * tnear + c;
        const Mask4 outside = c_start > 0;
        const Mask4 towards_hit = (outside & (b_start < 0)) | (~outside & (b_start > 0));
        const Lanes4 none = {INFINITY, INFINITY, INFINITY, INFINITY};
        const Mask4 candidate = towards_hit & (r2 >= 0) & (load4(lanes.reach + i) >= 0);
        store4(estimate + i, select4(candidate, abs4(c_start) / (2 * abs4(b_start)), none));
    }
    int first = 0;
    for (int i = 1; i < count_; ++i)
        if (estimate[i] < estimate[first]) first = i;
    const int tested = estimate[first] < INFINITY ? first : -1;
    int nearest = -1;
    if (tested >= 0 && test_lane(lanes, tested, query)) nearest = tested;

    std::uint32_t candidates = may_hit(query, lanes);
    if (tested >= 0) candidates &= ~(1u << tested);
    for (; candidates != 0; candidates &= candidates - 1) {
        const int i = __builtin_ctz(candidates);
        if (test_lane(lanes, i, query)) nearest = i;
    }
    return nearest;
}

bool SphereSet::occluded(RayQuery &query) const {
    if (count_ == 0) return false;
    Lanes lanes;
    compute_terms(query, lanes);
    for (std::uint32_t candidates = may_hit(query, lanes); candidates != 0; candidates &= candidates - 1)
        if (test_lane(lanes, __builtin_ctz(candidates), query)) return true;
    return false;
}

} // namespace ppm
