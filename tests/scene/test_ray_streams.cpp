// SPDX-License-Identifier: Apache-2.0
// Scene::intersect_stream (a camera's rays traced by Embree as one coherent stream) must give
// exactly what one Scene::intersect per ray gives: the callbacks of every kind (patches,
// quads, spheres inside the BVH, triangle meshes through their filter) find each ray's query
// by its Embree ray id, in Embree's packets. Checked bit for bit on a scene of every kind,
// with streams of 1 to max_stream rays, rays that miss the scene's box among them, and on a
// scene of spheres only (no BVH: the spheres are tested outside Embree). The one allowed
// difference: a ray through a seam of two patches may be given to either.
#include "api/api_support.h"

#include <ppm/ppm.h>

#include "test_support.h"

#include <cmath>
#include <cstring>
#include <vector>

using namespace ppm;

namespace {

struct OwnedScene {
    ppm_context context = nullptr;
    ppm_scene scene = nullptr;
    OwnedScene() {
        assert_int_equal(ppm_context_create(&context), PPM_OK);
        assert_int_equal(ppm_scene_create(context, &scene), PPM_OK);
    }
    ~OwnedScene() {
        ppm_scene_release(scene);
        ppm_context_release(context);
    }
    const Scene &internal() const { return *scene; }
};

bool identical(const ppm_hit &a, const ppm_hit &b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The same t and point, on two primitives of one geometry.
bool same_root_on_a_seam(const ppm_hit &a, const ppm_hit &b) {
    if (a.geom_id != b.geom_id || a.prim_id == b.prim_id || std::memcmp(&a.t, &b.t, sizeof a.t) != 0) return false;
    for (int k = 0; k < 3; ++k)
        if (!(std::fabs(a.p[k] - b.p[k]) <= 1e-12 * 16)) return false; // the scene is ~16 across
    return true;
}

// Camera-like rays from one point through a grid of directions (coherent, as the renderer
// sends them), every seventh one pointing away from the scene's box.
std::vector<ppm_ray> camera_rays(const double eye[3], int count) {
    std::vector<ppm_ray> rays;
    for (int k = 0; k < count; ++k) {
        ppm_ray r;
        for (int a = 0; a < 3; ++a) r.org[a] = eye[a];
        const double x = -0.6 + 1.2 * ((k * 37) % 61) / 60.0, y = -0.5 + 1.0 * ((k * 11) % 47) / 46.0;
        const bool away = k % 7 == 3;
        r.dir[0] = away ? 0.1 : x;
        r.dir[1] = away ? -1.0 : 1.0;
        r.dir[2] = away ? 0.2 : y;
        r.tnear = 0;
        r.tfar = INFINITY;
        rays.push_back(r);
    }
    return rays;
}

// hits_per_geometry[g] counts the hits on geometry g (the vector is grown as needed).
void check_streams_match_single_rays(const Scene &scene, const std::vector<ppm_ray> &rays,
                                     std::vector<int> &hits_per_geometry, int *ties) {
    for (size_t count : {size_t(1), size_t(5), size_t(17), Scene::max_stream}) {
        for (size_t start = 0; start + count <= rays.size(); start += count) {
            ppm_hit streamed[Scene::max_stream];
            scene.intersect_stream(&rays[start], nullptr, count, streamed);
            for (size_t i = 0; i < count; ++i) {
                ppm_hit single;
                scene.intersect(rays[start + i], single);
                if (!identical(single, streamed[i])) {
                    // A ray through a seam: the same root, found on one patch or its neighbour
                    // depending on which Embree handed over first.
                    assert_true(same_root_on_a_seam(single, streamed[i]));
                    ++*ties;
                }
                if (single.geom_id == PPM_INVALID_ID) continue;
                if (hits_per_geometry.size() <= single.geom_id) hits_per_geometry.resize(single.geom_id + 1);
                ++hits_per_geometry[single.geom_id];
            }
        }
    }
}

void stream_matches_single_rays_on_every_kind(void **) {
    OwnedScene s;
    uint32_t id;
    // A room of quads, the teapot, a sphere inside the BVH (the room's few spheres would all be
    // kept out of it, so there are more than the direct set holds), a two-triangle mesh.
    const double floor_o[3] = {-5, -5, 0}, x10[3] = {10, 0, 0}, y10[3] = {0, 10, 0}, z10[3] = {0, 0, 10};
    assert_int_equal(ppm_scene_add_quad(s.scene, floor_o, x10, y10, &id), PPM_OK);
    const double back_o[3] = {-5, 5, 0};
    assert_int_equal(ppm_scene_add_quad(s.scene, back_o, z10, x10, &id), PPM_OK);
    assert_int_equal(ppm_scene_load_bpt(s.scene, PPM_TEAPOT, &id), PPM_OK);
    for (int k = 0; k < 20; ++k) {
        const double centre[3] = {-4.0 + 0.4 * k, 3.0, 1.0 + 0.3 * (k % 5)};
        assert_int_equal(ppm_scene_add_sphere(s.scene, centre, 0.45, &id), PPM_OK);
    }
    const double positions[12] = {-4, 2, 5, -1, 2, 5, -1, 2, 8, -4, 2, 8};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    assert_int_equal(ppm_scene_add_triangle_mesh(s.scene, positions, 4, indices, 2, nullptr, nullptr, &id), PPM_OK);
    assert_int_equal(ppm_scene_commit(s.scene), PPM_OK);
    const double eye[3] = {0, -12, 3.5};
    std::vector<int> hits;
    int ties = 0;
    check_streams_match_single_rays(s.internal(), camera_rays(eye, 6 * int(Scene::max_stream) + 9), hits, &ties);
    assert_true(hits.size() == 24); // every kind is hit: quads 0, 1, teapot 2, spheres 3-22, mesh 23
    assert_true(hits[0] > 0 && hits[1] > 0 && hits[2] > 0 && hits[23] > 0);
    int sphere_hits = 0, all = 0;
    for (int g = 0; g < 24; ++g) {
        all += hits[g];
        sphere_hits += g >= 3 && g <= 22 ? hits[g] : 0;
    }
    assert_true(sphere_hits > 0);
    assert_true(ties * 50 < all);
}

void stream_matches_single_rays_without_a_bvh(void **) {
    OwnedScene s;
    uint32_t id;
    for (int k = 0; k < 6; ++k) {
        const double centre[3] = {-3.0 + 1.2 * k, 4.0, 1.0 + 0.5 * k};
        assert_int_equal(ppm_scene_add_sphere(s.scene, centre, 0.9, &id), PPM_OK);
    }
    assert_int_equal(ppm_scene_commit(s.scene), PPM_OK);
    const double eye[3] = {0, -6, 2.5};
    std::vector<int> hits;
    int ties = 0;
    check_streams_match_single_rays(s.internal(), camera_rays(eye, int(Scene::max_stream) + 3), hits, &ties);
    assert_false(hits.empty());
    assert_int_equal(ties, 0);
}

} // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(stream_matches_single_rays_on_every_kind),
        cmocka_unit_test(stream_matches_single_rays_without_a_bvh),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
