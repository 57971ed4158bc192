// SPDX-License-Identifier: Apache-2.0
#include "checkpoint_scene.h"

#include <cstdio>

namespace fuzz {

namespace {

bool ok(ppm_status status, const char *call) {
    if (status == PPM_OK) return true;
    std::fprintf(stderr, "%s: %s\n", call, ppm_last_error_message());
    return false;
}

} // namespace

ppm_renderer create_checkpoint_renderer(ppm_context context, const char *mode) {
    ppm_scene scene = nullptr;
    if (!ok(ppm_scene_create(context, &scene), "ppm_scene_create")) return nullptr;
    const double floor_origin[3] = {-2, 0, -2}, edge_u[3] = {0, 0, 4}, edge_v[3] = {4, 0, 0};
    const double center[3] = {0, 0.5, 0}, light[3] = {0, 2, 1}, intensity[3] = {5, 5, 5};
    const double grey[3] = {0.6, 0.6, 0.6}, silver[3] = {0.9, 0.9, 0.9};
    uint32_t floor_id = 0, sphere_id = 0, diffuse = 0, mirror = 0;
    ppm_renderer renderer = nullptr;
    if (ok(ppm_scene_add_quad(scene, floor_origin, edge_u, edge_v, &floor_id), "add_quad") &&
        ok(ppm_scene_add_sphere(scene, center, 0.5, &sphere_id), "add_sphere") &&
        ok(ppm_scene_add_diffuse_material(scene, grey, &diffuse), "add_diffuse_material") &&
        ok(ppm_scene_add_mirror_material(scene, silver, &mirror), "add_mirror_material") &&
        ok(ppm_scene_set_geometry_material(scene, floor_id, diffuse), "set_geometry_material") &&
        ok(ppm_scene_set_geometry_material(scene, sphere_id, mirror), "set_geometry_material") &&
        ok(ppm_scene_add_point_light(scene, light, intensity, nullptr), "add_point_light") &&
        ok(ppm_scene_commit(scene), "commit")) {
        ppm_camera camera{};
        camera.origin[1] = 1, camera.origin[2] = 3;
        camera.target[1] = 0.5;
        camera.up[1] = 1;
        camera.fov = 50;
        camera.width = camera.height = 4;
        if (ok(ppm_renderer_create(scene, &camera, &renderer), "ppm_renderer_create") &&
            !(ok(ppm_renderer_set_string(renderer, "mode", mode), "set mode") &&
              ok(ppm_renderer_set_int(renderer, "seed", 1), "set seed") &&
              ok(ppm_renderer_set_int(renderer, "photons_per_pass", 64), "set photons_per_pass") &&
              ok(ppm_renderer_set_int(renderer, "max_depth", 4), "set max_depth"))) {
            ppm_renderer_release(renderer);
            renderer = nullptr;
        }
    }
    ppm_scene_release(scene);
    return renderer;
}

} // namespace fuzz
