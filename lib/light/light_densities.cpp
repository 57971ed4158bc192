// SPDX-License-Identifier: Apache-2.0
// The densities of light sampling that multiple importance sampling between bidirectional
// techniques needs (light.h: EmissionDensities, illuminate). They mirror emit(): area lights
// emit from a point uniform in area, cosine-weighted about the emitting normal; point lights
// uniformly over the sphere, spots uniformly over their cone; lights at infinity pick a
// direction (uniform, or the environment map's distribution) and then a point on the disc of
// the scene's bounding sphere facing it.
#include "light/light.h"

#include "light/environment_map.h"
#include "math/warp.h"

#include <cmath>

namespace ppm {

EmissionDensities Light::emission_densities(const Vec3 &normal, const Vec3 &direction) const {
    EmissionDensities d;
    switch (type_) {
    case Type::Point:
        d.emission = 0.25 * kInvPi;
        d.direct = 1;
        return d;
    case Type::Spot: {
        const double cos_axis = dot(direction, frame_.n);
        d.emission = cos_axis > cos_cutoff_ ? 1.0 / (2.0 * kPi * (1.0 - cos_cutoff_)) : 0.0;
        d.direct = 1;
        return d;
    }
    case Type::Quad:
    case Type::Sphere:
    case Type::Disk:
    case Type::Cylinder:
    case Type::Mesh: {
        d.cos_light = dot(normal, direction);
        if (!(d.cos_light > 0) || !(area_ > 0)) return EmissionDensities{0, 0, 0};
        d.direct = 1.0 / area_;
        d.emission = d.direct * d.cos_light * kInvPi;
        return d;
    }
    case Type::Constant:
    case Type::Envmap:
    case Type::Directional: {
        const double disc = 1.0 / (kPi * scene_radius_ * scene_radius_);
        const double pdf_direction = type_ == Type::Directional ? 1.0 : pdf_direct(direction * -1.0);
        d.direct = pdf_direction;
        d.emission = pdf_direction * disc;
        return d;
    }
    }
    return d;
}

LightIllumination Light::illuminate(const Vec3 &p, double u1, double u2) const {
    LightIllumination s;
    switch (type_) {
    case Type::Point:
    case Type::Spot: {
        const Vec3 to_light = position_ - p;
        const double d2 = length2(to_light);
        s.distance = std::sqrt(d2);
        if (!(s.distance > 0)) return s;
        s.direction = to_light / s.distance;
        s.radiance = type_ == Type::Point ? color_ : spot_intensity(-dot(s.direction, frame_.n));
        s.direct_pdf_w = d2;
        s.densities = emission_densities(Vec3(), s.direction * -1.0);
        return s;
    }
    case Type::Quad:
    case Type::Sphere:
    case Type::Disk:
    case Type::Cylinder:
    case Type::Mesh: {
        Vec3 q, n, ng;
        if (type_ == Type::Quad) {
            q = position_ + edge_u_ * u1 + edge_v_ * u2;
            n = frame_.n;
        } else {
            sample_area(u1, u2, &q, &n, &ng);
        }
        const Vec3 to_light = q - p;
        const double d2 = length2(to_light);
        s.distance = std::sqrt(d2);
        if (!(s.distance > 0)) return s;
        s.direction = to_light / s.distance;
        s.densities = emission_densities(n, s.direction * -1.0);
        if (!(s.densities.cos_light > 0)) return s;
        s.radiance = color_;
        s.direct_pdf_w = s.densities.direct * d2 / s.densities.cos_light;
        return s;
    }
    case Type::Constant:
    case Type::Envmap:
    case Type::Directional: {
        s.distance = INFINITY;
        if (type_ == Type::Directional) {
            s.direction = direction_; // stored pointing towards the light
            s.radiance = color_;
            s.direct_pdf_w = 1;
        } else if (type_ == Type::Constant) {
            s.direction = uniform_sphere(u1, u2);
            s.radiance = color_;
            s.direct_pdf_w = 0.25 * kInvPi;
        } else {
            double pdf;
            const Vec3 local = env_->sample(u1, u2, &pdf);
            if (!(pdf > 0)) return s;
            s.direction = frame_.to_world(local);
            s.radiance = env_->eval(local);
            s.direct_pdf_w = pdf;
        }
        s.densities = emission_densities(Vec3(), s.direction * -1.0);
        return s;
    }
    }
    return s;
}

} // namespace ppm
