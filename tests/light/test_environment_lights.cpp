// SPDX-License-Identifier: Apache-2.0
// Lights at infinity (constant, envmap, directional): the envmap's sampling against its pdf
// (chi-square over cells), the pdf's integral over the sphere, Mitsuba 3's orientation of a
// lat-long map, bad input, and renders against analytic answers: a diffuse sphere under a
// constant environment is rho L (direct light on, and photons only), a plane under a
// directional light is E cos(theta) rho / pi.
#include "api/api_support.h"
#include "core/error.h"
#include "light/environment_map.h"
#include "light/light.h"
#include "material/texture.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "api_asserts.h"
#include "test_support.h"

using namespace ppm;

namespace {

constexpr double kPiD = 3.14159265358979323846;

double channel(const Rgb &c, int i) { return i == 0 ? c.r : i == 1 ? c.g : c.b; }

// A W x H map: grey `base` with pixel (bx, by) set to `bright` (by < 0: none), plus a gentle
// pattern so that cells differ.
std::shared_ptr<const Texture> make_map(int w, int h, double base, int bx, int by, double bright, bool pattern) {
    std::vector<float> rgb(static_cast<size_t>(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                double v = base * (pattern ? 1 + 0.5 * std::sin(x * 0.7 + c) * std::cos(y * 1.3) : 1);
                if (x == bx && y == by) v = bright;
                rgb[(static_cast<size_t>(y) * w + x) * 3 + c] = static_cast<float>(v);
            }
    return std::make_shared<Texture>(w, h, std::move(rgb), "test map");
}

const Vec3 kIdentity[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

void envmap_sampling_matches_its_pdf(void **) {
    const int w = 16, h = 9;
    const EnvironmentMap map(*make_map(w, h, 1.0, 5, 3, 40.0, true), 1.0);
    // Bins: the sampling cells (columns shifted half a texel, rows between pixel rows).
    const int rows = h - 1, bins = w * rows;
    std::vector<double> expected(bins, 0);
    // Expected probability of a bin: the pdf integrated over it, sub-sampled in (u, v) with
    // the Jacobian 2 pi^2 sin(theta).
    const int sub = 8;
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < w; ++i)
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b) {
                    const double u = (i + (a + 0.5) / sub) / w + 0.5 / w, v = (j + (b + 0.5) / sub) / rows;
                    const Vec3 d = EnvironmentMap::uv_to_direction(u, v);
                    expected[j * w + i] +=
                        map.pdf(d) * 2 * kPiD * kPiD * std::sin(v * kPiD) / (static_cast<double>(w) * rows * sub * sub);
                }
    double total = 0;
    for (double e : expected) total += e;
    assert_close(total, 1.0, 1e-9);
    const int n = 400000;
    std::vector<double> observed(bins, 0);
    test_rng rng{7};
    for (int k = 0; k < n; ++k) {
        double pdf;
        const Vec3 d = map.sample(test_rng_uniform(&rng), test_rng_uniform(&rng), &pdf);
        assert_true(pdf > 0);
        assert_close(pdf, map.pdf(d), 1e-6 * pdf);
        double u, v;
        EnvironmentMap::direction_to_uv(d, &u, &v);
        u -= 0.5 / w;
        u -= std::floor(u);
        const int i = std::min(static_cast<int>(u * w), w - 1), j = std::min(static_cast<int>(v * rows), rows - 1);
        observed[j * w + i] += 1;
    }
    double chi2 = 0;
    int dof = -1;
    for (int b = 0; b < bins; ++b) {
        const double e = expected[b] * n;
        if (e < 5) continue;
        chi2 += (observed[b] - e) * (observed[b] - e) / e;
        ++dof;
    }
    print_message("envmap chi-square %.1f over %d degrees of freedom\n", chi2, dof);
    assert_true(chi2 < dof + 5 * std::sqrt(2.0 * dof));
}

void envmap_pdf_integrates_to_one(void **) {
    const EnvironmentMap map(*make_map(12, 7, 0.3, 2, 5, 25.0, true), 2.0);
    // Midpoint rule over (theta, phi) on a grid aligned with the sampling cells (rows every
    // pi / 6, columns half a texel right): pdf sin(theta) is constant on each cell.
    const int nt = 6 * 120, np = 12 * 120;
    double sum = 0, radiance = 0;
    for (int a = 0; a < nt; ++a) {
        const double theta = (a + 0.5) * kPiD / nt;
        for (int b = 0; b < np; ++b) {
            const double phi = ((b + 0.5) / np + 0.5 / 12) * 2 * kPiD;
            const Vec3 d{std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta)};
            const double dw = std::sin(theta) * (kPiD / nt) * (2 * kPiD / np);
            sum += map.pdf(d) * dw;
            radiance += map.eval(d).mean() * dw;
        }
    }
    assert_close(sum, 1.0, 1e-9);
    // The integral the light's power uses, to first order in the cell size.
    assert_close(map.integral().mean(), radiance, 0.03 * radiance);
}

// Irradiance at a surface of normal n from a light, by its own shadow-ray samples.
double irradiance(const Light &light, const Vec3 &n, int samples = 200000) {
    test_rng rng{11};
    double sum = 0;
    for (int k = 0; k < samples; ++k) {
        const DirectLightSample s = light.sample_direct({0, 0, 0}, test_rng_uniform(&rng), test_rng_uniform(&rng));
        assert_true(std::isinf(s.distance) || s.radiance_over_pdf.is_black());
        sum += s.radiance_over_pdf.mean() * std::max(0.0, dot(s.direction, n));
    }
    return sum / samples;
}

void envmap_orientation_follows_mitsuba(void **) {
    // Mitsuba's mapping: d = (sin phi sin theta, cos theta, -cos phi sin theta), u = phi / 2 pi,
    // v = theta / pi; pixel x's centre at u = (x + 1/2) / W, row y at v = y / (H - 1).
    const Vec3 up = EnvironmentMap::uv_to_direction(0.3, 0.0);
    assert_close(up.y, 1, 1e-12);
    const Vec3 east = EnvironmentMap::uv_to_direction(0.25, 0.5);
    assert_close(east.x, 1, 1e-12);
    const Vec3 minus_z = EnvironmentMap::uv_to_direction(0.0, 0.5);
    assert_close(minus_z.z, -1, 1e-12);
    const int w = 8, h = 5;
    // Pixel (1, 2): u = 1.5 / 8 = 0.1875, v = 2 / 4 = 0.5 (the equator).
    const auto image = make_map(w, h, 0.0, 1, 2, 10.0, false);
    const EnvironmentMap map(*image, 3.0);
    const Vec3 d = EnvironmentMap::uv_to_direction(1.5 / w, 0.5);
    assert_close(map.eval(d).r, 30.0, 1e-6);
    assert_close(map.eval(EnvironmentMap::uv_to_direction(1.5 / w + 0.5 / w, 0.5)).g, 15.0, 1e-5); // bilinear
    assert_close(map.eval(EnvironmentMap::uv_to_direction(3.5 / w, 0.5)).b, 0.0, 1e-12);
    // The top row is the north pole (+Y): a map bright in row 0 only lights +Y.
    const EnvironmentMap top(*make_map(w, h, 0.0, 4, 0, 10.0, false), 1.0);
    assert_true(top.eval({0, 1, 0}).r > 0);
    assert_close(top.eval({0, -1, 0}).r, 0, 0);
    // A light bright in pixel (2, 2) (u = 2.5 / 8, 22.5 degrees past +X) lights a plane
    // facing it and not one facing away; to_world turns it.
    const Light light = Light::envmap(make_map(w, h, 0.0, 2, 2, 10.0, false), 1.0, kIdentity);
    const Vec3 towards = EnvironmentMap::uv_to_direction(2.5 / w, 0.5);
    const double facing = irradiance(light, towards), away = irradiance(light, towards * -1.0);
    print_message("envmap irradiance towards the bright pixel %.4f, away %.4f\n", facing, away);
    assert_true(facing > 0.1);
    assert_close(away, 0, 0);
    // Rotate 90 degrees about +Y: local +X goes to world -Z.
    const Vec3 rot_y[3] = {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}};
    const Light turned = Light::envmap(make_map(w, h, 0.0, 2, 2, 10.0, false), 1.0, rot_y);
    const Vec3 turned_towards{towards.z, towards.y, -towards.x}; // M (x, y, z) = (z, y, -x)
    assert_close(irradiance(turned, turned_towards), facing, 1e-9 + 1e-3 * facing);
    assert_close(irradiance(turned, turned_towards * -1.0), 0, 0);
    assert_close(turned.environment(turned_towards).r, light.environment(towards).r, 1e-9);
}

void lights_at_infinity_have_the_expected_power(void **) {
    Light c = Light::constant(Rgb(2.0));
    c.set_scene_sphere({1, 2, 3}, 2.0);
    assert_close(c.power().r, 4 * kPiD * kPiD * 4 * 2.0, 1e-9);
    Light d = Light::directional({0, 0, -1}, Rgb(3.0));
    d.set_scene_sphere({0, 0, 0}, 2.0);
    assert_close(d.power().g, kPiD * 4 * 3.0, 1e-9);
    // Photons: start outside the sphere on the light's side, travel along the light, carry
    // pi R^2 E (directional) or 4 pi^2 R^2 L (constant).
    test_rng rng{3};
    for (int k = 0; k < 1000; ++k) {
        const double u[4] = {test_rng_uniform(&rng), test_rng_uniform(&rng), test_rng_uniform(&rng),
                             test_rng_uniform(&rng)};
        const EmittedPhoton p = d.emit(u[0], u[1], u[2], u[3]);
        assert_close(p.direction.z, -1, 1e-12);
        assert_close(p.origin.z, 2.0, 1e-9);
        assert_true(p.origin.x * p.origin.x + p.origin.y * p.origin.y <= 4 + 1e-9);
        assert_close(p.flux.r, kPiD * 4 * 3.0, 1e-9);
        const EmittedPhoton q = c.emit(u[0], u[1], u[2], u[3]);
        assert_true(length(q.origin - Vec3{1, 2, 3}) >= 2.0 - 1e-9);
        assert_close(dot(q.origin - Vec3{1, 2, 3}, q.direction), -2.0, 1e-9);
        assert_close(q.flux.r, c.power().r, 1e-9);
        // Directional light arrives from minus its direction, with irradiance E.
        const DirectLightSample s = d.sample_direct({0, 0, 0}, u[0], u[1]);
        assert_close(s.direction.z, 1, 1e-12);
        assert_true(std::isinf(s.distance));
        assert_close(s.radiance_over_pdf.b, 3.0, 0);
    }
}

void write_exr(const std::string &path, int w, int h, const std::vector<float> &rgb) {
    auto out = OIIO::ImageOutput::create(path);
    assert_non_null(out.get());
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::FLOAT);
    assert_true(out->open(path, spec));
    assert_true(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
    out->close();
}

template <class F> std::string error_of(F &&f) {
    try {
        f();
    } catch (const Error &e) {
        return e.what();
    }
    return "";
}

void bad_input_is_refused(void **) {
    char folder[512];
    assert_int_equal(test_make_folder(folder, sizeof folder, "ppm-envmap-"), 0);
    const std::string missing = std::string(folder) + "/missing.exr";
    std::string message = error_of([&] { Texture::load(missing); });
    assert_non_null(std::strstr(message.c_str(), "missing.exr"));
    std::vector<float> rgb(4 * 3 * 3, 1.0f);
    rgb[7] = std::numeric_limits<float>::quiet_NaN();
    const std::string nan_path = std::string(folder) + "/nan.exr";
    write_exr(nan_path, 4, 3, rgb);
    message = error_of([&] { Texture::load(nan_path); });
    assert_non_null(std::strstr(message.c_str(), "nan.exr"));
    assert_non_null(std::strstr(message.c_str(), "NaN"));
    rgb[7] = 1.0f;
    const std::string ok_path = std::string(folder) + "/ok.exr";
    write_exr(ok_path, 4, 3, rgb);
    const auto image = Texture::load(ok_path);
    message = error_of([&] { Light::envmap(image, 0.0, kIdentity); });
    assert_non_null(std::strstr(message.c_str(), "scale"));
    message = error_of([&] { Light::envmap(image, std::nan(""), kIdentity); });
    assert_non_null(std::strstr(message.c_str(), "scale"));
    const Vec3 sheared[3] = {{1, 0, 0}, {0.5, 1, 0}, {0, 0, 1}};
    message = error_of([&] { Light::envmap(image, 1.0, sheared); });
    assert_non_null(std::strstr(message.c_str(), "to_world"));
    message = error_of([&] { Light::envmap(make_map(2, 2, 1, -1, -1, 0, false), 1.0, kIdentity); });
    assert_non_null(std::strstr(message.c_str(), "2 x 3"));
    message = error_of([&] { Light::constant(Rgb(-1.0)); });
    assert_non_null(std::strstr(message.c_str(), "radiance"));
    message = error_of([&] { Light::directional({0, 0, 0}, Rgb(1.0)); });
    assert_non_null(std::strstr(message.c_str(), "direction"));
    message = error_of([&] { Light::directional({0, 0, 1}, Rgb(NAN)); });
    assert_non_null(std::strstr(message.c_str(), "irradiance"));
    std::remove(nan_path.c_str());
    std::remove(ok_path.c_str());
    test_remove_folder(folder);
}

// --- Renders ---

struct Picture {
    int w = 0, h = 0;
    std::vector<float> rgb;
    double mean(int x0, int y0, int x1, int y1, int c) const {
        double s = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) s += rgb[(static_cast<size_t>(y) * w + x) * 3 + c];
        return s / ((x1 - x0) * (y1 - y0));
    }
};

Picture render(ppm_scene scene, const double origin[3], const double target[3], const double up[3], double fov,
               int size, const char *mode, int direct_lighting, int passes, int photons) {
    ppm_camera camera;
    std::memset(&camera, 0, sizeof camera);
    std::memcpy(camera.origin, origin, sizeof camera.origin);
    std::memcpy(camera.target, target, sizeof camera.target);
    std::memcpy(camera.up, up, sizeof camera.up);
    camera.fov = fov;
    camera.width = camera.height = static_cast<uint32_t>(size);
    ppm_renderer r = nullptr;
    assert_ppm_ok(ppm_renderer_create(scene, &camera, &r));
    assert_ppm_ok(ppm_renderer_set_string(r, "mode", mode));
    assert_ppm_ok(ppm_renderer_set_int(r, "direct_lighting", direct_lighting));
    if (std::strcmp(mode, "vcm") != 0) // vcm: its automatic count, one light subpath per pixel
        assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", photons));
    for (int i = 0; i < passes; ++i) assert_ppm_ok(ppm_render_pass(r));
    Picture p;
    p.w = p.h = size;
    p.rgb.resize(static_cast<size_t>(size) * size * 3);
    assert_ppm_ok(ppm_renderer_get_layer(r, "radiance", p.rgb.data(), p.rgb.size()));
    ppm_renderer_release(r);
    return p;
}

// `envmap` true: the same radiance as a uniform environment map (its own sampling and photons).
void sphere_under_constant_environment(void **state, const char *mode, int direct_lighting, bool envmap = false) {
    scene_fixture *f = static_cast<scene_fixture *>(*state);
    const double rho[3] = {0.5, 0.25, 0.8}, center[3] = {0, 0, 0};
    uint32_t m, g;
    assert_ppm_ok(ppm_scene_add_diffuse_material(f->scene, rho, &m));
    assert_ppm_ok(ppm_scene_add_sphere(f->scene, center, 1.0, &g));
    assert_ppm_ok(ppm_scene_set_geometry_material(f->scene, g, m));
    const Rgb radiance(1.0, 2.0, 0.5);
    if (envmap) {
        std::vector<float> rgb;
        for (int k = 0; k < 8 * 5; ++k) rgb.insert(rgb.end(), {1.0f, 2.0f, 0.5f});
        f->scene->shading.add_light(
            Light::envmap(std::make_shared<Texture>(8, 5, std::move(rgb), "uniform"), 1.0, kIdentity));
    } else {
        f->scene->shading.add_light(Light::constant(radiance));
    }
    assert_ppm_ok(ppm_scene_commit(f->scene));
    const double origin[3] = {0, 0, -4}, target[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    const Picture p = render(f->scene, origin, target, up, 40, 32, mode, direct_lighting, direct_lighting ? 128 : 24,
                             direct_lighting ? 2000 : 100000);
    // The sphere fills the centre (its silhouette is 29 degrees across); the corners see the sky.
    const double want[3] = {0.5 * 1.0, 0.25 * 2.0, 0.8 * 0.5};
    for (int c = 0; c < 3; ++c) {
        const double centre = p.mean(8, 8, 24, 24, c), corner = p.mean(0, 0, 3, 3, c);
        print_message("%s environment %s direct_lighting=%d channel %d: sphere %.4f (expected %.4f), sky "
                      "%.4f\n",
                      envmap ? "uniform envmap" : "constant", mode, direct_lighting, c, centre, want[c], corner);
        // One uniform shadow sample a pass: 1.3 rho L standard deviation each, 0.7 % over the
        // 16 x 16 x 128 samples.
        assert_close(centre, want[c], (direct_lighting ? 0.025 : 0.04) * want[c]);
        assert_close(corner, channel(radiance, c), 1e-6 * channel(radiance, c));
    }
}

void sphere_constant_sppm(void **state) { sphere_under_constant_environment(state, "sppm", 1); }
void sphere_constant_sppm_photons_only(void **state) { sphere_under_constant_environment(state, "sppm", 0); }
void sphere_constant_ppm(void **state) { sphere_under_constant_environment(state, "ppm", 1); }
void sphere_constant_pppm_photons_only(void **state) { sphere_under_constant_environment(state, "pppm", 0); }
void sphere_uniform_envmap(void **state) { sphere_under_constant_environment(state, "sppm", 1, true); }
void sphere_uniform_envmap_photons_only(void **state) { sphere_under_constant_environment(state, "sppm", 0, true); }
void sphere_constant_vcm(void **state) { sphere_under_constant_environment(state, "vcm", 1); }
void sphere_uniform_envmap_vcm(void **state) { sphere_under_constant_environment(state, "vcm", 1, true); }

void plane_under_directional_light(void **state, const char *mode, int direct_lighting) {
    scene_fixture *f = static_cast<scene_fixture *>(*state);
    const double rho[3] = {0.8, 0.8, 0.8};
    const double origin[3] = {-2, -2, 0}, eu[3] = {4, 0, 0}, ev[3] = {0, 4, 0};
    uint32_t m, g;
    assert_ppm_ok(ppm_scene_add_diffuse_material(f->scene, rho, &m));
    assert_ppm_ok(ppm_scene_add_quad(f->scene, origin, eu, ev, &g));
    assert_ppm_ok(ppm_scene_set_geometry_material(f->scene, g, m));
    const double theta = 0.6;
    const Rgb irradiance(2.0, 1.0, 3.0);
    f->scene->shading.add_light(Light::directional({std::sin(theta), 0, -std::cos(theta)}, irradiance));
    assert_ppm_ok(ppm_scene_commit(f->scene));
    const double cam[3] = {0, 0, 3}, target[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    const Picture p = render(f->scene, cam, target, up, 40, 24, mode, direct_lighting, direct_lighting ? 2 : 16,
                             direct_lighting ? 1000 : 200000);
    for (int c = 0; c < 3; ++c) {
        const double want = channel(irradiance, c) * std::cos(theta) * 0.8 / kPiD, got = p.mean(6, 6, 18, 18, c);
        print_message("directional %s direct_lighting=%d channel %d: %.4f (expected %.4f)\n", mode, direct_lighting, c,
                      got, want);
        // sppm's shadow rays are exact here; vcm weighs them against light tracing (noisy).
        const bool exact = direct_lighting && std::strcmp(mode, "sppm") == 0;
        assert_close(got, want, (exact ? 1e-5 : 0.03) * want);
    }
}

void plane_directional(void **state) { plane_under_directional_light(state, "sppm", 1); }
void plane_directional_photons_only(void **state) { plane_under_directional_light(state, "sppm", 0); }
void plane_directional_vcm(void **state) { plane_under_directional_light(state, "vcm", 1); }

// The three types through JSON and Mitsuba XML scene files (the generic light table): the
// sky a camera sees, and errors naming the parameter or the file.
Picture render_file(ppm_scene_file file, int passes) {
    ppm_renderer r = nullptr;
    assert_ppm_ok(ppm_scene_file_create_renderer(file, &r));
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", 1000));
    for (int i = 0; i < passes; ++i) assert_ppm_ok(ppm_render_pass(r));
    int64_t w = 0, h = 0, lights = 0;
    assert_ppm_ok(ppm_renderer_get_int(r, "width", &w));
    assert_ppm_ok(ppm_renderer_get_int(r, "height", &h));
    assert_ppm_ok(ppm_renderer_get_int(r, "lights", &lights));
    assert_true(lights >= 1);
    Picture p;
    p.w = static_cast<int>(w), p.h = static_cast<int>(h);
    p.rgb.resize(static_cast<size_t>(w * h * 3));
    assert_ppm_ok(ppm_renderer_get_layer(r, "radiance", p.rgb.data(), p.rgb.size()));
    ppm_renderer_release(r);
    return p;
}

ppm_status load_text(ppm_context context, const std::string &text, const char *name, const char *folder,
                     ppm_scene_file *out) {
    return ppm_scene_file_load_memory(context, text.data(), text.size(), name, folder, nullptr, out);
}

void scene_files_load_the_types(void **state) {
    scene_fixture *f = static_cast<scene_fixture *>(*state);
    char folder[512];
    assert_int_equal(test_make_folder(folder, sizeof folder, "ppm-envfile-"), 0);
    std::vector<float> rgb(6 * 4 * 3, 0.5f);
    write_exr(std::string(folder) + "/sky.exr", 6, 4, rgb);
    // JSON: constant + directional; the sky seen is the constant radiance.
    const std::string json = R"({
      "sensor": { "type": "perspective", "fov": 30,
                  "to_world": { "look_at": { "origin": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0] } },
                  "film": { "width": 16, "height": 16 } },
      "emitters": [ { "type": "constant", "radiance": [0.25, 0.5, 1.0] },
                    { "type": "directional", "direction": [0, 0, -1], "irradiance": 2 } ],
      "shapes": [ { "type": "sphere", "radius": 0.5 } ]
    })";
    ppm_scene_file file = nullptr;
    assert_ppm_ok(load_text(f->context, json, "lights.json", folder, &file));
    Picture p = render_file(file, 1);
    assert_close(p.mean(0, 0, 1, 1, 0), 0.25, 1e-6);
    assert_close(p.mean(0, 0, 1, 1, 2), 1.0, 1e-6);
    ppm_scene_file_release(file);
    // XML: an envmap by a relative file name, scaled; a directional light by to_world.
    const std::string xml = R"(<scene version="3.0.0">
      <sensor type="perspective"><float name="fov" value="30"/>
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
      </sensor>
      <emitter type="envmap"><string name="filename" value="sky.exr"/><float name="scale" value="3"/>
        <transform name="to_world"><rotate y="1" angle="90"/></transform></emitter>
      <emitter type="directional"><transform name="to_world"><lookat origin="0, 0, 0" target="0, -1, 0" up="0, 0, 1"/></transform>
        <rgb name="irradiance" value="1, 1, 1"/></emitter>
      <shape type="sphere"><float name="radius" value="0.5"/></shape>
    </scene>)";
    assert_ppm_ok(load_text(f->context, xml, "lights.xml", folder, &file));
    p = render_file(file, 1);
    assert_close(p.mean(0, 0, 1, 1, 1), 1.5, 1e-5);
    ppm_scene_file_release(file);
    // Errors name the parameter or the file.
    const auto fails = [&](const std::string &emitter, ppm_status status, const char *needle) {
        const std::string text = R"({ "emitters": [ )" + emitter + R"( ], "shapes": [ { "type": "sphere" } ] })";
        ppm_scene_file bad = nullptr;
        assert_ppm_error(load_text(f->context, text, "bad.json", folder, &bad), status, needle);
        assert_null(bad);
    };
    fails(R"({ "type": "envmap", "filename": "nowhere.exr" })", PPM_ERROR_IO, "nowhere.exr");
    fails(R"({ "type": "envmap", "filename": "sky.exr", "scale": 0 })", PPM_ERROR_PARSE, "scale");
    fails(R"({ "type": "envmap" })", PPM_ERROR_PARSE, "filename");
    fails(R"({ "type": "constant", "radiance": -1 })", PPM_ERROR_PARSE, "radiance");
    fails(R"({ "type": "directional", "radiance": 1 })", PPM_ERROR_PARSE, "radiance");
    fails(R"({ "type": "directional", "direction": [0, 0, 0] })", PPM_ERROR_PARSE, "direction");
    std::remove((std::string(folder) + "/sky.exr").c_str());
    test_remove_folder(folder);
}

} // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(envmap_sampling_matches_its_pdf),
        cmocka_unit_test(envmap_pdf_integrates_to_one),
        cmocka_unit_test(envmap_orientation_follows_mitsuba),
        cmocka_unit_test(lights_at_infinity_have_the_expected_power),
        cmocka_unit_test(bad_input_is_refused),
        cmocka_unit_test_setup_teardown(sphere_constant_sppm, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(sphere_constant_sppm_photons_only, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(sphere_constant_ppm, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(sphere_constant_pppm_photons_only, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(sphere_uniform_envmap, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(sphere_uniform_envmap_photons_only, scene_fixture_setup,
                                        scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(sphere_constant_vcm, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(sphere_uniform_envmap_vcm, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(plane_directional_vcm, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(plane_directional, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(plane_directional_photons_only, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(scene_files_load_the_types, scene_fixture_setup, scene_fixture_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
