// SPDX-License-Identifier: Apache-2.0
// The bidirectional modes' pass (vcm_integrator.h): the light subpaths with their light
// tracing, the grid over their vertices, then the camera subpaths (vcm_camera_paths.cpp).
#include "integrator/vcm/vcm_integrator.h"

#include "core/error.h"
#include "integrator/vcm/vcm_vertex.h"
#include "scene/spawn.h"
#include "shading/shading_normals.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>

namespace ppm {

namespace {

// Light subpaths are traced in blocks of this many; each block's vertices and splats are kept
// apart and joined in block order, so the result does not depend on the threads.
constexpr std::uint32_t kLightBlock = 64;

// Light tracing: light vertex `v` seen by the (pinhole) camera, its radiance splatted to the
// pixels the pixel filter reaches from where it projects to.
void trace_to_camera(const PassInputs &in, const VcmPassState &state, const VcmLightVertex &v,
                     std::vector<std::pair<std::uint32_t, Rgb>> &splats) {
    const Camera &camera = in.camera;
    double x, y;
    if (!camera.project(v.sp.p, &x, &y) || !(x >= 0 && y >= 0 && x <= camera.width() && y <= camera.height())) return;
    const Vec3 to_camera = camera.position() - v.sp.p;
    const double d2 = length2(to_camera), d = std::sqrt(d2);
    const Vec3 dir = to_camera / d;
    const double depth = -dot(dir, camera.forward()) * d;
    const Vec3 wi = v.sp.frame.to_local(dir);
    const Rgb f = v.sp.bsdf.eval(v.sp.wo_local, wi, TransportMode::Importance);
    const double camera_pdf_w = vcm_camera_pdf_w(camera, state.pixel_area, dir * -1.0);
    if (f.is_black() || !(camera_pdf_w > 0) || depth < camera.near_clip()) return;
    const double camera_pdf_a = camera_pdf_w * std::fabs(wi.z) / d2;
    const double rev = v.sp.bsdf.pdf(wi, v.sp.wo_local) * vcm_continuation(v.sp.bsdf);
    // The camera sees from its near clip plane on (what lies before it is not seen).
    const double cos_camera = depth / d;
    const double tfar = (d - camera.near_clip() / cos_camera) * (1 - 1e-7) - 8 * v.sp.hit.p_error;
    if (!(tfar > 0) || in.scene.scene().occluded(spawn_ray(v.sp.hit, dir, tfar), RayHints{&v.sp.hit})) return;
    const double shading = light_path_shading_correction(v.sp, v.sp.wo_local, wi);
    const PixelFilter &filter = camera.filter();
    const int width = camera.width(), height = camera.height();
    if (filter.is_box()) {
        // The one pixel holding the vertex, weighed in the order the images were made before
        // the filters, so that they stay the same bits.
        if (!(x < width && y < height)) return;
        const double w = mis_light_trace(state.mis, v.mis, camera_pdf_a, rev);
        const std::uint32_t px = static_cast<std::uint32_t>(x), py = static_cast<std::uint32_t>(y);
        splats.emplace_back(py * static_cast<std::uint32_t>(width) + px,
                            v.throughput * f * (w * camera_pdf_a * shading / state.mis.light_paths));
        return;
    }
    // Each pixel the filter reaches sees the vertex with its camera paths' film density
    // W_p(x, y) (camera/pixel_filter.h), which scales both the camera's density, for the
    // weight, and the pixel's importance.
    const Rgb contribution = v.throughput * f * (shading / state.mis.light_paths);
    const double r = filter.radius();
    const int y0 = std::max(0, static_cast<int>(std::floor(y - 0.5 - r)));
    const int y1 = std::min(height - 1, static_cast<int>(std::ceil(y - 0.5 + r)));
    const int x0 = std::max(0, static_cast<int>(std::floor(x - 0.5 - r)));
    const int x1 = std::min(width - 1, static_cast<int>(std::ceil(x - 0.5 + r)));
    for (int py = y0; py <= y1; ++py)
        for (int px = x0; px <= x1; ++px) {
            const double density = filter.density(px, py, x, y);
            if (!(density > 0)) continue;
            const double pdf_a = camera_pdf_a * density;
            const double w = mis_light_trace(state.mis, v.mis, pdf_a, rev);
            splats.emplace_back(static_cast<std::uint32_t>(py) * static_cast<std::uint32_t>(width) +
                                    static_cast<std::uint32_t>(px),
                                contribution * (w * pdf_a));
        }
}

} // namespace

bool VcmIntegrator::render_pass(const PassInputs &in, std::uint32_t pass, Film &film, PassTimes &times) {
    const auto start = std::chrono::steady_clock::now();
    PassEstimate estimate;
    estimate_pass(in, pass, estimate);
    if (in.cancelled()) return false;
    times.eye_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    times.search_build_seconds = 0;
    times.photon_seconds = 0;
    film.commit_estimated_pass(pass, estimate);
    return true;
}

void VcmIntegrator::make_slots(const PassInputs &, Film &film) {
    std::vector<std::uint32_t> slot_pixel(film.pixel_count());
    for (std::uint32_t p = 0; p < film.pixel_count(); ++p) slot_pixel[p] = p;
    film.set_slots(std::move(slot_pixel));
}

double VcmIntegrator::merge_radius(const PassInputs &in, std::uint32_t pass) {
    double r1 = in.settings.initial_radius;
    if (!(r1 > 0)) {
        const Box3 &bounds = in.scene.scene().bounds();
        const double distance = bounds.empty() ? 1.0 : length(bounds.center() - in.camera.position());
        r1 = in.settings.initial_radius_pixels * in.camera.pixel_size_at_unit_distance() * std::max(distance, 1e-6);
    }
    return r1 * std::pow(static_cast<double>(pass) + 1.0, 0.5 * (in.settings.alpha - 1.0));
}

void VcmIntegrator::trace_light_path(const PassInputs &in, const VcmPassState &state, std::uint32_t pass,
                                     std::uint32_t index, std::vector<VcmLightVertex> &vertices,
                                     std::vector<std::pair<std::uint32_t, Rgb>> &splats) const {
    const RenderScene &scene = in.scene;
    if (scene.lights().empty() || scene.total_power().is_black()) return;
    CounterRng rng(in.settings.seed, kVcmLightStream, pass, index);
    double pick = 0;
    const Light &light = scene.lights()[scene.pick_light(rng.uniform(), &pick)];
    const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform(), u4 = rng.uniform();
    const EmittedPhoton emitted = light.emit(u1, u2, u3, u4);
    const EmissionDensities densities = light.emission_densities(emitted.normal, emitted.direction);
    if (emitted.flux.is_black() || !(densities.emission > 0) || !(pick > 0)) return;
    Rgb throughput = emitted.flux / pick;
    SubpathMis mis = SubpathMis::light_start(state.mis, densities.emission * pick, densities.direct * pick,
                                             densities.cos_light, light.is_delta(), !light.is_infinite());
    ppm_ray ray;
    emitted.origin.store(ray.org);
    emitted.direction.store(ray.dir);
    ray.tnear = 0;
    ray.tfar = INFINITY;
    VcmLightVertex v;
    const ppm_hit *leaving = nullptr; // a light subpath starts at a light, not at a hit
    for (std::uint32_t length = 1;; ++length) {
        if (!scene.intersect(ray, v.sp, leaving, &rng)) return;
        const double cos_here = std::fabs(v.sp.wo_local.z);
        if (!(cos_here > 0)) return;
        const double t = v.sp.hit.t;
        mis.arrive(length > 1 || !light.is_infinite() ? t * t : 0.0, cos_here);
        if (vcm_connectible(v.sp.bsdf)) {
            v.throughput = throughput;
            v.mis = mis;
            v.path_length = length;
            if (state.light_tracing) trace_to_camera(in, state, v, splats);
            vertices.push_back(v);
        }
        if (static_cast<int>(length) + 2 > state.max_length) return;
        VcmScatter s;
        if (!vcm_scatter(v.sp, rng, TransportMode::Importance, s)) return;
        mis.scatter(state.mis, s.specular, std::fabs(s.wi.z), s.pdf_fwd, s.pdf_rev);
        throughput = throughput * s.weight * light_path_shading_correction(v.sp, v.sp.wo_local, s.wi);
        ray = spawn_ray(v.sp.hit, v.sp.frame.to_world(s.wi));
        leaving = &v.sp.hit;
    }
}

void VcmIntegrator::trace_light_paths(const PassInputs &in, std::uint32_t pass, VcmPassState &state) const {
    const std::uint32_t paths = state.light_paths;
    const std::uint32_t blocks = (paths + kLightBlock - 1) / kLightBlock;
    // Kept from pass to pass with their capacity: no page faults for memory just freed.
    auto &block_vertices = state.block_vertices;
    auto &block_counts = state.block_counts;
    auto &block_splats = state.block_splats;
    block_vertices.resize(blocks);
    block_counts.resize(blocks);
    block_splats.resize(blocks);
    for (std::uint32_t b = 0; b < blocks; ++b) {
        block_vertices[b].clear();
        block_counts[b].clear();
        block_splats[b].clear();
    }
    in.context.run([&] {
        tbb::parallel_for(std::uint32_t(0), blocks, [&](std::uint32_t b) {
            if (in.cancelled()) return;
            const std::uint32_t first = b * kLightBlock, last = std::min(paths, first + kLightBlock);
            for (std::uint32_t i = first; i < last; ++i) {
                const std::size_t before = block_vertices[b].size();
                trace_light_path(in, state, pass, i, block_vertices[b], block_splats[b]);
                block_counts[b].push_back(static_cast<std::uint32_t>(block_vertices[b].size() - before));
            }
        });
    });
    if (in.cancelled()) return;
    state.path_start.assign(paths + 1, 0);
    std::size_t total = 0;
    for (std::uint32_t b = 0; b < blocks; ++b) total += block_vertices[b].size();
    state.vertices.clear();
    state.vertices.reserve(total);
    std::uint32_t path = 0;
    for (std::uint32_t b = 0; b < blocks; ++b) {
        for (std::uint32_t count : block_counts[b]) {
            state.path_start[path + 1] = state.path_start[path] + count;
            ++path;
        }
        for (const VcmLightVertex &v : block_vertices[b]) state.vertices.push_back(&v);
    }
    // Splats in subpath order: the sum is the same for any thread count.
    state.splat.assign(in.camera.width() * static_cast<std::size_t>(in.camera.height()), Rgb());
    for (const auto &splats : block_splats)
        for (const auto &[pixel, value] : splats) state.splat[pixel] += value;
}

void VcmIntegrator::estimate_pass(const PassInputs &in, std::uint32_t pass, PassEstimate &out) {
    const std::uint32_t pixels = static_cast<std::uint32_t>(in.camera.width()) * in.camera.height();
    if (!state_) state_ = std::make_shared<VcmPassState>();
    VcmPassState &state = *state_;
    state.radius = merge_radius(in, pass);
    state.light_paths = static_cast<std::uint32_t>(in.settings.paths_per_pass(pixels));
    state.mis = MisFactors::make(state.radius, state.light_paths, connects(), merges());
    state.pixel_area = in.camera.pixel_size_at_unit_distance() * in.camera.pixel_size_at_unit_distance();
    state.max_length = in.settings.max_depth + 1;
    state.light_tracing = connects() && !in.camera.is_thin_lens();
    allocate_or_fail(std::to_string(state.light_paths) + " light subpaths",
                     std::uint64_t(state.light_paths) * (sizeof(VcmLightVertex) * 2 + 16) +
                         std::uint64_t(pixels) * sizeof(Rgb),
                     [&] { trace_light_paths(in, pass, state); });
    if (in.cancelled()) return;
    if (merges()) {
        state.points.resize(state.vertices.size());
        for (std::size_t k = 0; k < state.points.size(); ++k) state.points[k] = state.vertices[k]->sp.p;
        state.grid.build(state.points, state.radius);
        const std::vector<std::uint32_t> &order = state.grid.order();
        state.merge_records.resize(order.size());
        for (std::size_t k = 0; k < order.size(); ++k) {
            const VcmLightVertex &v = *state.vertices[order[k]];
            const Vec3 arriving = v.sp.frame.to_world(v.sp.wo_local);
            state.merge_records[k] = {arriving,  v.throughput,  v.mis.dvcm,
                                      v.mis.dvm, v.path_length, static_cast<float>(std::fabs(dot(arriving, v.sp.ng)))};
        }
    }
    out.radiance.assign(pixels, Rgb());
    out.merges.assign(pixels, 0);
    out.radius = state.radius;
    out.light_paths = state.light_paths;
    in.context.run([&] {
        tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, pixels, 64), [&](const auto &range) {
            if (in.cancelled()) return;
            for (std::uint32_t p = range.begin(); p < range.end(); ++p)
                out.radiance[p] = trace_camera_path(in, state, pass, p, out.merges[p]) + state.splat[p];
        });
    });
}

} // namespace ppm
