#include "geometry/sphere_geometry.h"

#include "core/error.h"
#include "geometry/sphere_test.h"
#include "scene/user_geometry.h"

#include <cfloat>

namespace ppm {

namespace {

bool test_sphere(const SphereGeometry::Data &s, unsigned, RayQuery &query) {
    return test_sphere_terms(sphere_terms(s.center, s.radius, query), query);
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
    data_.inv_radius = 1 / data_.radius;
    data_.rounding = 32 * DBL_EPSILON * (max_abs_component(data_.center) + data_.radius);
    Box3 box;
    box.extend(data_.center - Vec3{1, 1, 1} * data_.radius);
    box.extend(data_.center + Vec3{1, 1, 1} * data_.radius);
    return box;
}

RTCGeometry SphereGeometry::create_embree(RTCDevice device, const EmbreeFrame &frame) {
    data_.frame = frame;
    return new_user_geometry<Data, test_sphere>(device, data_, 1, sphere_bounds);
}

void SphereGeometry::describe_hit(const RayQuery &query, double tolerance, ppm_hit &hit) const {
    const Vec3 along = query.org + query.dir * query.hit.t - data_.center;
    const Vec3 n = normalize(along * data_.inv_radius); // nearly unit: no square root (vec3.h)
    const Vec3 p = data_.center + n * data_.radius; // back onto the sphere
    p.store(hit.p);
    n.store(hit.ng);
    n.store(hit.ns);
    hit.p_error = tolerance + data_.rounding;
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
