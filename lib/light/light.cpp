// SPDX-License-Identifier: Apache-2.0
#include "light/light.h"

#include "core/error.h"
#include "geometry/mesh_data.h"
#include "light/environment_map.h"
#include "material/texture.h"
#include "math/sin_cos.h"
#include "math/warp.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace ppm {

namespace {

constexpr double kDegree = kPi / 180.0;

void check_color(const Rgb &c, const char *name) {
    if (!c.is_finite() || c.min() < 0)
        invalid_argument(std::string("light ") + name + " must be finite and >= 0 in every channel");
}

void check_point(const Vec3 &p, const char *name) {
    if (!is_finite(p)) invalid_argument(std::string("light ") + name + " has a NaN or infinite coordinate");
}

// Direction in a cone of half-angle acos(1 - one_minus_cos_max) around +z, uniform in solid angle.
Vec3 uniform_cone(double u1, double u2, double one_minus_cos_max) {
    const double cos_theta = 1.0 - u1 * one_minus_cos_max;
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    double sin_phi, cos_phi;
    sin_cos_2pi(u2, &sin_phi, &cos_phi);
    return {sin_theta * cos_phi, sin_theta * sin_phi, cos_theta};
}

// Where a photon from a light at infinity arriving along -towards starts: on the disk of
// radius R perpendicular to `towards`, tangent to the scene's bounding sphere on its side.
Vec3 disk_origin(const Vec3 &center, double radius, const Vec3 &towards, double u1, double u2) {
    double x, y;
    square_to_uniform_disk_concentric(u1, u2, &x, &y);
    const Frame f = Frame::from_normal(towards);
    return center + (f.s * x + f.t * y + towards) * radius;
}

} // namespace

Light Light::constant(const Rgb &radiance) {
    check_color(radiance, "radiance");
    Light l;
    l.type_ = Type::Constant;
    l.color_ = radiance;
    l.set_scene_sphere(Vec3{0, 0, 0}, 1);
    return l;
}

Light Light::envmap(std::shared_ptr<const Texture> image, double scale, const Vec3 to_world_columns[3]) {
    if (!image) invalid_argument("envmap needs an image");
    for (int c = 0; c < 3; ++c) check_point(to_world_columns[c], "to_world");
    // A rotation (or a mirrored one) times a uniform scale: columns of one length, orthogonal.
    const double s = length(to_world_columns[0]);
    const auto close = [&](double a, double b) { return std::fabs(a - b) <= 1e-6 * s * s; };
    bool ok = s > 0;
    for (int a = 0; a < 3 && ok; ++a)
        for (int b = 0; b < 3 && ok; ++b)
            ok = close(dot(to_world_columns[a], to_world_columns[b]), a == b ? s * s : 0.0);
    if (!ok) invalid_argument("envmap to_world must be a rotation (possibly mirrored, uniformly scaled)");
    Light l;
    l.type_ = Type::Envmap;
    l.env_ = std::make_shared<const EnvironmentMap>(*image, scale);
    l.frame_.s = to_world_columns[0] / s;
    l.frame_.t = to_world_columns[1] / s;
    l.frame_.n = to_world_columns[2] / s;
    l.set_scene_sphere(Vec3{0, 0, 0}, 1);
    return l;
}

Light Light::directional(const Vec3 &direction, const Rgb &irradiance) {
    check_point(direction, "direction");
    check_color(irradiance, "irradiance");
    if (!(length2(direction) > 0)) invalid_argument("directional light direction must not be zero");
    Light l;
    l.type_ = Type::Directional;
    l.direction_ = normalize(direction) * -1.0;
    l.color_ = irradiance;
    l.set_scene_sphere(Vec3{0, 0, 0}, 1);
    return l;
}

void Light::set_scene_sphere(const Vec3 &center, double radius) {
    if (!is_infinite()) return;
    position_ = center;
    scene_radius_ = radius;
    const double disk = kPi * radius * radius;
    switch (type_) {
    case Type::Constant: power_ = color_ * (4 * kPi * disk); break;
    case Type::Envmap: power_ = env_->integral() * disk; break;
    case Type::Directional: power_ = color_ * disk; break;
    default: break;
    }
}

Rgb Light::environment(const Vec3 &towards) const {
    switch (type_) {
    case Type::Constant: return color_;
    case Type::Envmap: return env_->eval(frame_.to_local(towards));
    default: return Rgb();
    }
}

double Light::pdf_direct(const Vec3 &towards) const {
    switch (type_) {
    case Type::Constant: return 0.25 * kInvPi;
    case Type::Envmap: return env_->pdf(frame_.to_local(towards));
    default: return 0;
    }
}

Light Light::point(const Vec3 &position, const Rgb &intensity) {
    check_point(position, "position");
    check_color(intensity, "intensity");
    Light l;
    l.type_ = Type::Point;
    l.position_ = position;
    l.color_ = intensity;
    l.power_ = intensity * (4.0 * kPi);
    return l;
}

Light Light::spot(const Vec3 &position, const Vec3 &target, const Rgb &intensity, double cutoff_angle_degrees,
                  double beam_width_degrees) {
    check_point(position, "position");
    check_point(target, "target");
    check_color(intensity, "intensity");
    if (!(length2(target - position) > 0)) invalid_argument("spot light target equals its position");
    if (!(cutoff_angle_degrees > 0 && cutoff_angle_degrees <= 180))
        invalid_argument("spot light cutoff_angle must be in (0, 180] degrees, not " +
                         format_number(cutoff_angle_degrees));
    if (!(beam_width_degrees > 0 && beam_width_degrees <= cutoff_angle_degrees))
        invalid_argument("spot light beam_width must be in (0, cutoff_angle] degrees, not " +
                         format_number(beam_width_degrees));
    Light l;
    l.type_ = Type::Spot;
    l.position_ = position;
    l.frame_ = Frame::from_normal(normalize(target - position));
    l.color_ = intensity;
    l.cutoff_ = cutoff_angle_degrees * kDegree;
    l.beam_ = beam_width_degrees * kDegree;
    l.cos_cutoff_ = std::cos(l.cutoff_);
    l.cos_beam_ = std::cos(l.beam_);
    // Power = 2 pi * integral of falloff(theta) sin(theta): 1 up to the beam width, then
    // (cutoff - theta) / (cutoff - beam), whose integral has a closed form.
    double solid_angle = 1.0 - l.cos_beam_;
    if (l.cutoff_ > l.beam_)
        solid_angle += (std::sin(l.beam_) - std::sin(l.cutoff_)) / (l.cutoff_ - l.beam_) + l.cos_beam_;
    l.power_ = intensity * (2.0 * kPi * solid_angle);
    return l;
}

Light Light::quad(const Vec3 &origin, const Vec3 &edge_u, const Vec3 &edge_v, const Rgb &radiance) {
    check_point(origin, "origin");
    check_color(radiance, "radiance");
    const Vec3 n = cross(edge_u, edge_v);
    if (!(length(n) > 0) || !is_finite(n)) invalid_argument("area light quad has zero area");
    Light l;
    l.type_ = Type::Quad;
    l.position_ = origin;
    l.edge_u_ = edge_u;
    l.edge_v_ = edge_v;
    l.area_ = length(n);
    l.frame_ = Frame::from_normal(n / l.area_);
    l.color_ = radiance;
    l.power_ = radiance * (kPi * l.area_);
    return l;
}

Light Light::sphere(const Vec3 &center, double radius, const Rgb &radiance) {
    check_point(center, "center");
    check_color(radiance, "radiance");
    if (!(radius > 0) || !std::isfinite(radius)) invalid_argument("area light sphere radius must be > 0");
    Light l;
    l.type_ = Type::Sphere;
    l.position_ = center;
    l.radius_ = radius;
    l.area_ = 4.0 * kPi * radius * radius;
    l.color_ = radiance;
    l.power_ = radiance * (kPi * l.area_);
    return l;
}

Light Light::disk(const Vec3 &center, const Vec3 &axis_u, const Vec3 &axis_v, const Rgb &radiance, bool flip) {
    check_point(center, "center");
    check_color(radiance, "radiance");
    const Vec3 n = cross(axis_u, axis_v);
    if (!(length(n) > 0) || !is_finite(n)) invalid_argument("area light disk has zero area");
    Light l;
    l.type_ = Type::Disk;
    l.position_ = center;
    l.edge_u_ = axis_u;
    l.edge_v_ = axis_v;
    l.normal_sign_ = flip ? -1 : 1;
    l.frame_ = Frame::from_normal(n / length(n) * l.normal_sign_);
    l.area_ = kPi * length(n); // an affine map scales every area by |axis_u x axis_v|
    l.color_ = radiance;
    l.power_ = radiance * (kPi * l.area_);
    return l;
}

Light Light::cylinder(const Vec3 &p0, const Vec3 &p1, double radius, const Rgb &radiance, bool flip) {
    check_point(p0, "p0");
    check_point(p1, "p1");
    check_color(radiance, "radiance");
    const double height = length(p1 - p0);
    if (!(height > 0) || !std::isfinite(height)) invalid_argument("area light cylinder has p0 == p1");
    if (!(radius > 0) || !std::isfinite(radius)) invalid_argument("area light cylinder radius must be > 0");
    Light l;
    l.type_ = Type::Cylinder;
    l.position_ = p0;
    l.edge_u_ = p1 - p0;
    l.radius_ = radius;
    l.normal_sign_ = flip ? -1 : 1;
    l.frame_ = Frame::from_normal(l.edge_u_ / height); // n = axis; s, t span the cross-section
    l.area_ = 2 * kPi * radius * height;
    l.color_ = radiance;
    l.power_ = radiance * (kPi * l.area_);
    return l;
}

Light Light::mesh(std::shared_ptr<const MeshData> mesh, const Rgb &radiance, bool flip) {
    check_color(radiance, "radiance");
    if (!mesh || mesh->indices.size() < 3) invalid_argument("area light mesh has no triangles");
    auto table = std::make_shared<MeshTable>();
    const MeshData &m = *mesh;
    const size_t count = m.indices.size() / 3;
    table->cdf.resize(count);
    double sum = 0;
    for (size_t k = 0; k < count; ++k) {
        const Vec3 &p0 = m.positions[m.indices[3 * k]];
        sum += 0.5 * length(cross(m.positions[m.indices[3 * k + 1]] - p0, m.positions[m.indices[3 * k + 2]] - p0));
        table->cdf[k] = sum;
    }
    if (!(sum > 0) || !std::isfinite(sum)) invalid_argument("area light mesh has zero area");
    for (double &c : table->cdf) c /= sum;
    table->cdf.back() = 1;
    table->mesh = std::move(mesh);
    Light l;
    l.type_ = Type::Mesh;
    l.normal_sign_ = flip ? -1 : 1;
    l.area_ = sum;
    l.color_ = radiance;
    l.power_ = radiance * (kPi * sum);
    l.table_ = std::move(table);
    return l;
}

size_t Light::pick_triangle(double u) const {
    if (!table_) return 0;
    const std::vector<double> &cdf = table_->cdf;
    // First entry above u: a zero-area triangle repeats its predecessor's value and is skipped.
    return std::min<size_t>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin(), cdf.size() - 1);
}

void Light::sample_area(double u1, double u2, Vec3 *p, Vec3 *n, Vec3 *ng) const {
    switch (type_) {
    case Type::Quad:
        *p = position_ + edge_u_ * u1 + edge_v_ * u2;
        *n = *ng = frame_.n;
        return;
    case Type::Disk: {
        const double r = std::sqrt(u1);
        double sin_phi, cos_phi;
        sin_cos_2pi(u2, &sin_phi, &cos_phi);
        *p = position_ + edge_u_ * (r * cos_phi) + edge_v_ * (r * sin_phi);
        *n = *ng = frame_.n;
        return;
    }
    case Type::Cylinder: {
        double sin_phi, cos_phi;
        sin_cos_2pi(u2, &sin_phi, &cos_phi);
        const Vec3 radial = frame_.s * cos_phi + frame_.t * sin_phi;
        *p = position_ + edge_u_ * u1 + radial * radius_;
        *n = *ng = radial * normal_sign_;
        return;
    }
    case Type::Sphere:
        *n = *ng = uniform_sphere(u1, u2);
        *p = position_ + *n * radius_;
        return;
    case Type::Mesh: {
        const MeshData &m = *table_->mesh;
        const std::vector<double> &cdf = table_->cdf;
        const size_t k = pick_triangle(u1);
        // Reuse u1 within the chosen triangle's interval of the CDF.
        const double lo = k > 0 ? cdf[k - 1] : 0.0, width = cdf[k] - lo;
        const double v1 = width > 0 ? std::clamp((u1 - lo) / width, 0.0, 1.0) : 0.5;
        // Uniform in the triangle (square_to_uniform_triangle): b1 = 1 - sqrt(v1), b2 = u2 sqrt(v1).
        const double s = std::sqrt(v1), b1 = 1 - s, b2 = u2 * s, b0 = 1 - b1 - b2;
        const uint32_t i0 = m.indices[3 * k], i1 = m.indices[3 * k + 1], i2 = m.indices[3 * k + 2];
        const Vec3 &p0 = m.positions[i0], &p1 = m.positions[i1], &p2 = m.positions[i2];
        *p = p0 * b0 + p1 * b1 + p2 * b2;
        const Vec3 face = normalize(cross(p1 - p0, p2 - p0)) * normal_sign_;
        *n = face;
        if (!m.normals.empty()) {
            const Vec3 interpolated = m.normals[i0] * b0 + m.normals[i1] * b1 + m.normals[i2] * b2;
            if (length2(interpolated) > 0) *n = normalize(interpolated) * normal_sign_;
        }
        *ng = face;
        return;
    }
    default:
        *p = position_;
        *n = *ng = frame_.n;
        return;
    }
}

Rgb Light::spot_intensity(double cos_theta) const {
    if (cos_theta <= cos_cutoff_) return Rgb();
    if (cos_theta >= cos_beam_) return color_;
    return color_ * ((cutoff_ - std::acos(std::min(1.0, cos_theta))) / (cutoff_ - beam_));
}

EmittedPhoton Light::emit(double u1, double u2, double u3, double u4) const {
    EmittedPhoton photon;
    switch (type_) {
    case Type::Point:
        photon.origin = position_;
        photon.direction = uniform_sphere(u1, u2);
        photon.flux = power_;
        break;
    case Type::Spot: {
        const double one_minus_cos = 1.0 - cos_cutoff_;
        const Vec3 local = uniform_cone(u1, u2, one_minus_cos);
        photon.origin = position_;
        photon.direction = frame_.to_world(local);
        photon.flux = spot_intensity(local.z) * (2.0 * kPi * one_minus_cos);
        break;
    }
    case Type::Quad: {
        const Vec3 local = square_to_cosine_hemisphere(u3, u4);
        photon.direction = frame_.to_world(local);
        photon.origin = position_ + edge_u_ * u1 + edge_v_ * u2 + frame_.n * surface_offset_;
        photon.normal = frame_.n;
        photon.flux = power_; // L cos / (pdf_area * cos / pi) = pi L A
        break;
    }
    case Type::Sphere: {
        const Vec3 n = uniform_sphere(u1, u2);
        photon.direction = Frame::from_normal(n).to_world(square_to_cosine_hemisphere(u3, u4));
        photon.origin = position_ + n * (radius_ + surface_offset_);
        photon.normal = n;
        photon.flux = power_;
        break;
    }
    case Type::Disk:
    case Type::Cylinder:
    case Type::Mesh: {
        Vec3 p, n, ng;
        sample_area(u1, u2, &p, &n, &ng);
        // Cosine-weighted about the emitting normal (Mitsuba's area emitter sample_ray), so
        // the flux is pi L A; the start is moved off the surface along the face normal, on the
        // side the photon leaves to.
        photon.direction = Frame::from_normal(n).to_world(square_to_cosine_hemisphere(u3, u4));
        photon.origin = p + ng * (dot(photon.direction, ng) >= 0 ? surface_offset_ : -surface_offset_);
        photon.normal = n;
        photon.flux = power_;
        break;
    }
    case Type::Constant:
    case Type::Envmap:
    case Type::Directional: {
        // A direction towards the light, then a point on the disk facing it: flux
        // L / (pdf_direction * pdf_area) with pdf_area = 1 / (pi R^2).
        Vec3 towards = direction_;
        Rgb radiance_over_pdf = color_;
        if (type_ == Type::Constant) {
            towards = uniform_sphere(u1, u2);
            radiance_over_pdf = color_ * (4 * kPi);
        } else if (type_ == Type::Envmap) {
            double pdf;
            const Vec3 local = env_->sample(u1, u2, &pdf);
            towards = frame_.to_world(local);
            radiance_over_pdf = pdf > 0 ? env_->eval(local) / pdf : Rgb();
        }
        photon.origin = disk_origin(position_, scene_radius_, towards, u3, u4);
        photon.direction = towards * -1.0;
        photon.flux = radiance_over_pdf * (kPi * scene_radius_ * scene_radius_);
        break;
    }
    }
    return photon;
}

DirectLightSample Light::sample_direct(const Vec3 &p, double u1, double u2) const {
    DirectLightSample s;
    switch (type_) {
    case Type::Point:
    case Type::Spot: {
        const Vec3 to_light = position_ - p;
        s.distance = length(to_light);
        if (!(s.distance > 0)) return s;
        s.direction = to_light / s.distance;
        const Rgb intensity = type_ == Type::Point ? color_ : spot_intensity(-dot(s.direction, frame_.n));
        s.radiance_over_pdf = intensity / (s.distance * s.distance);
        return s;
    }
    case Type::Quad: {
        const Vec3 q = position_ + edge_u_ * u1 + edge_v_ * u2;
        const Vec3 to_light = q - p;
        const double d2 = length2(to_light);
        s.distance = std::sqrt(d2);
        if (!(s.distance > 0)) return s;
        // One division for the direction and the solid-angle pdf (a shadow ray per visible
        // point waits on this chain).
        const double inv_distance = 1.0 / s.distance;
        s.direction = to_light * inv_distance;
        const double cos_light = -dot(s.direction, frame_.n);
        if (cos_light > 0) s.radiance_over_pdf = color_ * (area_ * cos_light * (inv_distance * inv_distance));
        return s;
    }
    case Type::Sphere: {
        const Vec3 to_center = position_ - p;
        const double dc2 = length2(to_center), r2 = radius_ * radius_;
        if (!(dc2 > r2)) return s;
        const double dc = std::sqrt(dc2);
        const double cos_max = std::sqrt(1.0 - r2 / dc2);
        const double one_minus_cos = (r2 / dc2) / (1.0 + cos_max); // no cancellation when far
        const Vec3 local = uniform_cone(u1, u2, one_minus_cos);
        s.direction = Frame::from_normal(to_center / dc).to_world(local);
        // Nearer intersection of the sampled direction with the sphere.
        const double b = dc * local.z, disc = std::max(0.0, r2 - (dc2 - b * b));
        s.distance = std::max(0.0, b - std::sqrt(disc));
        s.radiance_over_pdf = color_ * (2.0 * kPi * one_minus_cos);
        return s;
    }
    case Type::Disk:
    case Type::Cylinder:
    case Type::Mesh: {
        Vec3 q, n, ng;
        sample_area(u1, u2, &q, &n, &ng);
        const Vec3 to_light = q - p;
        const double d2 = length2(to_light);
        s.distance = std::sqrt(d2);
        if (!(s.distance > 0)) return s;
        const double inv_distance = 1.0 / s.distance;
        s.direction = to_light * inv_distance;
        // pdf in solid angle = dist^2 / (cos_light A).
        const double cos_light = -dot(s.direction, n);
        if (cos_light > 0) s.radiance_over_pdf = color_ * (area_ * cos_light * (inv_distance * inv_distance));
        return s;
    }
    case Type::Constant:
        s.direction = uniform_sphere(u1, u2);
        s.distance = INFINITY;
        s.radiance_over_pdf = color_ * (4 * kPi);
        return s;
    case Type::Envmap: {
        double pdf;
        const Vec3 local = env_->sample(u1, u2, &pdf);
        if (!(pdf > 0)) return s;
        s.direction = frame_.to_world(local);
        s.distance = INFINITY;
        s.radiance_over_pdf = env_->eval(local) / pdf;
        return s;
    }
    case Type::Directional:
        s.direction = direction_;
        s.distance = INFINITY;
        s.radiance_over_pdf = color_;
        return s;
    }
    return s;
}

} // namespace ppm
