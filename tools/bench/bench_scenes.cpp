// SPDX-License-Identifier: Apache-2.0
#include "bench_scenes.h"
#include "common/status.h"

#include <cmath>
#include <stdexcept>

namespace bench {

using ppm_tools::check_with_status;

namespace {

uint32_t diffuse(ppm_scene scene, double r, double g, double b) {
    const double rgb[3] = {r, g, b};
    uint32_t id = 0;
    check_with_status(ppm_scene_add_diffuse_material(scene, rgb, &id), "ppm_scene_add_diffuse_material");
    return id;
}

void sphere(ppm_scene scene, double radius, double x, double y, double z, uint32_t material) {
    const double c[3] = {x, y, z};
    uint32_t id = 0;
    check_with_status(ppm_scene_add_sphere(scene, c, radius, &id), "ppm_scene_add_sphere");
    check_with_status(ppm_scene_set_geometry_material(scene, id, material), "ppm_scene_set_geometry_material");
}

uint32_t quad(ppm_scene scene, const double o[3], const double u[3], const double v[3], uint32_t material) {
    uint32_t id = 0;
    check_with_status(ppm_scene_add_quad(scene, o, u, v, &id), "ppm_scene_add_quad");
    check_with_status(ppm_scene_set_geometry_material(scene, id, material), "ppm_scene_set_geometry_material");
    return id;
}

void set_camera(ppm_camera &c, const double o[3], const double t[3], const double up[3], double fov, int w, int h) {
    for (int k = 0; k < 3; ++k) {
        c.origin[k] = o[k];
        c.target[k] = t[k];
        c.up[k] = up[k];
    }
    c.fov = fov;
    c.width = static_cast<uint32_t>(w);
    c.height = static_cast<uint32_t>(h);
}

// smallppm.cpp (Hachisuka 2008/2009): the scene table, camera and light as published.
void build_smallppm(ppm_scene s, ppm_camera &camera, int w, int h) {
    sphere(s, 1e5, 1e5 + 1, 40.8, 81.6, diffuse(s, .75, .25, .25));   // left
    sphere(s, 1e5, -1e5 + 99, 40.8, 81.6, diffuse(s, .25, .25, .75)); // right
    sphere(s, 1e5, 50, 40.8, 1e5, diffuse(s, .75, .75, .75));         // back
    sphere(s, 1e5, 50, 40.8, -1e5 + 170, diffuse(s, 0, 0, 0));        // front
    sphere(s, 1e5, 50, 1e5, 81.6, diffuse(s, .75, .75, .75));         // bottom
    sphere(s, 1e5, 50, -1e5 + 81.6, 81.6, diffuse(s, .75, .75, .75)); // top
    const double white[3] = {.999, .999, .999};
    uint32_t mirror = 0, glass = 0;
    check_with_status(ppm_scene_add_mirror_material(s, white, &mirror), "ppm_scene_add_mirror_material");
    check_with_status(ppm_scene_add_dielectric_material(s, 1.5, 1.0, &glass), "ppm_scene_add_dielectric_material");
    sphere(s, 16.5, 27, 16.5, 47, mirror);
    sphere(s, 16.5, 73, 16.5, 88, glass);
    sphere(s, 8.5, 50, 8.5, 60, diffuse(s, .999, .999, .999));
    // smallppm emits photons of flux 2500 * 4 pi each from a point: intensity 2500 W/sr.
    const double light[3] = {50, 60, 85}, intensity[3] = {2500, 2500, 2500};
    check_with_status(ppm_scene_add_point_light(s, light, intensity, nullptr), "ppm_scene_add_point_light");
    // Camera at (50, 48, 295.6) looking along (0, -0.042612, -1); its image plane half-width
    // is 0.5 * 0.5135 * w / h, so the horizontal fov is 2 atan(0.25675 w / h).
    const double origin[3] = {50, 48, 295.6}, target[3] = {50, 48 - 0.042612, 294.6}, up[3] = {0, 1, 0};
    set_camera(camera, origin, target, up, 2 * std::atan(0.5 * 0.5135 * w / h) * 180 / 3.14159265358979323846, w, h);
    camera.near_clip = 140; // smallppm starts its rays 140 units out, past the front wall (z = 170)
}

// z up; box [-5, 5] x [-5, 5] x [0, 10] open towards the camera at -y.
void build_teapot_glass(ppm_scene s, ppm_camera &camera, const std::string &teapot, int w, int h) {
    const uint32_t white = diffuse(s, .75, .75, .75), red = diffuse(s, .75, .2, .2), green = diffuse(s, .2, .6, .25);
    const double floor_o[3] = {-5, -5, 0}, x10[3] = {10, 0, 0}, y10[3] = {0, 10, 0}, z10[3] = {0, 0, 10};
    quad(s, floor_o, x10, y10, white); // floor
    const double ceil_o[3] = {-5, -5, 10};
    quad(s, ceil_o, y10, x10, white); // ceiling
    const double back_o[3] = {-5, 5, 0};
    quad(s, back_o, z10, x10, white); // back
    quad(s, floor_o, y10, z10, red);  // left (x = -5)
    const double right_o[3] = {5, -5, 0};
    quad(s, right_o, z10, y10, green); // right (x = 5)
    // Area light: a 3 x 3 square just under the ceiling, facing down.
    const double light_o[3] = {-1.5, -1.5, 9.99}, lx[3] = {3, 0, 0}, ly[3] = {0, 3, 0};
    const uint32_t light = quad(s, light_o, ly, lx, white);
    const double radiance[3] = {12, 12, 12};
    check_with_status(ppm_scene_set_geometry_emission(s, light, radiance), "ppm_scene_set_geometry_emission");
    uint32_t glass = 0, pot = 0;
    check_with_status(ppm_scene_add_dielectric_material(s, 1.5, 1.0, &glass), "ppm_scene_add_dielectric_material");
    check_with_status(ppm_scene_load_bpt(s, teapot.c_str(), &pot), "ppm_scene_load_bpt");
    check_with_status(ppm_scene_set_geometry_material(s, pot, glass), "ppm_scene_set_geometry_material");
    const double m[16] = {1.2, 0, 0, -0.3, 0, 1.2, 0, 0, 0, 0, 1.2, 0.001, 0, 0, 0, 1};
    check_with_status(ppm_scene_set_geometry_transform(s, pot, m), "ppm_scene_set_geometry_transform");
    const double origin[3] = {0, -19, 4.6}, target[3] = {0, 0, 3.6}, up[3] = {0, 0, 1};
    set_camera(camera, origin, target, up, 38, w, h);
}

} // namespace

BenchScene build_bench_scene(ppm_context context, const std::string &name, const std::string &teapot_path, int width,
                             int height) {
    BenchScene b;
    check_with_status(ppm_scene_create(context, b.scene.out()), "ppm_scene_create");
    if (name == "smallppm")
        build_smallppm(b.scene, b.camera, width, height);
    else if (name == "teapot-glass")
        build_teapot_glass(b.scene, b.camera, teapot_path, width, height);
    else
        throw std::runtime_error("unknown scene '" + name + "' (scenes: smallppm, teapot-glass)");
    check_with_status(ppm_scene_commit(b.scene), "ppm_scene_commit");
    return b;
}

} // namespace bench
