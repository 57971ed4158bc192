#include "geometry/sphere_geometry.h"

#include "core/error.h"
#include "scene/user_geometry.h"

#include <cfloat>

namespace ppm {

namespace {

// The ray's terms for one sphere: the quadratic |org + t dir - centre|^2 - r^2 =
// a t^2 + 2 b t + c with a = |dir|^2, and |f|^2 for error bounds.
struct SphereTerms {
    Vec3 f; // org - centre
    double b, ff, r2, c;
};

SphereTerms sphere_terms(const SphereGeometry::Data &s, const RayQuery &query) {
    SphereTerms t;
    t.f = query.org - s.center;
    t.b = dot(t.f, query.dir);
    t.ff = dot(t.f, t.f);
    t.r2 = s.radius * s.radius;
    t.c = t.ff - t.r2;
    return t;
}

// Outside the sphere (beyond the rounding of c): then both roots have the sign of -b.
bool surely_outside(const SphereTerms &t) { return t.c > 4 * DBL_EPSILON * t.ff; }

// Roots of |org + t dir - c|^2 = r^2 in the cancellation-free form of "Precision Improvements
// for Ray/Sphere Intersection" (Haines et al., Ray Tracing Gems, ch. 7).
bool test_sphere_terms(const SphereTerms &terms, RayQuery &query) {
    const Vec3 &f = terms.f;
    const double b = terms.b, ff = terms.ff, r2 = terms.r2, c = terms.c;
    // Outside and moving away from the centre: both roots are behind the origin (their product
    // c/a > 0, their sum -2b/a <= 0) and tnear >= 0. No division or sqrt.
    if (b >= 0 && surely_outside(terms)) return false;
    const double a = query.dir_length2, inv_a = query.inv_dir_length2;
    // No root in [tnear, hit.t], the interval still open: f(t) = a t^2 + 2 b t + c is convex,
    // so it has none there when it is negative at both ends (inside the sphere all along:
    // Hachisuka's room lies inside all six wall spheres, and a ray that has found one wall
    // skips the walls it would leave the sphere through later), or when it is positive at
    // the far end before its vertex (both roots beyond). The margins cover f's rounding.
    // Saves the sqrt and division of every sphere but the ones that set hit.t.
    const double t_far = query.hit.t;
    if (t_far < INFINITY) {
        const auto f_at = [&](double t) { return (a * t + 2 * b) * t + c; };
        const auto margin = [&](double t) { return 1e-12 * (a * t * t + 2 * std::fabs(b) * t + ff + r2); };
        const double far_value = f_at(t_far), far_margin = margin(t_far);
        if (far_value > far_margin && b < -a * t_far) return false;
        if (far_value < -far_margin && f_at(query.tnear) < -margin(query.tnear)) return false;
    }
    const Vec3 l = f - query.dir * (b * inv_a);
    const double disc = a * (r2 - dot(l, l));
    if (!(disc >= 0)) return false;
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    double t0 = q * inv_a, t1 = q != 0 ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    for (double t : {t0, t1})
        if (t >= query.tnear && t <= query.hit.t) {
            query.record(t, 0, 0, 0);
            return true;
        }
    return false;
}

bool test_sphere(const SphereGeometry::Data &s, unsigned, RayQuery &query) {
    return test_sphere_terms(sphere_terms(s, query), query);
}

void sphere_bounds(const RTCBoundsFunctionArguments *args) {
    const auto &s = *static_cast<const SphereGeometry::Data *>(args->geometryUserPtr);
    Box3 box;
    box.extend(s.center - Vec3{1, 1, 1} * s.radius);
    box.extend(s.center + Vec3{1, 1, 1} * s.radius);
    write_embree_bounds(box, s.frame, *args->bounds_o);
}

} // namespace

SphereGeometry::SphereGeometry(const Vec3 &center, double radius)
    : source_center_(center), source_radius_(radius) {}

void SphereGeometry::check_transform(const Affine &transform) const {
    const Vec3 x = transform.vector({1, 0, 0}), y = transform.vector({0, 1, 0}),
               z = transform.vector({0, 0, 1});
    const double lx = length(x), ly = length(y), lz = length(z);
    const double tolerance = 1e-9 * std::max({lx, ly, lz});
    if (std::fabs(lx - ly) > tolerance || std::fabs(lx - lz) > tolerance ||
        std::fabs(dot(x, y)) > tolerance * lx || std::fabs(dot(y, z)) > tolerance * ly ||
        std::fabs(dot(x, z)) > tolerance * lx)
        invalid_argument("a sphere takes only rotations, translations and uniform scaling");
}

Box3 SphereGeometry::prepare(const Affine &transform) {
    data_.center = transform.point(source_center_);
    const Vec3 x = transform.vector({1, 0, 0});
    data_.radius = source_radius_ * length(x);
    data_.axis[0] = normalize(x);
    data_.axis[1] = normalize(transform.vector({0, 1, 0}));
    data_.axis[2] = normalize(transform.vector({0, 0, 1}));
    Box3 box;
    box.extend(data_.center - Vec3{1, 1, 1} * data_.radius);
    box.extend(data_.center + Vec3{1, 1, 1} * data_.radius);
    return box;
}

bool SphereGeometry::test(const Data &data, RayQuery &query) { return test_sphere(data, 0, query); }

int SphereGeometry::test_nearest(const Data *const *spheres, size_t count, RayQuery &query) {
    // The first to test: the smallest estimate num / den (den > 0) of where a sphere is hit,
    // exact for plane-like spheres: the entry c / -2b from outside, the exit |c| / 2b from
    // inside when moving away from the centre. Exits towards the centre lie beyond it, and
    // outside spheres left behind have no hit, so neither is chosen. Compared by
    // cross-multiplying: no division. The terms of the first 8 spheres are kept for the tests.
    constexpr size_t kKept = 8;
    SphereTerms kept[kKept];
    size_t first = count;
    double best_num = 0, best_den = 1;
    for (size_t i = 0; i < count; ++i) {
        const SphereTerms t = sphere_terms(*spheres[i], query);
        if (i < kKept) kept[i] = t;
        if (surely_outside(t) ? t.b >= 0 : t.b <= 0) continue;
        const double num = std::fabs(t.c), den = 2 * std::fabs(t.b);
        if (first == count || num * best_den < best_num * den) {
            first = i;
            best_num = num;
            best_den = den;
        }
    }
    const auto test = [&](size_t i) {
        return test_sphere_terms(i < kKept ? kept[i] : sphere_terms(*spheres[i], query), query);
    };
    int nearest = -1;
    if (first < count && test(first)) nearest = static_cast<int>(first);
    for (size_t i = 0; i < count; ++i)
        if (i != first && test(i)) nearest = static_cast<int>(i);
    return nearest;
}

RTCGeometry SphereGeometry::create_embree(RTCDevice device, const EmbreeFrame &frame) {
    data_.frame = frame;
    return new_user_geometry<Data, test_sphere>(device, data_, 1, sphere_bounds);
}

void SphereGeometry::describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const {
    const Vec3 along = query.org + query.dir * query.hit.t - data_.center;
    const Vec3 n = normalize(along);
    const Vec3 p = data_.center + n * data_.radius; // back onto the sphere
    p.store(hit.p);
    n.store(hit.ng);
    n.store(hit.ns);
    hit.p_error = tolerance + 32 * DBL_EPSILON * (max_abs_component(data_.center) + data_.radius);
}

// Spherical coordinates of the normal in the object's frame: u = phi / 2 pi from its x axis
// towards y, v = theta / pi from its z axis.
void SphereGeometry::compute_uv(ppm_hit &hit) const {
    const Vec3 n = Vec3::from(hit.ng);
    const double lx = dot(n, data_.axis[0]), ly = dot(n, data_.axis[1]), lz = dot(n, data_.axis[2]);
    double phi = std::atan2(ly, lx);
    if (phi < 0) phi += 2 * M_PI;
    hit.u = phi / (2 * M_PI);
    hit.v = std::acos(std::clamp(lz, -1.0, 1.0)) / M_PI;
}

} // namespace ppm
