// SPDX-License-Identifier: Apache-2.0
// Threads through the public C API; ctest label "threads", which scripts/tsan.sh runs under
// ThreadSanitizer. Every check compares with a single-threaded run, bit for bit:
//  - passes on several worker threads give the image of one worker thread (SPPM and PPM), and
//    two renderers of one scene rendering at once from two application threads each give it;
//  - many application threads querying one committed scene at once (intersect and occluded,
//    in batches run on the calling thread and on the context's workers, and the getters) get
//    the single-threaded answers; scenes of one context built on several threads at once too;
//  - cancel during a pass (SPPM and PPM, the first pass and a later one): the pass returns
//    CANCELLED, the image and counters are those of the last completed pass, and the next
//    passes give the images of a render that was never cancelled;
//  - get_layer, save_checkpoint and the counters (passes, photons, pass times) on other
//    threads during passes: they always see the state after a completed pass, and a
//    checkpoint saved during a pass resumes bit-exactly.
// Worker threads only record what they saw; the assertions run on the test's own thread.
// The standard headers come first: cmocka defines macros (fail, ...) that clash with them.
#include <atomic>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <ppm/ppm.h>

#include "api_asserts.h"
#include "test_support.h"

namespace {

using Image = std::vector<float>;

constexpr int kWidth = 24, kHeight = 18;
constexpr int64_t kPhotons = 3000;
// A pass of this many photons does not end within any test's lifetime unless cancelled.
constexpr int64_t kEndlessPhotons = int64_t(1) << 31;
constexpr int kPasses = 3;

// An open box of diffuse walls with a mirror sphere, a glass sphere, a coated triangle pair,
// a point light and an area light: camera paths split at glass and coats in PPM mode.
void build_room(ppm_scene scene) {
    const double grey[3] = {0.6, 0.6, 0.6}, white[3] = {0.9, 0.9, 0.9}, base[3] = {0.2, 0.5, 0.3};
    uint32_t wall = 0, mirror = 0, glass = 0, coated = 0;
    assert_ppm_ok(ppm_scene_add_diffuse_material(scene, grey, &wall));
    assert_ppm_ok(ppm_scene_add_mirror_material(scene, white, &mirror));
    assert_ppm_ok(ppm_scene_add_dielectric_material(scene, 1.5, 1.0, &glass));
    assert_ppm_ok(ppm_scene_add_coated_material(scene, base, 1.5, 1.0, &coated));
    const double quads[5][9] = {
        {-1, -1, -1, 2, 0, 0, 0, 0, 2}, // floor
        {-1, 1, -1, 2, 0, 0, 0, 0, 2},  // ceiling
        {-1, -1, -1, 2, 0, 0, 0, 2, 0}, // back
        {-1, -1, -1, 0, 2, 0, 0, 0, 2}, // left
        {1, -1, -1, 0, 2, 0, 0, 0, 2},  // right
    };
    for (const auto &q : quads) assert_ppm_ok(ppm_scene_add_quad(scene, q, q + 3, q + 6, nullptr));
    // Under the ceiling, emitting downwards (edge_u x edge_v = -y).
    const double lamp[9] = {-0.3, 0.99, -0.3, 0.6, 0, 0, 0, 0, 0.6}, radiance[3] = {4, 4, 4};
    uint32_t id = 0;
    assert_ppm_ok(ppm_scene_add_quad(scene, lamp, lamp + 3, lamp + 6, &id));
    assert_ppm_ok(ppm_scene_set_geometry_emission(scene, id, radiance));
    const double mirror_center[3] = {-0.5, -0.6, -0.3}, glass_center[3] = {0.45, -0.6, 0.2};
    assert_ppm_ok(ppm_scene_add_sphere(scene, mirror_center, 0.35, &id));
    assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, mirror));
    assert_ppm_ok(ppm_scene_add_sphere(scene, glass_center, 0.35, &id));
    assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, glass));
    const double positions[12] = {0.2, 0.1, -0.9, 0.8, 0.1, -0.9, 0.8, 0.7, -0.6, 0.2, 0.7, -0.6};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    assert_ppm_ok(ppm_scene_add_triangle_mesh(scene, positions, 4, indices, 2, nullptr, nullptr, &id));
    assert_ppm_ok(ppm_scene_set_geometry_material(scene, id, coated));
    const double light_position[3] = {0, 0.6, 0.4}, intensity[3] = {1, 1, 1};
    assert_ppm_ok(ppm_scene_add_point_light(scene, light_position, intensity, nullptr));
    assert_ppm_ok(ppm_scene_commit(scene));
}

ppm_renderer make_renderer(ppm_scene scene, const char *mode) {
    ppm_camera camera;
    std::memset(&camera, 0, sizeof camera);
    camera.origin[2] = 3.2;
    camera.up[1] = 1;
    camera.fov = 40;
    camera.width = kWidth;
    camera.height = kHeight;
    ppm_renderer r = nullptr;
    assert_ppm_ok(ppm_renderer_create(scene, &camera, &r));
    assert_ppm_ok(ppm_renderer_set_string(r, "mode", mode));
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", kPhotons));
    assert_ppm_ok(ppm_renderer_set_int(r, "seed", 11));
    return r;
}

// Callable from any thread (no assertion): false if get_layer failed.
bool read_image(ppm_renderer r, Image &out) {
    out.assign(size_t(3) * kWidth * kHeight, -1.0f);
    return ppm_renderer_get_layer(r, "radiance", out.data(), out.size()) == PPM_OK;
}

Image image_of(ppm_renderer r) {
    Image image;
    assert_true(read_image(r, image));
    return image;
}

int64_t int_of(ppm_renderer r, const char *key) {
    int64_t value = -1;
    assert_ppm_ok(ppm_renderer_get_int(r, key, &value));
    return value;
}

std::string file_bytes(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The images after 0, 1, ..., kPasses + 2 passes of a renderer that runs on one worker thread
// and is never disturbed.
std::vector<Image> reference_images(ppm_context context, ppm_scene scene, const char *mode) {
    assert_ppm_ok(ppm_context_set_int(context, "threads", 1));
    ppm_renderer r = make_renderer(scene, mode);
    std::vector<Image> images{image_of(r)};
    for (int pass = 1; pass <= kPasses + 2; ++pass) {
        assert_ppm_ok(ppm_render_pass(r));
        images.push_back(image_of(r));
    }
    ppm_renderer_release(r);
    assert_ppm_ok(ppm_context_set_int(context, "threads", 0));
    return images;
}

struct Fixture {
    ppm_context context = nullptr;
    ppm_scene scene = nullptr;
    std::vector<Image> sppm, ppm; // reference_images of each mode
    char folder[512] = {0};

    const std::vector<Image> &reference(const std::string &mode) const { return mode == "ppm" ? ppm : sppm; }
    std::string path(const char *name) const { return std::string(folder) + "/" + name; }
};

int setup(void **state) {
    auto *f = new Fixture;
    *state = f;
    if (ppm_context_create(&f->context) != PPM_OK || ppm_scene_create(f->context, &f->scene) != PPM_OK) return -1;
    if (test_make_folder(f->folder, sizeof f->folder, "ppm-threads-") != 0) return -1;
    build_room(f->scene);
    f->sppm = reference_images(f->context, f->scene, "sppm");
    f->ppm = reference_images(f->context, f->scene, "ppm");
    // The room is lit: a render that lost its photons or its direct light would not match.
    double sum = 0;
    for (float v : f->sppm[kPasses]) sum += v;
    return sum > 0 && f->sppm[1] != f->sppm[2] && f->ppm[1] != f->ppm[2] ? 0 : -1;
}

int teardown(void **state) {
    auto *f = static_cast<Fixture *>(*state);
    ppm_scene_release(f->scene);
    ppm_context_release(f->context);
    if (f->folder[0]) test_remove_folder(f->folder);
    delete f;
    return 0;
}

// ----------------------------------------------------------------------------------------------
// Rendering on several threads

void passes_on_worker_threads_match_one_thread(void **state) {
    auto *f = static_cast<Fixture *>(*state);
    // More workers than cores: the pass's tasks interleave on every run.
    assert_ppm_ok(ppm_context_set_int(f->context, "threads", 4));
    for (const char *mode : {"sppm", "ppm"}) {
        ppm_renderer r = make_renderer(f->scene, mode);
        for (int pass = 1; pass <= kPasses; ++pass) {
            assert_ppm_ok(ppm_render_pass(r));
            assert_true(image_of(r) == f->reference(mode)[pass]);
        }
        ppm_renderer_release(r);
    }
    assert_ppm_ok(ppm_context_set_int(f->context, "threads", 0));
}

void renderers_of_one_scene_render_at_once(void **state) {
    auto *f = static_cast<Fixture *>(*state);
    const char *modes[2] = {"sppm", "ppm"};
    ppm_renderer renderers[2] = {make_renderer(f->scene, modes[0]), make_renderer(f->scene, modes[1])};
    std::vector<Image> images[2];
    ppm_status failed[2] = {PPM_OK, PPM_OK};
    std::vector<std::thread> threads;
    for (int k = 0; k < 2; ++k)
        threads.emplace_back([&, k] {
            for (int pass = 1; pass <= kPasses && failed[k] == PPM_OK; ++pass) {
                failed[k] = ppm_render_pass(renderers[k]);
                Image image;
                if (!read_image(renderers[k], image)) failed[k] = PPM_ERROR_INTERNAL;
                images[k].push_back(image);
            }
        });
    for (std::thread &t : threads) t.join();
    for (int k = 0; k < 2; ++k) {
        assert_int_equal(failed[k], PPM_OK);
        for (int pass = 1; pass <= kPasses; ++pass) assert_true(images[k][pass - 1] == f->reference(modes[k])[pass]);
        ppm_renderer_release(renderers[k]);
    }
}

// ----------------------------------------------------------------------------------------------
// Cancel and checkpoints during a pass

// Whether a pass of `r` is running. load_checkpoint takes the renderer's pass lock without
// waiting and refuses with "a pass of this renderer is running" while a pass holds it;
// otherwise it fails on the missing file (before the first pass) or because passes have run,
// and changes nothing.
bool pass_running(ppm_renderer r, const std::string &missing_file) {
    return ppm_renderer_load_checkpoint(r, missing_file.c_str()) == PPM_ERROR_INVALID_OPERATION &&
           std::strstr(ppm_last_error_message(), "is running");
}

// ppm_render_pass, tried again while a pass_running() probe holds the pass lock for a moment.
ppm_status render_pass_beside_probe(ppm_renderer r, std::string &message) {
    for (;;) {
        const ppm_status status = ppm_render_pass(r);
        message = ppm_last_error_message();
        if (status != PPM_ERROR_INVALID_OPERATION || message.find("another pass") == std::string::npos) return status;
        std::this_thread::yield();
    }
}

// A pass that only ends when cancelled runs on its own thread; `during` runs on the test's
// thread once the pass is known to be running, then the pass is cancelled. Returns the pass's
// status and message.
template <class During>
ppm_status cancelled_pass(ppm_renderer r, const Fixture &f, std::string &message, During &&during) {
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", kEndlessPhotons));
    std::atomic<bool> returned{false};
    ppm_status status = PPM_OK;
    std::thread pass([&] {
        status = render_pass_beside_probe(r, message);
        returned = true;
    });
    const std::string missing = f.path("missing.ckpt");
    while (!returned && !pass_running(r, missing)) std::this_thread::yield();
    if (!returned) during();
    assert_ppm_ok(ppm_renderer_cancel(r));
    pass.join();
    assert_ppm_ok(ppm_renderer_set_int(r, "photons_per_pass", kPhotons));
    return status;
}

void cancel_during_pass(Fixture *f, const char *mode, int completed_passes) {
    const std::vector<Image> &reference = f->reference(mode);
    ppm_renderer r = make_renderer(f->scene, mode);
    for (int pass = 0; pass < completed_passes; ++pass) assert_ppm_ok(ppm_render_pass(r));
    Image during_image;
    bool read_during = false;
    std::string message;
    const ppm_status status = cancelled_pass(r, *f, message, [&] { read_during = read_image(r, during_image); });
    if (status != PPM_ERROR_CANCELLED)
        fail_msg("%s pass %d returned %s (%s), expected cancelled", mode, completed_passes + 1,
                 ppm_status_string(status), message.c_str());
    assert_non_null(std::strstr(message.c_str(), "cancelled"));
    // The cancelled pass left nothing: the image and counters of the last completed pass.
    assert_true(read_during);
    assert_true(during_image == reference[completed_passes]);
    assert_true(image_of(r) == reference[completed_passes]);
    assert_int_equal(int_of(r, "passes"), completed_passes);
    assert_int_equal(int_of(r, "photons_emitted"), completed_passes * kPhotons);
    // ... and the render goes on as if it had never been cancelled.
    for (int pass = completed_passes + 1; pass <= completed_passes + 2; ++pass) {
        assert_ppm_ok(ppm_render_pass(r));
        assert_true(image_of(r) == reference[pass]);
    }
    ppm_renderer_release(r);
}

void cancel_during_first_sppm_pass(void **state) { cancel_during_pass(static_cast<Fixture *>(*state), "sppm", 0); }
void cancel_during_later_sppm_pass(void **state) { cancel_during_pass(static_cast<Fixture *>(*state), "sppm", 2); }
// PPM's first pass fixes the hit points; cancelled, it must fix them again next time.
void cancel_during_first_ppm_pass(void **state) { cancel_during_pass(static_cast<Fixture *>(*state), "ppm", 0); }
void cancel_during_later_ppm_pass(void **state) { cancel_during_pass(static_cast<Fixture *>(*state), "ppm", 2); }

void checkpoint_saved_during_pass_is_the_last_completed_one(void **state) {
    auto *f = static_cast<Fixture *>(*state);
    for (const char *mode : {"sppm", "ppm"}) {
        ppm_renderer r = make_renderer(f->scene, mode);
        assert_ppm_ok(ppm_render_pass(r));
        const std::string before = f->path("before.ckpt"), during = f->path("during.ckpt");
        assert_ppm_ok(ppm_renderer_save_checkpoint(r, before.c_str()));
        ppm_status saved = PPM_ERROR_INTERNAL;
        std::string message;
        const ppm_status status =
            cancelled_pass(r, *f, message, [&] { saved = ppm_renderer_save_checkpoint(r, during.c_str()); });
        assert_int_equal(status, PPM_ERROR_CANCELLED);
        assert_int_equal(saved, PPM_OK);
        const std::string bytes = file_bytes(during);
        assert_true(bytes.size() > 0);
        assert_true(bytes == file_bytes(before));
        ppm_renderer_release(r);

        // Resumed from it, a render continues bit for bit.
        ppm_renderer resumed = make_renderer(f->scene, mode);
        assert_ppm_ok(ppm_renderer_load_checkpoint(resumed, during.c_str()));
        assert_true(image_of(resumed) == f->reference(mode)[1]);
        assert_ppm_ok(ppm_render_pass(resumed));
        assert_true(image_of(resumed) == f->reference(mode)[2]);
        ppm_renderer_release(resumed);
    }
}

// A reader and a checkpoint writer loop on their own threads through a whole render, from
// before its first pass (when the pixel slots are made) to after its last.
void readers_during_passes_see_completed_passes(void **state) {
    auto *f = static_cast<Fixture *>(*state);
    for (const char *mode : {"sppm", "ppm"}) {
        const std::vector<Image> &reference = f->reference(mode);
        ppm_renderer r = make_renderer(f->scene, mode);
        std::vector<std::string> boundaries; // the checkpoint after 1, 2, ... passes
        std::atomic<bool> done{false};
        std::atomic<int> reads{0}, unexpected_images{0}, failed_reads{0}, unexpected_counters{0};
        std::thread reader([&] {
            Image image;
            do {
                // The counters a progress display shows: each within what the render reaches.
                int64_t passes = -1, emitted = -1;
                double seconds[3] = {-1, -1, -1};
                if (!read_image(r, image) || ppm_renderer_get_int(r, "passes", &passes) != PPM_OK ||
                    ppm_renderer_get_int(r, "photons_emitted", &emitted) != PPM_OK ||
                    ppm_renderer_get_double(r, "last_eye_pass_seconds", &seconds[0]) != PPM_OK ||
                    ppm_renderer_get_double(r, "last_photon_pass_seconds", &seconds[1]) != PPM_OK ||
                    ppm_renderer_get_double(r, "last_search_build_seconds", &seconds[2]) != PPM_OK) {
                    ++failed_reads;
                    continue;
                }
                if (passes < 0 || passes > kPasses || emitted < 0 || emitted > kPasses * kPhotons ||
                    emitted % kPhotons != 0)
                    ++unexpected_counters;
                for (double s : seconds)
                    if (!(s >= 0 && s < 1e6)) ++unexpected_counters;
                bool known = false;
                for (const Image &expected : reference) known = known || image == expected;
                if (!known) ++unexpected_images;
                ++reads;
            } while (!done);
        });
        std::set<std::string> saved;
        std::atomic<int> failed_saves{0};
        const std::string saver_path = f->path("saver.ckpt");
        std::thread saver([&] {
            do {
                if (ppm_renderer_save_checkpoint(r, saver_path.c_str()) != PPM_OK)
                    ++failed_saves;
                else
                    saved.insert(file_bytes(saver_path));
            } while (!done);
        });
        for (int pass = 1; pass <= kPasses; ++pass) {
            assert_ppm_ok(ppm_render_pass(r));
            const std::string path = f->path("boundary.ckpt");
            assert_ppm_ok(ppm_renderer_save_checkpoint(r, path.c_str()));
            boundaries.push_back(file_bytes(path));
        }
        done = true;
        reader.join();
        saver.join();
        assert_int_equal(failed_reads.load(), 0);
        assert_int_equal(unexpected_images.load(), 0);
        assert_int_equal(unexpected_counters.load(), 0);
        assert_true(reads.load() > 0);
        assert_int_equal(failed_saves.load(), 0);
        assert_true(image_of(r) == reference[kPasses]);
        // Every checkpoint written during the render is one of a pass boundary, or the one of
        // a renderer that has not completed a pass (identity only).
        ppm_renderer fresh = make_renderer(f->scene, mode);
        const std::string empty_path = f->path("empty.ckpt");
        assert_ppm_ok(ppm_renderer_save_checkpoint(fresh, empty_path.c_str()));
        ppm_renderer_release(fresh);
        boundaries.push_back(file_bytes(empty_path));
        for (const std::string &bytes : saved) {
            bool known = false;
            for (const std::string &b : boundaries) known = known || bytes == b;
            assert_true(known);
        }
        ppm_renderer_release(r);
    }
}

// ----------------------------------------------------------------------------------------------
// Scene queries from many application threads

constexpr int kQueryThreads = 8;
constexpr size_t kRays = 1024;

// The teapot's patches, a sphere, a quad and a triangle pair.
void build_query_scene(ppm_scene scene) {
    assert_ppm_ok(ppm_scene_load_bpt(scene, PPM_TEAPOT, nullptr));
    const double center[3] = {0, 1.5, 0}, origin[3] = {-4, -0.5, -4}, eu[3] = {8, 0, 0}, ev[3] = {0, 0, 8};
    assert_ppm_ok(ppm_scene_add_sphere(scene, center, 0.7, nullptr));
    assert_ppm_ok(ppm_scene_add_quad(scene, origin, eu, ev, nullptr));
    const double positions[12] = {-3, 0, -2, 3, 0, -2, 3, 3, -2.5, -3, 3, -2.5};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    assert_ppm_ok(ppm_scene_add_triangle_mesh(scene, positions, 4, indices, 2, nullptr, nullptr, nullptr));
    assert_ppm_ok(ppm_scene_commit(scene));
}

// Rays from around the scene towards points inside its bounds; every fourth ends halfway
// there.
std::vector<ppm_ray> query_rays(ppm_scene scene) {
    double lower[3], upper[3];
    assert_ppm_ok(ppm_scene_get_bounds(scene, lower, upper));
    test_rng rng = {42};
    std::vector<ppm_ray> rays(kRays);
    for (size_t i = 0; i < kRays; ++i) {
        ppm_ray &ray = rays[i];
        double length = 0;
        for (int a = 0; a < 3; ++a) {
            const double span = upper[a] - lower[a];
            ray.org[a] = lower[a] - span + 3 * span * test_rng_uniform(&rng);
            const double target = lower[a] + span * test_rng_uniform(&rng);
            ray.dir[a] = target - ray.org[a];
            length += ray.dir[a] * ray.dir[a];
        }
        ray.tnear = 0;
        ray.tfar = i % 4 == 3 ? 0.5 : INFINITY;
        if (length == 0) ray.dir[0] = 1;
    }
    return rays;
}

struct QueryAnswers {
    std::vector<ppm_hit> hits;
    std::vector<uint8_t> occluded;
    double lower[3], upper[3];
    std::vector<double> patches;
    bool operator==(const QueryAnswers &o) const {
        return hits.size() == o.hits.size() &&
               std::memcmp(hits.data(), o.hits.data(), hits.size() * sizeof(ppm_hit)) == 0 && occluded == o.occluded &&
               std::memcmp(lower, o.lower, sizeof lower) == 0 && std::memcmp(upper, o.upper, sizeof upper) == 0 &&
               patches == o.patches;
    }
};

// Callable from any thread: the answers in batches of `batch` rays (below the library's
// threshold a batch runs on the calling thread, above it on the context's workers); false
// if a call failed.
bool query(ppm_scene scene, const std::vector<ppm_ray> &rays, size_t batch, QueryAnswers &out) {
    out.hits.assign(rays.size(), ppm_hit{});
    out.occluded.assign(rays.size(), 2);
    size_t patch_count = 0;
    bool ok = ppm_scene_get_primitive_count(scene, 0, &patch_count) == PPM_OK;
    out.patches.assign(patch_count * 48, 0.0);
    ok = ok && ppm_scene_get_bezier_patches(scene, 0, out.patches.data(), out.patches.size()) == PPM_OK;
    ok = ok && ppm_scene_get_bounds(scene, out.lower, out.upper) == PPM_OK;
    for (size_t first = 0; ok && first < rays.size(); first += batch) {
        const size_t count = std::min(batch, rays.size() - first);
        ok = ppm_scene_intersect(scene, &rays[first], count, &out.hits[first]) == PPM_OK &&
             ppm_scene_occluded(scene, &rays[first], count, &out.occluded[first]) == PPM_OK;
    }
    return ok;
}

QueryAnswers single_threaded_answers(ppm_context context, ppm_scene scene, const std::vector<ppm_ray> &rays) {
    assert_ppm_ok(ppm_context_set_int(context, "threads", 1));
    QueryAnswers answers;
    assert_true(query(scene, rays, 1, answers));
    assert_ppm_ok(ppm_context_set_int(context, "threads", 0));
    // Most rays hit something, and a ray is occluded exactly when it hits.
    size_t hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const bool hit = answers.hits[i].geom_id != PPM_INVALID_ID;
        hits += hit;
        assert_int_equal(answers.occluded[i], hit ? 1 : 0);
    }
    assert_true(hits > rays.size() / 2 && hits < rays.size());
    return answers;
}

void many_threads_query_one_scene(void **state) {
    auto *f = static_cast<scene_fixture *>(*state);
    build_query_scene(f->scene);
    const std::vector<ppm_ray> rays = query_rays(f->scene);
    const QueryAnswers expected = single_threaded_answers(f->context, f->scene, rays);
    assert_ppm_ok(ppm_context_set_int(f->context, "threads", 4));
    std::atomic<int> failed{0}, differ{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < kQueryThreads; ++t)
        threads.emplace_back([&, t] {
            // Odd threads query in batches large enough for the context's workers.
            QueryAnswers answers;
            if (!query(f->scene, rays, t % 2 ? 512 : 64, answers))
                ++failed;
            else if (!(answers == expected))
                ++differ;
        });
    for (std::thread &t : threads) t.join();
    assert_int_equal(failed.load(), 0);
    assert_int_equal(differ.load(), 0);
}

void scenes_of_one_context_built_at_once(void **state) {
    auto *f = static_cast<scene_fixture *>(*state);
    build_query_scene(f->scene);
    const std::vector<ppm_ray> rays = query_rays(f->scene);
    const QueryAnswers expected = single_threaded_answers(f->context, f->scene, rays);
    constexpr int kBuilders = 3;
    ppm_scene scenes[kBuilders] = {};
    for (ppm_scene &s : scenes) assert_ppm_ok(ppm_scene_create(f->context, &s));
    std::atomic<int> failed{0}, differ{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < kBuilders; ++t)
        threads.emplace_back([&, t] {
            // No assertion here: build_query_scene's would jump off this thread.
            ppm_scene s = scenes[t];
            const double center[3] = {0, 1.5, 0}, origin[3] = {-4, -0.5, -4}, eu[3] = {8, 0, 0}, ev[3] = {0, 0, 8};
            const double positions[12] = {-3, 0, -2, 3, 0, -2, 3, 3, -2.5, -3, 3, -2.5};
            const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
            QueryAnswers answers;
            if (ppm_scene_load_bpt(s, PPM_TEAPOT, nullptr) != PPM_OK ||
                ppm_scene_add_sphere(s, center, 0.7, nullptr) != PPM_OK ||
                ppm_scene_add_quad(s, origin, eu, ev, nullptr) != PPM_OK ||
                ppm_scene_add_triangle_mesh(s, positions, 4, indices, 2, nullptr, nullptr, nullptr) != PPM_OK ||
                ppm_scene_commit(s) != PPM_OK || !query(s, rays, 512, answers))
                ++failed;
            else if (!(answers == expected))
                ++differ;
        });
    for (std::thread &t : threads) t.join();
    for (ppm_scene s : scenes) ppm_scene_release(s);
    assert_int_equal(failed.load(), 0);
    assert_int_equal(differ.load(), 0);
}

} // namespace

int main(void) {
    const struct CMUnitTest render_tests[] = {
        cmocka_unit_test(passes_on_worker_threads_match_one_thread),
        cmocka_unit_test(renderers_of_one_scene_render_at_once),
        cmocka_unit_test(cancel_during_first_sppm_pass),
        cmocka_unit_test(cancel_during_later_sppm_pass),
        cmocka_unit_test(cancel_during_first_ppm_pass),
        cmocka_unit_test(cancel_during_later_ppm_pass),
        cmocka_unit_test(checkpoint_saved_during_pass_is_the_last_completed_one),
        cmocka_unit_test(readers_during_passes_see_completed_passes),
    };
    const struct CMUnitTest query_tests[] = {
        cmocka_unit_test_setup_teardown(many_threads_query_one_scene, scene_fixture_setup, scene_fixture_teardown),
        cmocka_unit_test_setup_teardown(scenes_of_one_context_built_at_once, scene_fixture_setup,
                                        scene_fixture_teardown),
    };
    int failed = cmocka_run_group_tests_name("rendering", render_tests, setup, teardown);
    failed += cmocka_run_group_tests_name("scene queries", query_tests, nullptr, nullptr);
    return failed;
}
