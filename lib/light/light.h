// SPDX-License-Identifier: Apache-2.0
// Light sources, in Mitsuba 3's units so scenes translate one to one:
//  - point (`point`): `intensity` I in W/sr, power 4 pi I;
//  - spot (`spot`): intensity I on the axis, full up to `beam_width` and falling linearly in
//    angle to zero at `cutoff_angle` (src/emitters/spot.cpp, falloff_curve);
//  - area (`area` on a `rectangle`, `sphere`, `disk`, `cylinder` or triangle mesh shape):
//    `radiance` L, emitted on the side the surface normal points to only (the quad's
//    edge_u x edge_v, the sphere's outside, the disk's axis_u x axis_v, the cylinder's outside,
//    a mesh's shading normal; all reversed by flip_normals), with power pi L A.
//    A mesh light follows Mitsuba 3's area emitter on a mesh (src/emitters/area.cpp,
//    src/render/mesh.cpp sample_position): a point uniform in area (a triangle from a CDF over
//    the areas, then uniform in it), whose normal is the interpolated vertex normal when the
//    mesh has vertex normals and the face normal otherwise. That normal decides the emitting
//    side and gives the cosine of the solid-angle pdf dist^2 / (cos A) and of the photons'
//    cosine-weighted directions; a camera ray sees the emission when it arrives on the side
//    of the hit's shading normal (RenderScene::shade), the same normal.
//  - lights at infinity: constant (`constant`, uniform `radiance` L from every direction),
//    environment map (`envmap`, a lat-long image times `scale`, oriented by `to_world`) and
//    directional (`directional`, `irradiance` E on a surface facing the light, a delta
//    light). Photons from them cross a disk perpendicular to their direction that covers
//    the scene's bounding sphere (radius R): power pi R^2 times the integral of L over
//    directions (constant 4 pi^2 R^2 L, directional pi R^2 E). See set_scene_sphere.
// A light answers the two questions the renderer asks: a photon leaving it (emit) and the
// light arriving at a point from one sample on it (sample_direct).
#pragma once

#include "math/frame.h"
#include "math/rgb.h"
#include "math/vec3.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace ppm {

struct MeshData;

struct EmittedPhoton {
    Vec3 origin;
    Vec3 direction; // unit
    Rgb flux;       // power carried, as if this light emitted only this one photon
    Vec3 normal;    // area lights: the emitting normal at the origin (else zero)
};

// The densities a bidirectional estimator (vcm_integrator) weighs its techniques with, for a
// point on a light and a direction light leaves it along (Georgiev et al. 2012, and SmallVCM's
// Emit/Illuminate/GetRadiance).
struct EmissionDensities {
    // Density of emit() producing this origin and direction: the origin's in area measure (1
    // for a point light; 1 / (pi R^2) on the disc of a light at infinity) times the
    // direction's in solid angle (1 for a directional light).
    double emission = 0;
    // Density of illuminate() picking this point: area measure on an area light, solid angle
    // for an environment light, 1 for a delta light.
    double direct = 0;
    double cos_light = 1; // between the emitting normal and the direction (1 without a normal)
};

// One sample of the light arriving at a point, with its densities (illuminate()).
struct LightIllumination {
    Vec3 direction;              // unit, from the point towards the light
    double distance = 0;         // to the sampled point (infinite for lights at infinity)
    Rgb radiance;                // arriving radiance (point and spot lights: intensity); 0 if none
    double direct_pdf_w = 0;     // solid-angle density of `direction` (point and spot lights: dist^2)
    EmissionDensities densities; // of the light leaving the sampled point towards the receiver
};

// One sample of the light arriving at a point.
struct DirectLightSample {
    Vec3 direction;        // unit, from the point towards the light
    double distance = 0;   // to the sampled point on the light (for the shadow ray)
    Rgb radiance_over_pdf; // L(direction) / pdf(direction), solid angle measure; 0 if none
};

class EnvironmentMap;
class Texture;

class Light {
public:
    enum class Type { Point, Spot, Quad, Sphere, Disk, Cylinder, Mesh, Constant, Envmap, Directional };

    // Factories check their arguments (finite, non-negative colours; positive sizes; angles
    // with 0 < beam_width <= cutoff_angle <= 180 degrees; Mitsuba accepts wide
    // cones, and 180 lights the whole sphere) and throw ppm::Error naming the bad one.
    static Light point(const Vec3 &position, const Rgb &intensity);
    static Light spot(const Vec3 &position, const Vec3 &target, const Rgb &intensity, double cutoff_angle_degrees,
                      double beam_width_degrees);
    static Light quad(const Vec3 &origin, const Vec3 &edge_u, const Vec3 &edge_v, const Rgb &radiance);
    static Light sphere(const Vec3 &center, double radius, const Rgb &radiance);
    // {center + x axis_u + y axis_v : x^2 + y^2 <= 1} (an ellipse under a general transform),
    // emitting towards axis_u x axis_v, or away from it when `flip`.
    static Light disk(const Vec3 &center, const Vec3 &axis_u, const Vec3 &axis_v, const Rgb &radiance, bool flip);
    // The open tube of `radius` around the segment p0 -> p1, emitting outwards (inwards when
    // `flip`).
    static Light cylinder(const Vec3 &p0, const Vec3 &p1, double radius, const Rgb &radiance, bool flip);
    // A triangle mesh in world space, shared (not copied): the light keeps it alive. Triangles
    // of zero area are never sampled; a mesh of zero total area is refused.
    static Light mesh(std::shared_ptr<const MeshData> mesh, const Rgb &radiance, bool flip);

    // Surface area of an area light (0 for point and spot lights).
    double area() const { return area_; }
    // Index of the triangle a uniform number picks (mesh lights; probability area / total).
    size_t pick_triangle(double u) const;
    // The mesh a mesh light samples (the geometry's own world-space data), else null.
    const MeshData *mesh_data() const { return table_ ? table_->mesh.get() : nullptr; }

    // Lights at infinity. `to_world` of an envmap: the columns of its linear part (a rotation,
    // possibly mirrored, times a uniform scale; anything else is refused). `direction` of a
    // directional light: where its light travels (Mitsuba's `direction`).
    static Light constant(const Rgb &radiance);
    static Light envmap(std::shared_ptr<const Texture> image, double scale, const Vec3 to_world_columns[3]);
    static Light directional(const Vec3 &direction, const Rgb &irradiance);

    Type type() const { return type_; }
    bool is_infinite() const { return type_ == Type::Constant || type_ == Type::Envmap || type_ == Type::Directional; }
    // Whether a camera ray that leaves the scene in some direction sees this light.
    bool is_environment() const { return type_ == Type::Constant || type_ == Type::Envmap; }
    // Radiance arriving from direction `towards` (unit, world, pointing away from the scene)
    // of an environment light (constant, envmap); black for every other light.
    Rgb environment(const Vec3 &towards) const;
    // Solid-angle density sample_direct draws `towards` with (environment lights only).
    double pdf_direct(const Vec3 &towards) const;
    // The scene's bounding sphere, which photons from lights at infinity are aimed at; sets
    // their power. The renderer calls it with the committed scene's bounds.
    void set_scene_sphere(const Vec3 &center, double radius);
    const EnvironmentMap *environment_map() const { return env_.get(); }
    Rgb power() const { return power_; }

    // A photon from four uniform numbers in [0, 1). Area lights start it `surface_offset`
    // off the surface so it does not hit its own emitter.
    EmittedPhoton emit(double u1, double u2, double u3, double u4) const;
    // Light at `p` from one point on the light picked by (u1, u2); radiance_over_pdf is zero
    // when the sample sees the light's back or p is inside a spherical light.
    DirectLightSample sample_direct(const Vec3 &p, double u1, double u2) const;

    // The bidirectional estimator's questions (light_densities.cpp). Delta lights (point, spot,
    // directional) cannot be hit by a ray; lights at infinity are not finite.
    bool is_delta() const { return type_ == Type::Point || type_ == Type::Spot || type_ == Type::Directional; }
    // Densities of light leaving a point of this light with emitting normal `normal` (as
    // EmittedPhoton::normal, or a hit's shading normal) along `direction` (unit, away from the
    // light; for lights at infinity, the direction their light travels).
    EmissionDensities emission_densities(const Vec3 &normal, const Vec3 &direction) const;
    // Light at `p` from one point picked by (u1, u2): uniform in area on every area light (a
    // sphere too, unlike sample_direct), so that emission_densities().direct is its density.
    LightIllumination illuminate(const Vec3 &p, double u1, double u2) const;

    // Distance photons start off an area light's surface (the scene's hit tolerance).
    void set_surface_offset(double offset) { surface_offset_ = offset; }
    // The scene geometry an area light is (shadow rays towards it skip it), else PPM_INVALID_ID.
    void set_geometry(uint32_t geom_id) { geom_id_ = geom_id; }
    uint32_t geometry() const { return geom_id_; }

private:
    Light() = default;
    Rgb spot_intensity(double cos_theta) const;
    // A point of an area light uniform in area, and its unit emitting normal `n`; `ng` is the
    // surface's own (face) normal on the emitting side, for the photons' offset.
    void sample_area(double u1, double u2, Vec3 *p, Vec3 *n, Vec3 *ng) const;

    struct MeshTable {
        std::shared_ptr<const MeshData> mesh;
        std::vector<double> cdf; // cumulative triangle areas over the total, last = 1
    };

    Type type_ = Type::Point;
    Rgb color_; // intensity (point, spot) or radiance (area)
    Rgb power_;
    Vec3 position_;        // point/spot position, quad origin, sphere centre, scene sphere centre
    Vec3 direction_;       // directional: towards the light (minus Mitsuba's direction)
    Vec3 edge_u_, edge_v_; // quad edges, disk axes; cylinder: p1 - p0 in edge_u_
    Frame frame_;          // spot: n = axis; quad: n = unit normal; envmap: columns of to_world in s, t, n
    double area_ = 0;
    double radius_ = 0;
    double cos_cutoff_ = 0, cos_beam_ = 1, cutoff_ = 0, beam_ = 0;
    double surface_offset_ = 0;
    double normal_sign_ = 1; // -1 when flip_normals
    std::shared_ptr<const MeshTable> table_;
    double scene_radius_ = 0;                   // lights at infinity: bounding sphere
    std::shared_ptr<const EnvironmentMap> env_; // envmap
    uint32_t geom_id_ = 0xFFFFFFFFu;            // PPM_INVALID_ID
};

} // namespace ppm
