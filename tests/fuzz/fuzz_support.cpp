// SPDX-License-Identifier: Apache-2.0
#include "fuzz_support.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <vector>

#include <ftw.h>
#include <unistd.h>

namespace fuzz {

namespace {

std::string temp_dir;

int remove_entry(const char *path, const struct stat *, int, struct FTW *) { return std::remove(path); }

void remove_temp_dir() {
    if (!temp_dir.empty()) nftw(temp_dir.c_str(), remove_entry, 8, FTW_DEPTH | FTW_PHYS);
}

const std::string &ensure_temp_dir() {
    if (temp_dir.empty()) {
        const char *base = std::getenv("TMPDIR");
        std::string pattern = std::string(base && *base ? base : "/tmp") + "/ppm-fuzz.XXXXXX";
        std::vector<char> buffer(pattern.begin(), pattern.end());
        buffer.push_back('\0');
        if (!mkdtemp(buffer.data())) die("cannot create a temporary folder from " + pattern);
        temp_dir = buffer.data();
        std::atexit(remove_temp_dir);
    }
    return temp_dir;
}

void check(ppm_status status, const char *call) {
    if (status != PPM_OK) die(std::string(call) + " failed with " + ppm_status_string(status));
}

bool all_finite(const double *v, int n) {
    for (int i = 0; i < n; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}

} // namespace

void die(const std::string &what) {
    std::fprintf(stderr, "fuzz target: %s\n  last error: %s\n", what.c_str(), ppm_last_error_message());
    std::fflush(stderr);
    remove_temp_dir();
    std::abort();
}

ppm_context context() {
    static ppm_context ctx = [] {
        ppm_context created = nullptr;
        check(ppm_context_create(&created), "ppm_context_create");
        check(ppm_context_set_int(created, "threads", 1), "ppm_context_set_int(threads)");
        return created;
    }();
    return ctx;
}

std::string write_temp_file(const std::string &name, const uint8_t *data, size_t size) {
    const std::string path = ensure_temp_dir() + "/" + name;
    FILE *file = std::fopen(path.c_str(), "wb");
    if (!file) die("cannot write " + path);
    if (size > 0 && std::fwrite(data, 1, size, file) != size) die("cannot write " + path);
    if (std::fclose(file) != 0) die("cannot write " + path);
    return path;
}

void limit_renderer(ppm_renderer renderer) {
    int64_t photons = 0, depth = 0;
    check(ppm_renderer_get_int(renderer, "photons_per_pass", &photons), "get photons_per_pass");
    check(ppm_renderer_get_int(renderer, "max_depth", &depth), "get max_depth");
    if (photons > kPhotonsPerPass)
        check(ppm_renderer_set_int(renderer, "photons_per_pass", kPhotonsPerPass), "set photons_per_pass");
    if (depth > kMaxDepth) check(ppm_renderer_set_int(renderer, "max_depth", kMaxDepth), "set max_depth");
}

void render_one_pass(ppm_renderer renderer) {
    int64_t before = 0, after = 0, emitted = 0, width = 0, height = 0;
    check(ppm_renderer_get_int(renderer, "passes", &before), "get passes");
    check(ppm_renderer_get_int(renderer, "photons_emitted", &emitted), "get photons_emitted");
    if (before < 0 || emitted < 0)
        die("the renderer reports " + std::to_string(before) + " passes and " + std::to_string(emitted) + " photons");
    check(ppm_render_pass(renderer), "ppm_render_pass on a scene that loaded");
    check(ppm_renderer_get_int(renderer, "passes", &after), "get passes");
    if (after != before + 1) die("the pass count went from " + std::to_string(before) + " to " + std::to_string(after));
    check(ppm_renderer_get_int(renderer, "width", &width), "get width");
    check(ppm_renderer_get_int(renderer, "height", &height), "get height");
    for (const auto &[layer, channels] : {std::pair<const char *, int>{"radiance", 3}, {"radius", 1}, {"photons", 1}}) {
        std::vector<float> values(static_cast<size_t>(width * height * channels));
        check(ppm_renderer_get_layer(renderer, layer, values.data(), values.size()), "ppm_renderer_get_layer");
        for (size_t i = 0; i < values.size(); ++i)
            if (!std::isfinite(values[i]) || values[i] < 0)
                die(std::string("layer ") + layer + ": pixel " + std::to_string(i / channels) + " channel " +
                    std::to_string(i % channels) + " is " + std::to_string(values[i]));
    }
}

void check_geometry_scene(ppm_scene scene) {
    double lower[3], upper[3];
    check(ppm_scene_get_bounds(scene, lower, upper), "ppm_scene_get_bounds");
    if (!all_finite(lower, 3) || !all_finite(upper, 3)) die("a committed scene has non-finite bounds");
    double center[3], extent = 0;
    for (int k = 0; k < 3; ++k) {
        center[k] = lower[k] / 2 + upper[k] / 2;
        extent = std::fmax(extent, upper[k] - lower[k]);
    }
    const double distance = 2 * extent + 1;
    const double view[3] = {0.36, 0.48, 0.8};
    ppm_camera camera{};
    for (int k = 0; k < 3; ++k) {
        camera.origin[k] = center[k] + distance * view[k];
        camera.target[k] = center[k];
        camera.up[k] = k == 1;
    }
    camera.fov = 60;
    camera.width = camera.height = kFilmSize;

    // Rays from the camera position through the box: hits must be finite and in range.
    // Bright enough to light the scene at its size, within the limit of light values.
    const double intensity = std::fmin(distance * distance, 1e18);
    if (!all_finite(camera.origin, 3) || !std::isfinite(intensity)) return;
    std::vector<ppm_ray> rays(16);
    for (size_t i = 0; i < rays.size(); ++i) {
        ppm_ray &ray = rays[i];
        for (int k = 0; k < 3; ++k) {
            ray.org[k] = camera.origin[k];
            const double jitter = (static_cast<double>((i >> k) & 1) - 0.5) * 0.2 * (i != 0);
            ray.dir[k] = -view[k] + jitter;
        }
        ray.tnear = 0;
        ray.tfar = INFINITY;
    }
    std::vector<ppm_hit> hits(rays.size());
    check(ppm_scene_intersect(scene, rays.data(), rays.size(), hits.data()), "ppm_scene_intersect");
    for (const ppm_hit &hit : hits)
        if (hit.geom_id != PPM_INVALID_ID &&
            (!std::isfinite(hit.t) || !all_finite(hit.p, 3) || !all_finite(hit.ng, 3) || !all_finite(hit.ns, 3) ||
             !std::isfinite(hit.u) || !std::isfinite(hit.v)))
            die("a hit has a NaN or infinite field");

    const double light_intensity[3] = {intensity, intensity, intensity};
    check(ppm_scene_add_point_light(scene, camera.origin, light_intensity, nullptr), "ppm_scene_add_point_light");
    ppm_renderer renderer = nullptr;
    check(ppm_renderer_create(scene, &camera, &renderer), "ppm_renderer_create");
    limit_renderer(renderer);
    render_one_pass(renderer);
    ppm_renderer_release(renderer);
}

} // namespace fuzz

namespace fuzz {

void expect_located_error(ppm_status status, std::initializer_list<ppm_status> allowed, const std::string &file_name,
                          const char *call) {
    static const bool verbose = std::getenv("PPM_FUZZ_VERBOSE") != nullptr;
    if (verbose) std::fprintf(stderr, "%s: %s: %s\n", call, ppm_status_string(status), ppm_last_error_message());
    bool listed = false;
    for (ppm_status s : allowed) listed = listed || s == status;
    if (!listed)
        die(std::string(call) + " returned " + ppm_status_string(status) + ", which its documentation does not list");
    if (std::strstr(ppm_last_error_message(), file_name.c_str()) == nullptr)
        die(std::string(call) + " failed with a message that does not name the file " + file_name);
}

} // namespace fuzz
