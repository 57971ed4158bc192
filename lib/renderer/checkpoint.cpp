// SPDX-License-Identifier: Apache-2.0
// Renderer::save_checkpoint and load_checkpoint: the progressive state in a versioned binary
// file.
//
// Layout (native byte order, which the header records):
//   "PPMCKPT\0", u32 version, u32 byte-order mark 0x01020304
//   u32 width, u32 height, u32 mode, u32 direct_lighting, u64 seed,
//   f64 initial_radius, f64 initial_radius_pixels, u64 camera hash, u64 scene hash
//   u64 passes, u64 photons emitted, u64 slot count n
//   n x u32 pixel of each slot, n x 8 f64 statistics (N, R^2, tau rgb, direct rgb)
//   u64 FNV-1a hash of every byte before it
// In PPM mode the fixed hit points are not stored: the first eye pass is deterministic, so
// load_checkpoint traces it again and checks that it gives the same slots.
#include "renderer/renderer.h"

#include "core/error.h"
#include "integrator/camera_paths.h"
#include "io/atomic_file.h"
#include "io/binary_record.h"
#include "io/text_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace ppm {

namespace {

constexpr char kCheckpointMagic[8] = {'P', 'P', 'M', 'C', 'K', 'P', 'T', '\0'};
constexpr std::uint32_t kCheckpointVersion = 1;
constexpr std::uint32_t kCheckpointByteOrderMark = 0x01020304;

[[noreturn]] void corrupt_checkpoint(const std::string &path, const std::string &what) {
    fail(PPM_ERROR_PARSE, path + ": corrupt checkpoint: " + what);
}

// Every pass emits at least one photon and at most the largest photons_per_pass; statistics
// exist exactly when a pass has completed.
void check_counts(const std::string &path, std::uint64_t passes, std::uint64_t emitted, std::uint64_t slots) {
    // The API reports both counts as int64_t; passes <= emitted is checked below.
    if (emitted > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
        corrupt_checkpoint(path, std::to_string(emitted) + " photons emitted, more than 2^63 - 1");
    if (passes == 0 && (emitted != 0 || slots != 0))
        corrupt_checkpoint(path, "no pass recorded, but " + std::to_string(emitted) + " photons emitted and " +
                                     std::to_string(slots) + " pixel slots");
    if (passes > 0 && slots == 0)
        corrupt_checkpoint(path, std::to_string(passes) + " passes recorded but no pixel statistics");
    if (passes > 0 && (emitted < passes || emitted / passes > kMaxPhotonsPerPass))
        corrupt_checkpoint(path, std::to_string(emitted) + " photons emitted do not fit " + std::to_string(passes) +
                                     " passes of 1 to " + std::to_string(kMaxPhotonsPerPass) + " photons");
}

} // namespace

// A checksum only proves that the file is as written; these bounds prove that the numbers
// could have come from a render, so that a crafted file cannot make the next pass compute
// NaN or infinite radiance. Each photon path adds at most one photon per scattering event to
// a pixel (n <= emitted * max_depth limit); radii only shrink from the largest initial
// radius any visible point can get; every estimate must fit the float image.
void Renderer::check_statistics(const std::string &path, const std::vector<PixelStatistics> &stats,
                                std::uint64_t passes, std::uint64_t emitted) const {
    const Box3 &box = scene_->bounds();
    const Vec3 far_corner{
        std::max(std::abs(box.lower.x - camera_settings_.origin.x), std::abs(box.upper.x - camera_settings_.origin.x)),
        std::max(std::abs(box.lower.y - camera_settings_.origin.y), std::abs(box.upper.y - camera_settings_.origin.y)),
        std::max(std::abs(box.lower.z - camera_settings_.origin.z), std::abs(box.upper.z - camera_settings_.origin.z))};
    const double longest_path = length(far_corner) + kMaxDepthLimit * length(box.upper - box.lower);
    const double largest_r2 = footprint_r2(pass_inputs(), longest_path);
    const double most_photons = static_cast<double>(emitted) * kMaxDepthLimit;
    const auto bad = [&](std::size_t slot, const char *field, double value, const char *rule) {
        corrupt_checkpoint(path, "pixel slot " + std::to_string(slot) + ": " + field + " = " + format_number(value) +
                                     " (" + rule + ")");
    };
    const auto check_colour = [&](std::size_t slot, const char *field, const Rgb &c) {
        for (double v : {c.r, c.g, c.b})
            if (!(v >= 0 && std::isfinite(v))) bad(slot, field, v, "must be finite and >= 0");
    };
    for (std::size_t i = 0; i < stats.size(); ++i) {
        const PixelStatistics &s = stats[i];
        if (!(s.n >= 0 && s.n <= most_photons))
            bad(i, "photon count N", s.n,
                ("must lie in [0, photons emitted x " + std::to_string(kMaxDepthLimit) + "]").c_str());
        if (!(s.r2 >= 0 && s.r2 <= largest_r2))
            bad(i, "radius squared", s.r2, "must lie in [0, the largest initial radius squared]");
        if (s.n > 0 && !(s.r2 > 0)) bad(i, "radius squared", s.r2, "must be > 0 where photons were found");
        // A slot gets its radius before it gathers flux; the next pass would give a slot with
        // r2 = 0 the initial radius and keep its flux.
        if (s.r2 == 0 && !s.tau.is_black())
            bad(i, "flux tau", std::max({s.tau.r, s.tau.g, s.tau.b}), "must be 0 where no radius was set");
        check_colour(i, "flux tau", s.tau);
        check_colour(i, "direct light", s.direct);
        const Rgb l = radiance_estimate(s, emitted, passes);
        for (double v : {l.r, l.g, l.b})
            if (!(v <= std::numeric_limits<float>::max())) bad(i, "radiance", v, "too large for the image");
    }
}

std::uint64_t Renderer::camera_hash() const {
    Fnv1a h;
    const CameraSettings &c = camera_settings_;
    h.add(c.origin), h.add(c.target), h.add(c.up), h.add(c.fov), h.add(c.width), h.add(c.height);
    h.add(c.aperture_radius), h.add(c.focus_distance), h.add(c.near_clip);
    // Only a crop window, an offset and a filter other than the box are hashed, so that
    // checkpoints of other renders stay readable.
    if (c.cropped()) h.add(c.crop_x0), h.add(c.crop_y0), h.add(c.crop_x1), h.add(c.crop_y1);
    if (c.offset()) h.add(c.principal_point_offset_x), h.add(c.principal_point_offset_y);
    if (c.filter.type != PixelFilterType::Box)
        h.add(static_cast<int>(c.filter.type)), h.add(pixel_filter_parameter(c.filter));
    return h.value();
}

// What identifies a scene well enough to refuse a foreign checkpoint: its geometries (kind,
// primitive count, placement, material, emission), bounds, materials and lights' power.
std::uint64_t Renderer::scene_hash() const {
    Fnv1a h;
    h.add(scene_->geometry_count());
    for (std::size_t g = 0; g < scene_->geometry_count(); ++g) {
        const Geometry &geometry = scene_->geometry(static_cast<std::uint32_t>(g));
        h.add(geometry.kind(), std::strlen(geometry.kind()));
        h.add(geometry.primitive_count());
        for (const auto &row : geometry.transform.m)
            for (double v : row) h.add(v);
        h.add(geometry.material);
        h.add(render_scene_.emission(static_cast<std::uint32_t>(g)));
    }
    h.add(scene_->bounds().lower), h.add(scene_->bounds().upper);
    h.add(material_count_);
    h.add(point_light_count_);
    h.add(render_scene_.total_power());
    return h.value();
}

void Renderer::save_checkpoint(const std::string &path) const {
    // A pass-independent render's checkpoint is its partial render (none before a pass).
    if (mode_traits(settings_.mode).supports_partials && started()) {
        Owned<Partial>(make_partial())->save(path);
        return;
    }
    ByteWriter w;
    // The state after the last completed pass (no slots before the first: only the identity).
    film_.with_state([&](const std::vector<std::uint32_t> &slot_pixel, const std::vector<PixelStatistics> &stats,
                         std::uint64_t passes, std::uint64_t emitted) {
        const std::uint64_t slots = slot_pixel.size();
        w.put_bytes(kCheckpointMagic, sizeof kCheckpointMagic);
        w.put(kCheckpointVersion), w.put(kCheckpointByteOrderMark);
        w.put(static_cast<std::uint32_t>(width())), w.put(static_cast<std::uint32_t>(height()));
        w.put(static_cast<std::uint32_t>(settings_.mode)), w.put(static_cast<std::uint32_t>(settings_.direct_lighting));
        w.put(settings_.seed), w.put(settings_.initial_radius), w.put(settings_.initial_radius_pixels);
        w.put(camera_hash()), w.put(scene_hash());
        w.put(passes), w.put(emitted), w.put(slots);
        if (slots > 0) {
            w.put_bytes(slot_pixel.data(), slots * sizeof(std::uint32_t));
            for (const PixelStatistics &s : stats) {
                const double values[8] = {s.n, s.r2, s.tau.r, s.tau.g, s.tau.b, s.direct.r, s.direct.g, s.direct.b};
                w.put_bytes(values, sizeof values);
            }
        }
    });
    Fnv1a h;
    h.add(w.buffer().data(), w.buffer().size());
    w.put(h.value());
    write_file_atomically(path, w.buffer().data(), w.buffer().size());
}

void Renderer::load_checkpoint(const std::string &path) {
    std::unique_lock<std::mutex> one_pass(pass_mutex_, std::try_to_lock);
    if (!one_pass.owns_lock()) fail(PPM_ERROR_INVALID_OPERATION, "a pass of this renderer is running");
    if (started()) fail(PPM_ERROR_INVALID_OPERATION, "a checkpoint can only be loaded before the first pass");

    const std::string bytes = read_text_file(path);
    if (mode_traits(settings_.mode).supports_partials && bytes.compare(0, 8, "PPMPART", 8) == 0)
        return load_partial_checkpoint(path, bytes);
    ByteReader r(path, "checkpoint", bytes.data(), bytes.size());
    char magic[sizeof kCheckpointMagic];
    r.get_bytes(magic, sizeof magic, "header");
    if (std::memcmp(magic, kCheckpointMagic, sizeof magic) != 0)
        fail(PPM_ERROR_PARSE, path + ": not a libppm checkpoint");
    const auto version = r.get<std::uint32_t>("header");
    if (version != kCheckpointVersion)
        fail(PPM_ERROR_PARSE, path + ": checkpoint version " + std::to_string(version) +
                                  "; this libppm reads version " + std::to_string(kCheckpointVersion));
    if (r.get<std::uint32_t>("header") != kCheckpointByteOrderMark)
        fail(PPM_ERROR_PARSE, path + ": checkpoint written on a machine of another byte order");
    if (bytes.size() < sizeof(std::uint64_t)) fail(PPM_ERROR_PARSE, path + ": truncated checkpoint");
    Fnv1a h;
    h.add(bytes.data(), bytes.size() - sizeof(std::uint64_t));
    std::uint64_t stored_hash;
    std::memcpy(&stored_hash, bytes.data() + bytes.size() - sizeof stored_hash, sizeof stored_hash);

    // The recorded identity, checked field by field so that the message says what differs.
    const auto width_ = r.get<std::uint32_t>("header"), height_ = r.get<std::uint32_t>("header");
    const auto mode = r.get<std::uint32_t>("header"), direct = r.get<std::uint32_t>("header");
    const auto seed = r.get<std::uint64_t>("header");
    const auto radius = r.get<double>("header"), radius_pixels = r.get<double>("header");
    const auto camera = r.get<std::uint64_t>("header"), scene = r.get<std::uint64_t>("header");
    const auto passes = r.get<std::uint64_t>("header"), emitted = r.get<std::uint64_t>("header");
    const auto slots = r.get<std::uint64_t>("header");
    const std::uint64_t body = slots * (sizeof(std::uint32_t) + 8 * sizeof(double)) + sizeof(std::uint64_t);
    if (slots > (std::uint64_t(1) << 40) || r.remaining() != body || stored_hash != h.value())
        fail(PPM_ERROR_PARSE, path + ": corrupt or truncated checkpoint (size or checksum does not match)");

    const auto differs = [&](const std::string &what, const std::string &theirs, const std::string &ours) {
        invalid_argument(path + ": checkpoint of another render: its " + what + " is " + theirs +
                         ", this renderer's is " + ours);
    };
    if (width_ != static_cast<std::uint32_t>(width()) || height_ != static_cast<std::uint32_t>(height()))
        differs("image size", std::to_string(width_) + " x " + std::to_string(height_),
                std::to_string(width()) + " x " + std::to_string(height()));
    if (mode != static_cast<std::uint32_t>(settings_.mode))
        differs("mode", RenderSettings::mode_name(mode), settings_.get_string("mode"));
    if (direct != static_cast<std::uint32_t>(settings_.direct_lighting))
        differs("direct_lighting", std::to_string(direct), std::to_string(settings_.direct_lighting));
    if (seed != settings_.seed) differs("seed", std::to_string(seed), std::to_string(settings_.seed));
    if (radius != settings_.initial_radius || radius_pixels != settings_.initial_radius_pixels)
        differs("initial radius (scene units, pixels)", format_number(radius) + ", " + format_number(radius_pixels),
                format_number(settings_.initial_radius) + ", " + format_number(settings_.initial_radius_pixels));
    if (camera != camera_hash()) invalid_argument(path + ": checkpoint of another render: the camera differs");
    if (scene != scene_hash()) invalid_argument(path + ": checkpoint of another render: the scene differs");
    check_counts(path, passes, emitted, slots);
    if (slots == 0) return; // saved before any pass completed: nothing to restore

    std::vector<std::uint32_t> pixels;
    std::vector<PixelStatistics> stats;
    allocate_or_fail(path + ": the checkpoint's " + std::to_string(slots) + " pixel slots",
                     slots * (sizeof(std::uint32_t) + sizeof(PixelStatistics)), [&] {
                         pixels.resize(slots);
                         stats.resize(slots);
                     });
    r.get_bytes(pixels.data(), slots * sizeof(std::uint32_t), "slots");
    for (PixelStatistics &s : stats) {
        double v[8];
        r.get_bytes(v, sizeof v, "statistics");
        s.n = v[0], s.r2 = v[1], s.tau = Rgb{v[2], v[3], v[4]}, s.direct = Rgb{v[5], v[6], v[7]};
    }
    check_statistics(path, stats, passes, emitted);

    // Rebuild the slots as the first pass made them (SPPM: one per pixel; PPM: the first eye
    // pass's split paths, traced again), then take the statistics.
    film_.clear_slots();
    integrator().make_slots(pass_inputs(), film_);
    if (cancelled()) {
        film_.clear_slots();
        fail(PPM_ERROR_CANCELLED, "loading the checkpoint was cancelled");
    }
    if (film_.slot_pixels() != pixels) {
        film_.clear_slots();
        invalid_argument(path + ": checkpoint of another render: its hit points differ from this renderer's");
    }
    film_.restore(std::move(stats), passes, emitted);
}

} // namespace ppm
