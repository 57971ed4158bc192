// SPDX-License-Identifier: Apache-2.0
// Area lights on every shape that can emit, against analytic answers:
//  - a unit square as 2 triangles and as an irregular triangulation (with a zero-area
//    triangle) gives the irradiance of the square quad light on its axis, E = 4 L x /
//    sqrt(1 + x^2) atan(x / sqrt(1 + x^2)) with x = half side / distance, and its power pi L A;
//  - triangles are chosen in proportion to their area (chi-square);
//  - a mesh emits on the side of its shading normal (vertex normals when it has them, else
//    the face normal), the other side after flip_normals, for shadow rays, photons and camera
//    rays alike;
//  - a 1000-triangle sphere mesh approaches the analytic sphere light, E = pi L (r / d)^2;
//  - disks and cylinders: hit distance, normal and uv of Mitsuba's shapes; power pi L A;
//    a disk's irradiance on its axis pi L R^2 / (R^2 + h^2); inside a tube emitting inwards
//    pi L cos^2(alpha) facing an opening of half-angle alpha;
//  - bad input (degenerate disk, p0 == p1, bad radius, flip on a sphere, emitting patches).
#include "api/api_support.h"
#include "geometry/mesh_data.h"
#include "scene/mesh_geometry.h"
#include "shading/render_scene.h"

#include <ppm/ppm.h>

#include "test_support.h"

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

using namespace ppm;

namespace {

constexpr double kPiD = 3.14159265358979323846;

struct Fixture {
    ppm_context context = nullptr;
    ppm_scene scene = nullptr;
    Fixture() {
        assert_int_equal(ppm_context_create(&context), PPM_OK);
        assert_int_equal(ppm_scene_create(context, &scene), PPM_OK);
    }
    ~Fixture() {
        ppm_scene_release(scene);
        ppm_context_release(context);
    }
    uint32_t mesh(const std::vector<double> &positions, const std::vector<uint32_t> &indices,
                  const std::vector<double> *normals = nullptr) {
        uint32_t id = 0;
        assert_int_equal(ppm_scene_add_triangle_mesh(scene, positions.data(), positions.size() / 3, indices.data(),
                                                     indices.size() / 3, normals ? normals->data() : nullptr, nullptr,
                                                     &id),
                         PPM_OK);
        return id;
    }
    void emit(uint32_t id, double radiance) {
        const double l[3] = {radiance, radiance, radiance};
        assert_int_equal(ppm_scene_set_geometry_emission(scene, id, l), PPM_OK);
    }
    // The renderer's view: commits and returns the lights (area lights in geometry order).
    std::unique_ptr<RenderScene> render_scene() {
        assert_int_equal(ppm_scene_commit(scene), PPM_OK);
        return std::make_unique<RenderScene>(*scene, scene->shading);
    }
};

// Irradiance at p on a surface of normal n from `light`, averaged over `count` samples.
double irradiance(const Light &light, const Vec3 &p, const Vec3 &n, int count, uint64_t seed = 7) {
    test_rng rng{seed};
    double sum = 0;
    for (int i = 0; i < count; ++i) {
        const double u1 = test_rng_uniform(&rng), u2 = test_rng_uniform(&rng);
        const DirectLightSample s = light.sample_direct(p, u1, u2);
        const double cos_receiver = dot(s.direction, n);
        if (cos_receiver > 0) sum += s.radiance_over_pdf.mean() * cos_receiver;
    }
    return sum / count;
}

// Square light of half side s at distance h above the point, facing it.
double square_irradiance(double radiance, double s, double h) {
    const double x = s / h, r = std::sqrt(1 + x * x);
    return 4 * radiance * x / r * std::atan(x / r);
}

// The unit square [-0.5, 0.5]^2 at z = 1, normal -z (clockwise seen from above).
const std::vector<double> kSquare = {-0.5, -0.5, 1, -0.5, 0.5, 1, 0.5, 0.5, 1, 0.5, -0.5, 1};
const std::vector<uint32_t> kSquareTriangles = {0, 1, 2, 0, 2, 3};

// The same square cut irregularly: a fan around an off-centre point through the corners and
// two points on the edges, plus a zero-area triangle along an edge.
const std::vector<double> kIrregular = {-0.5, -0.5, 1,    -0.5, 0.5,  1,   0.5, 0.5, 1,   0.5, -0.5,
                                        1,    0.1,  -0.3, 1,    -0.5, 0.2, 1,   0.3, 0.5, 1};
const std::vector<uint32_t> kIrregularTriangles = {4, 0, 5, 4, 5, 1, 4, 1, 6, 4, 6,
                                                   2, 4, 2, 3, 4, 3, 0, 0, 5, 1}; // last: no area

void square_mesh_matches_quad_light(void **) {
    const double radiance = 2.0;
    const double expected = square_irradiance(radiance, 0.5, 1.0);
    const Vec3 p{0, 0, 0}, up{0, 0, 1};
    double quad_power = 0;
    {
        Fixture f;
        const double o[3] = {-0.5, -0.5, 1}, eu[3] = {0, 1, 0}, ev[3] = {1, 0, 0}; // normal -z
        uint32_t id = 0;
        assert_int_equal(ppm_scene_add_quad(f.scene, o, eu, ev, &id), PPM_OK);
        f.emit(id, radiance);
        const auto rs = f.render_scene();
        assert_close(irradiance(rs->lights()[0], p, up, 200000), expected, 0.01 * expected);
        quad_power = rs->lights()[0].power().mean();
        assert_close(quad_power, kPiD * radiance, 1e-12);
    }
    for (int irregular = 0; irregular < 2; ++irregular) {
        Fixture f;
        const uint32_t id = irregular ? f.mesh(kIrregular, kIrregularTriangles) : f.mesh(kSquare, kSquareTriangles);
        f.emit(id, radiance);
        const auto rs = f.render_scene();
        assert_int_equal(rs->lights().size(), 1);
        const Light &light = rs->lights()[0];
        assert_true(light.type() == Light::Type::Mesh);
        // The light samples the geometry's own world-space data, not a copy.
        assert_true(light.mesh_data() == &static_cast<const MeshGeometry &>(f.scene->geometry(id)).world());
        assert_close(light.area(), 1.0, 1e-12);
        assert_close(light.power().mean(), quad_power, 1e-12);
        assert_close(irradiance(light, p, up, 200000), expected, 0.01 * expected);
        // Photons start on the square (just below it), leave downwards, cosine-distributed
        // (mean cos 2/3), each with the light's whole power.
        test_rng rng{3};
        double mean_cos = 0;
        const int count = 100000;
        for (int i = 0; i < count; ++i) {
            double u[4];
            for (double &x : u) x = test_rng_uniform(&rng);
            const EmittedPhoton ph = light.emit(u[0], u[1], u[2], u[3]);
            assert_true(std::fabs(ph.origin.x) <= 0.5 + 1e-9 && std::fabs(ph.origin.y) <= 0.5 + 1e-9);
            assert_true(ph.origin.z < 1 && ph.origin.z > 1 - 1e-6);
            assert_true(ph.direction.z < 0);
            assert_close(ph.flux.mean(), quad_power, 1e-12);
            mean_cos += -ph.direction.z / count;
        }
        assert_close(mean_cos, 2.0 / 3.0, 0.005);
    }
}

void triangles_chosen_in_proportion_to_area(void **) {
    Fixture f;
    const uint32_t id = f.mesh(kIrregular, kIrregularTriangles);
    f.emit(id, 1);
    const auto rs = f.render_scene();
    const Light &light = rs->lights()[0];
    const size_t n = kIrregularTriangles.size() / 3;
    std::vector<double> area(n);
    for (size_t k = 0; k < n; ++k) {
        const double *a = &kIrregular[3 * kIrregularTriangles[3 * k]],
                     *b = &kIrregular[3 * kIrregularTriangles[3 * k + 1]],
                     *c = &kIrregular[3 * kIrregularTriangles[3 * k + 2]];
        area[k] = 0.5 * std::fabs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    std::vector<int> counts(n, 0);
    test_rng rng{11};
    const int samples = 100000;
    for (int i = 0; i < samples; ++i) counts[light.pick_triangle(test_rng_uniform(&rng))]++;
    assert_int_equal(counts[n - 1], 0); // the zero-area triangle
    double chi2 = 0;
    for (size_t k = 0; k + 1 < n; ++k) {
        const double expected = samples * area[k];
        chi2 += (counts[k] - expected) * (counts[k] - expected) / expected;
    }
    // 5 degrees of freedom: P(chi2 > 20.5) = 0.001.
    assert_true(chi2 < 20.5);
}

// A triangle at z = 1 whose face normal is +z (counter-clockwise from above).
const std::vector<double> kUpTriangle = {0, 0, 1, 1, 0, 1, 0, 1, 1};
const std::vector<uint32_t> kOneTriangle = {0, 1, 2};

void mesh_emits_on_the_side_of_its_shading_normal(void **) {
    const Vec3 above{0.2, 0.2, 2}, below{0.2, 0.2, 0};
    const Vec3 down{0, 0, -1}, up{0, 0, 1};
    const std::vector<double> normals_down = {0, 0, -1, 0, 0, -1, 0, 0, -1};
    for (int variant = 0; variant < 4; ++variant) {
        // 0: face normal up; 1: flipped; 2: vertex normals down; 3: vertex normals down, flipped.
        Fixture f;
        const uint32_t id = f.mesh(kUpTriangle, kOneTriangle, variant >= 2 ? &normals_down : nullptr);
        if (variant % 2) assert_int_equal(ppm_scene_set_geometry_flip_normals(f.scene, id, 1), PPM_OK);
        f.emit(id, 1);
        const auto rs = f.render_scene();
        const Light &light = rs->lights()[0];
        const bool emits_up = variant == 0 || variant == 3;
        const double e_above = irradiance(light, above, down, 1000), e_below = irradiance(light, below, up, 1000);
        assert_true(emits_up ? (e_above > 0 && e_below == 0) : (e_above == 0 && e_below > 0));
        test_rng rng{5};
        for (int i = 0; i < 100; ++i) {
            double u[4];
            for (double &x : u) x = test_rng_uniform(&rng);
            const EmittedPhoton ph = light.emit(u[0], u[1], u[2], u[3]);
            assert_true(emits_up ? ph.direction.z > 0 : ph.direction.z < 0);
        }
        // Camera rays see the emission from the emitting side only.
        for (int from_above = 0; from_above < 2; ++from_above) {
            ppm_ray ray{};
            ray.org[0] = 0.2;
            ray.org[1] = 0.2;
            ray.org[2] = from_above ? 3 : -1;
            ray.dir[2] = from_above ? -1 : 1;
            ray.tfar = INFINITY;
            SurfacePoint sp;
            assert_true(rs->intersect(ray, sp));
            assert_true(sp.emitted.is_black() == (from_above != emits_up));
        }
    }
}

// UV sphere of `rings` x `segments` quads (two triangles each, one at the poles) with radial
// vertex normals.
void sphere_mesh(double r, int rings, int segments, std::vector<double> &pos, std::vector<uint32_t> &idx,
                 std::vector<double> &normals) {
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            const double theta = kPiD * i / rings, phi = 2 * kPiD * j / segments;
            const double n[3] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
            for (double c : n) {
                pos.push_back(r * c);
                normals.push_back(c);
            }
        }
    const auto at = [&](int i, int j) { return static_cast<uint32_t>(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            // Outward winding: (theta, phi) increasing is (down, around), so a, c, b.
            const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            if (i > 0) idx.insert(idx.end(), {a, b, d});
            if (i + 1 < rings) idx.insert(idx.end(), {d, b, c});
        }
}

void sphere_mesh_approaches_the_sphere_light(void **) {
    std::vector<double> pos, normals;
    std::vector<uint32_t> idx;
    sphere_mesh(1.0, 20, 26, pos, idx, normals); // 2 * 20 * 26 - 2 * 26 = 988 triangles
    assert_true(idx.size() / 3 >= 980 && idx.size() / 3 <= 1040);
    Fixture f;
    const uint32_t mesh = f.mesh(pos, idx, &normals);
    f.emit(mesh, 1);
    const double c[3] = {0, 0, 0};
    uint32_t sphere = 0;
    assert_int_equal(ppm_scene_add_sphere(f.scene, c, 1.0, &sphere), PPM_OK);
    f.emit(sphere, 1);
    const auto rs = f.render_scene();
    const Light &m = rs->lights()[0], &s = rs->lights()[1];
    assert_true(m.type() == Light::Type::Mesh && s.type() == Light::Type::Sphere);
    // The inscribed mesh's area falls short by O(1 / n^2): here about 1 %.
    assert_close(m.power().mean() / s.power().mean(), 1.0, 0.015);
    assert_true(m.power().mean() < s.power().mean());
    const double d = 3.0, expected = kPiD / (d * d);
    const Vec3 p{d, 0, 0}, n{-1, 0, 0};
    assert_close(irradiance(s, p, n, 100000), expected, 0.005 * expected);
    assert_close(irradiance(m, p, n, 400000), expected, 0.02 * expected);
}

void disk_and_cylinder_hits(void **) {
    Fixture f;
    const double c[3] = {0, 0, 0}, ux[3] = {1, 0, 0}, uy[3] = {0, 1, 0};
    uint32_t disk = 0, cyl = 0;
    assert_int_equal(ppm_scene_add_disk(f.scene, c, ux, uy, &disk), PPM_OK);
    const double p0[3] = {10, 0, 0}, p1[3] = {10, 0, 1};
    assert_int_equal(ppm_scene_add_cylinder(f.scene, p0, p1, 1.0, &cyl), PPM_OK);
    assert_int_equal(ppm_scene_commit(f.scene), PPM_OK);
    const auto trace = [&](const double o[3], const double d[3], ppm_hit &hit) {
        ppm_ray ray{};
        std::memcpy(ray.org, o, sizeof ray.org);
        std::memcpy(ray.dir, d, sizeof ray.dir);
        ray.tfar = INFINITY;
        assert_int_equal(ppm_scene_intersect(f.scene, &ray, 1, &hit), PPM_OK);
    };
    ppm_hit hit;
    {
        const double o[3] = {0.3, 0.4, 5}, d[3] = {0, 0, -1};
        trace(o, d, hit);
        assert_int_equal(hit.geom_id, disk);
        assert_close(hit.t, 5, 1e-12);
        assert_close(hit.ng[2], 1, 1e-15);
        assert_close(hit.ns[2], 1, 1e-15);
        assert_close(hit.u, 0.5, 1e-12);
        assert_close(hit.v, std::atan2(0.4, 0.3) / (2 * kPiD), 1e-12);
        const double o2[3] = {0.3, -0.4, -2}, d2[3] = {0, 0, 1};
        trace(o2, d2, hit); // from below: same normal (two-sided), v past one half
        assert_int_equal(hit.geom_id, disk);
        assert_close(hit.v, 1 - std::atan2(0.4, 0.3) / (2 * kPiD), 1e-12);
        const double o3[3] = {0.8, 0.61, 5};
        trace(o3, d, hit); // r = 1.006: outside
        assert_int_equal(hit.geom_id, PPM_INVALID_ID);
    }
    {
        const double o[3] = {15, 0, 0.5}, d[3] = {-1, 0, 0};
        trace(o, d, hit); // outside: the near side at x = 11
        assert_int_equal(hit.geom_id, cyl);
        assert_close(hit.t, 4, 1e-12);
        assert_close(hit.ng[0], 1, 1e-12);
        assert_close(hit.u, 0, 1e-12);
        assert_close(hit.v, 0.5, 1e-12);
        const double o2[3] = {10, 0, 0.25}, d2[3] = {0, 2, 0};
        trace(o2, d2, hit); // from the axis: the far side, normal still outward
        assert_int_equal(hit.geom_id, cyl);
        assert_close(hit.t, 0.5, 1e-12);
        assert_close(hit.ng[1], 1, 1e-12);
        assert_close(hit.u, 0.25, 1e-12);
        assert_close(hit.v, 0.25, 1e-12);
        const double o3[3] = {10, 0, 2}, d3[3] = {0.5, 0, -0.6};
        trace(o3, d3, hit); // in through the open top: only the far root, on the inside
        assert_int_equal(hit.geom_id, cyl);
        assert_close(hit.t, 2, 1e-12);
        assert_close(hit.p[2], 0.8, 1e-12);
        assert_close(hit.ng[0], 1, 1e-12);
        const double o4[3] = {15, 0, 1.5};
        trace(o4, d, hit); // above the tube
        assert_int_equal(hit.geom_id, PPM_INVALID_ID);
    }
}

void disk_and_cylinder_lights(void **) {
    const double radiance = 1.5;
    Fixture f;
    // A disk of radius 2 at z = 1 facing down (flipped), and a tube of radius 0.5, height 4
    // emitting inwards.
    const double c[3] = {0, 0, 1}, ux[3] = {2, 0, 0}, uy[3] = {0, 2, 0};
    uint32_t disk = 0, cyl = 0;
    assert_int_equal(ppm_scene_add_disk(f.scene, c, ux, uy, &disk), PPM_OK);
    assert_int_equal(ppm_scene_set_geometry_flip_normals(f.scene, disk, 1), PPM_OK);
    f.emit(disk, radiance);
    const double p0[3] = {20, 0, -2}, p1[3] = {20, 0, 2};
    assert_int_equal(ppm_scene_add_cylinder(f.scene, p0, p1, 0.5, &cyl), PPM_OK);
    assert_int_equal(ppm_scene_set_geometry_flip_normals(f.scene, cyl, 1), PPM_OK);
    f.emit(cyl, radiance);
    const auto rs = f.render_scene();
    const Light &d = rs->lights()[0], &t = rs->lights()[1];
    assert_close(d.power().mean(), kPiD * radiance * kPiD * 4, 1e-9);
    assert_close(t.power().mean(), kPiD * radiance * 2 * kPiD * 0.5 * 4, 1e-9);
    const double h = 1.5, disk_expected = kPiD * radiance * 4 / (4 + h * h);
    assert_close(irradiance(d, {0, 0, 1 - h}, {0, 0, 1}, 200000), disk_expected, 0.01 * disk_expected);
    assert_close(irradiance(d, {0, 0, 1 + h}, {0, 0, -1}, 1000), 0, 0); // its back
    const double cos_alpha = 2 / std::sqrt(4 + 0.25), tube_expected = kPiD * radiance * cos_alpha * cos_alpha;
    assert_close(irradiance(t, {20, 0, 0}, {0, 0, 1}, 400000), tube_expected, 0.01 * tube_expected);
    test_rng rng{9};
    for (int i = 0; i < 200; ++i) {
        double u[4];
        for (double &x : u) x = test_rng_uniform(&rng);
        const EmittedPhoton pd = d.emit(u[0], u[1], u[2], u[3]), pt = t.emit(u[0], u[1], u[2], u[3]);
        assert_true(pd.direction.z < 0 && pd.origin.x * pd.origin.x + pd.origin.y * pd.origin.y <= 4 + 1e-9);
        const Vec3 radial{pt.origin.x - 20, pt.origin.y, 0};
        assert_true(dot(radial, pt.direction) < 0); // inwards
        assert_close(length(radial), 0.5, 1e-6);
        assert_true(pt.origin.z >= -2 && pt.origin.z <= 2);
    }
}

void bad_input(void **) {
    Fixture f;
    const double c[3] = {0, 0, 0}, ux[3] = {1, 0, 0}, ux2[3] = {2, 0, 0}, nan3[3] = {NAN, 0, 0};
    uint32_t id = 0;
    assert_int_equal(ppm_scene_add_disk(f.scene, c, ux, ux2, &id), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(std::strstr(ppm_last_error_message(), "no area"));
    assert_int_equal(ppm_scene_add_disk(f.scene, nan3, ux, ux2, &id), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(std::strstr(ppm_last_error_message(), "center"));
    assert_int_equal(ppm_scene_add_cylinder(f.scene, c, c, 1, &id), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(std::strstr(ppm_last_error_message(), "p0 and p1"));
    assert_int_equal(ppm_scene_add_cylinder(f.scene, c, ux, 0, &id), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(std::strstr(ppm_last_error_message(), "radius"));
    assert_int_equal(ppm_scene_add_cylinder(f.scene, c, ux, NAN, &id), PPM_ERROR_INVALID_ARGUMENT);
    assert_int_equal(ppm_scene_add_cylinder(f.scene, nan3, ux, 1, &id), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(std::strstr(ppm_last_error_message(), "p0"));
    assert_int_equal(ppm_scene_add_sphere(f.scene, c, 1, &id), PPM_OK);
    assert_int_equal(ppm_scene_set_geometry_flip_normals(f.scene, id, 1), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(std::strstr(ppm_last_error_message(), "flip_normals"));
    std::vector<double> patch(48);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            patch[3 * (4 * i + j)] = j;
            patch[3 * (4 * i + j) + 1] = i;
        }
    assert_int_equal(ppm_scene_add_bezier_patches(f.scene, patch.data(), 1, &id), PPM_OK);
    const double l[3] = {1, 1, 1};
    assert_int_equal(ppm_scene_set_geometry_emission(f.scene, id, l), PPM_ERROR_INVALID_ARGUMENT);
    assert_non_null(std::strstr(ppm_last_error_message(), "Bezier patches cannot be area lights"));
}

} // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(square_mesh_matches_quad_light),
        cmocka_unit_test(triangles_chosen_in_proportion_to_area),
        cmocka_unit_test(mesh_emits_on_the_side_of_its_shading_normal),
        cmocka_unit_test(sphere_mesh_approaches_the_sphere_light),
        cmocka_unit_test(disk_and_cylinder_hits),
        cmocka_unit_test(disk_and_cylinder_lights),
        cmocka_unit_test(bad_input),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
