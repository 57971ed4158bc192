// SPDX-License-Identifier: Apache-2.0
#include "film/partial.h"

#include "core/error.h"
#include "film/film.h"
#include "io/atomic_file.h"
#include "io/binary_record.h"
#include "io/text_file.h"
#include "settings/render_settings.h"

#include <zlib.h>

#include <cstring>
#include <limits>

namespace ppm {

namespace {

constexpr char kPartialMagic[8] = {'P', 'P', 'M', 'P', 'A', 'R', 'T', '\0'};
constexpr std::uint32_t kPartialVersion = 1;
constexpr std::uint32_t kPartialByteOrderMark = 0x01020304;
constexpr std::size_t kPixelRecordBytes = 4 * sizeof(Fixed128) + sizeof(std::uint64_t);
constexpr std::uint64_t kMaxRanges = std::uint64_t(1) << 32;
constexpr std::uint64_t kMaxPixels = std::uint64_t(1) << 28; // the renderer's image limit

[[noreturn]] void corrupt_partial(const std::string &origin, const std::string &what) {
    fail(PPM_ERROR_PARSE, origin + ": corrupt partial render: " + what);
}

void put_identity(ByteWriter &w, const RenderIdentity &id) {
    w.put(id.width), w.put(id.height), w.put(id.mode), w.put(id.direct_lighting), w.put(id.seed);
    w.put(id.initial_radius), w.put(id.initial_radius_pixels), w.put(id.alpha), w.put(id.photons_per_pass);
    w.put(id.max_depth), w.put(id.glossy_gather_alpha_bits), w.put(id.camera_hash), w.put(id.scene_hash);
}

RenderIdentity get_identity(ByteReader &r) {
    RenderIdentity id;
    id.width = r.get<std::uint32_t>("header"), id.height = r.get<std::uint32_t>("header");
    id.mode = r.get<std::uint32_t>("header"), id.direct_lighting = r.get<std::uint32_t>("header");
    id.seed = r.get<std::uint64_t>("header");
    id.initial_radius = r.get<double>("header"), id.initial_radius_pixels = r.get<double>("header");
    id.alpha = r.get<double>("header"), id.photons_per_pass = r.get<std::uint64_t>("header");
    id.max_depth = r.get<std::uint32_t>("header");
    id.glossy_gather_alpha_bits = r.get<std::uint32_t>("header");
    id.camera_hash = r.get<std::uint64_t>("header"), id.scene_hash = r.get<std::uint64_t>("header");
    return id;
}

std::vector<unsigned char> pack_pixels(const PassSums &sums) {
    std::vector<unsigned char> raw(sums.pixel_count() * kPixelRecordBytes);
    unsigned char *out = raw.data();
    for (const PassSums::Pixel &p : sums.pixels()) {
        std::memcpy(out, p.radiance, sizeof p.radiance), out += sizeof p.radiance;
        std::memcpy(out, &p.radius, sizeof p.radius), out += sizeof p.radius;
        std::memcpy(out, &p.photons, sizeof p.photons), out += sizeof p.photons;
    }
    return raw;
}

} // namespace

std::uint32_t glossy_gather_alpha_bits(double value) {
    if (value == RenderSettings{}.glossy_gather_alpha) return 0;
    const float f = static_cast<float>(value);
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    return bits == 0 ? 1 : bits; // 0.0 itself: the smallest subnormal, never a real setting
}

double glossy_gather_alpha(const RenderIdentity &id) {
    if (id.glossy_gather_alpha_bits == 0) return RenderSettings{}.glossy_gather_alpha;
    float f;
    std::memcpy(&f, &id.glossy_gather_alpha_bits, sizeof f);
    return f;
}

std::string RenderIdentity::difference(const RenderIdentity &o) const {
    const auto text = [](const char *what, const std::string &ours, const std::string &theirs) {
        return std::string("its ") + what + " is " + ours + ", the other's is " + theirs;
    };
    const auto number = [](auto v) { return std::to_string(v); };
    if (width != o.width || height != o.height)
        return text("image size", number(width) + " x " + number(height), number(o.width) + " x " + number(o.height));
    if (mode != o.mode) return text("mode", RenderSettings::mode_name(mode), RenderSettings::mode_name(o.mode));
    if (direct_lighting != o.direct_lighting)
        return text("direct_lighting", number(direct_lighting), number(o.direct_lighting));
    if (seed != o.seed) return text("seed", number(seed), number(o.seed));
    if (initial_radius != o.initial_radius || initial_radius_pixels != o.initial_radius_pixels)
        return text("initial radius (scene units, pixels)",
                    format_number(initial_radius) + ", " + format_number(initial_radius_pixels),
                    format_number(o.initial_radius) + ", " + format_number(o.initial_radius_pixels));
    if (alpha != o.alpha) return text("alpha", format_number(alpha), format_number(o.alpha));
    if (photons_per_pass != o.photons_per_pass)
        return text("photons_per_pass", number(photons_per_pass), number(o.photons_per_pass));
    if (max_depth != o.max_depth) return text("max_depth", number(max_depth), number(o.max_depth));
    if (glossy_gather_alpha_bits != o.glossy_gather_alpha_bits)
        return text("glossy_gather_alpha", format_number(glossy_gather_alpha(*this)),
                    format_number(glossy_gather_alpha(o)));
    if (camera_hash != o.camera_hash) return "the cameras differ";
    if (scene_hash != o.scene_hash) return "the scenes differ";
    return "";
}

std::vector<char> Partial::serialize() const {
    const std::vector<unsigned char> raw = pack_pixels(sums_);
    uLongf compressed_size = compressBound(static_cast<uLong>(raw.size()));
    std::vector<unsigned char> compressed(compressed_size);
    // Level 1: the records are mostly zero bytes (the high words of the sums), which the
    // fastest level already removes; higher levels cost several times the time for a few %.
    if (compress2(compressed.data(), &compressed_size, raw.data(), static_cast<uLong>(raw.size()), 1) != Z_OK)
        fail(PPM_ERROR_OUT_OF_MEMORY,
             "cannot compress the partial render of " + std::to_string(sums_.pixel_count()) + " pixels");
    ByteWriter w;
    w.put_bytes(kPartialMagic, sizeof kPartialMagic);
    w.put(kPartialVersion), w.put(kPartialByteOrderMark);
    put_identity(w, identity_);
    w.put(pass_total_), w.put(sums_.photons_emitted()), w.put(sums_.rejected());
    const auto &ranges = sums_.passes().ranges();
    w.put(static_cast<std::uint64_t>(ranges.size()));
    for (const PassSet::Range &range : ranges) w.put(range.first), w.put(range.end);
    w.put(static_cast<std::uint64_t>(sums_.pixel_count())), w.put(static_cast<std::uint64_t>(compressed_size));
    w.put_bytes(compressed.data(), compressed_size);
    Fnv1a h;
    h.add(w.buffer().data(), w.buffer().size());
    w.put(h.value());
    return std::move(w.buffer());
}

const std::vector<char> &Partial::serialized() const {
    if (serialized_.empty()) serialized_ = serialize();
    return serialized_;
}

void Partial::save(const std::string &path) const {
    const std::vector<char> &bytes = serialized();
    write_file_atomically(path, bytes.data(), bytes.size());
}

Partial *Partial::load(const std::string &path) {
    const std::string bytes = read_text_file(path);
    return parse(bytes.data(), bytes.size(), path);
}

Partial *Partial::parse(const char *data, std::size_t size, const std::string &origin) {
    ByteReader r(origin, "partial render", data, size);
    char magic[sizeof kPartialMagic];
    r.get_bytes(magic, sizeof magic, "header");
    if (std::memcmp(magic, kPartialMagic, sizeof magic) != 0)
        fail(PPM_ERROR_PARSE, origin + ": not a libppm partial render");
    const auto version = r.get<std::uint32_t>("header");
    if (version != kPartialVersion)
        fail(PPM_ERROR_PARSE, origin + ": partial render version " + std::to_string(version) +
                                  "; this libppm reads version " + std::to_string(kPartialVersion));
    if (r.get<std::uint32_t>("header") != kPartialByteOrderMark)
        fail(PPM_ERROR_PARSE, origin + ": partial render written on a machine of another byte order");
    if (size < sizeof(std::uint64_t)) fail(PPM_ERROR_PARSE, origin + ": truncated partial render");
    Fnv1a h;
    h.add(data, size - sizeof(std::uint64_t));
    std::uint64_t stored_hash;
    std::memcpy(&stored_hash, data + size - sizeof stored_hash, sizeof stored_hash);
    if (stored_hash != h.value())
        fail(PPM_ERROR_PARSE, origin + ": corrupt or truncated partial render (the checksum does not match)");

    const RenderIdentity identity = get_identity(r);
    const ModeTraits *mode = find_mode(identity.mode);
    if (!mode || !mode->supports_partials)
        corrupt_partial(origin, "mode " + std::to_string(identity.mode) + " is not a mode of partial renders");
    const std::uint64_t pixels = std::uint64_t(identity.width) * identity.height;
    if (identity.width == 0 || identity.height == 0 || pixels > kMaxPixels)
        corrupt_partial(origin,
                        "image size " + std::to_string(identity.width) + " x " + std::to_string(identity.height));
    if (identity.photons_per_pass < 1 || identity.photons_per_pass > std::uint64_t(kMaxPhotonsPerPass))
        corrupt_partial(origin, "photons_per_pass " + std::to_string(identity.photons_per_pass));
    const auto pass_total = r.get<std::uint64_t>("header");
    const auto emitted = r.get<std::uint64_t>("header"), rejected = r.get<std::uint64_t>("header");
    const auto range_count = r.get<std::uint64_t>("pass ranges");
    if (range_count > kMaxRanges || range_count * 16 > r.remaining())
        corrupt_partial(origin, std::to_string(range_count) + " pass ranges");
    std::vector<PassSet::Range> ranges(range_count);
    for (PassSet::Range &range : ranges)
        range.first = r.get<std::uint64_t>("pass ranges"), range.end = r.get<std::uint64_t>("pass ranges");
    PassSet pass_set;
    if (!pass_set.assign_checked(std::move(ranges)))
        corrupt_partial(origin, "the pass ranges are not sorted, disjoint and non-empty");
    if (!pass_set.empty() && pass_set.ranges().back().end > kPassIndexLimit)
        corrupt_partial(origin, "pass index " + std::to_string(pass_set.ranges().back().end - 1) + " of 2^32 or more");
    if (pass_total > kPassIndexLimit) corrupt_partial(origin, "a total of " + std::to_string(pass_total) + " passes");
    const std::uint64_t passes = pass_set.count();
    if (passes == 0) corrupt_partial(origin, "no pass");
    // The identity holds the paths each pass traced (photons_per_pass resolved: paths_per_pass).
    const bool bidirectional = mode->bidirectional;
    const std::uint64_t per_pass = identity.photons_per_pass;
    if (emitted != passes * per_pass)
        corrupt_partial(origin, std::to_string(emitted) +
                                    (bidirectional ? " light subpaths in " : " photons emitted in ") +
                                    std::to_string(passes) + " passes of " + std::to_string(per_pass));
    const auto stored_pixels = r.get<std::uint64_t>("pixels");
    const auto compressed_size = r.get<std::uint64_t>("pixels");
    if (stored_pixels != pixels)
        corrupt_partial(origin,
                        std::to_string(stored_pixels) + " pixel records for " + std::to_string(pixels) + " pixels");
    if (compressed_size != r.remaining() - sizeof(std::uint64_t))
        corrupt_partial(origin, "the pixel records' size does not match the file's");

    std::vector<unsigned char> raw;
    PassSums sums;
    allocate_or_fail(origin + ": the partial render's " + std::to_string(pixels) + " pixels",
                     pixels * (kPixelRecordBytes + sizeof(PassSums::Pixel)), [&] {
                         raw.resize(pixels * kPixelRecordBytes);
                         sums = PassSums(pixels);
                     });
    sums.passes() = pass_set;
    sums.add_photons_emitted(emitted);
    sums.add_rejected(rejected);
    uLongf raw_size = static_cast<uLongf>(raw.size());
    const auto *compressed = reinterpret_cast<const unsigned char *>(data + r.position());
    if (uncompress(raw.data(), &raw_size, compressed, static_cast<uLong>(compressed_size)) != Z_OK ||
        raw_size != raw.size())
        corrupt_partial(origin, "the pixel records do not decompress to " + std::to_string(pixels) + " records");
    const unsigned char *in = raw.data();
    for (std::size_t i = 0; i < pixels; ++i) {
        PassSums::Pixel &p = sums.pixels()[i];
        std::memcpy(p.radiance, in, sizeof p.radiance), in += sizeof p.radiance;
        std::memcpy(&p.radius, in, sizeof p.radius), in += sizeof p.radius;
        std::memcpy(&p.photons, in, sizeof p.photons), in += sizeof p.photons;
        // Sums of values in [0, 2^80] quanta over at most 2^64 passes.
        for (const Fixed128 v : {p.radiance[0], p.radiance[1], p.radiance[2], p.radius})
            if (v < 0) corrupt_partial(origin, "pixel " + std::to_string(i) + ": a negative sum");
    }
    auto *partial = new Partial(identity, std::move(sums), origin);
    partial->set_pass_total(pass_total);
    return partial;
}

void Partial::check_mergeable(const RenderIdentity &identity, const PassSet &passes, const std::string &origin) const {
    const std::string difference = identity.difference(identity_);
    if (!difference.empty())
        invalid_argument(origin + " is a partial of another render than " + origin_ + ": " + difference);
    if (const auto overlap = passes.first_overlap(sums_.passes()))
        invalid_argument(origin + " and " + origin_ + " both hold pass" +
                         (overlap->end - overlap->first == 1 ? " " : "es ") + PassSet::describe(*overlap));
}

void Partial::merge(const Partial &other) {
    check_mergeable(other.identity_, other.sums_.passes(), other.origin_);
    sums_.merge(other.sums_);
    set_pass_total(std::max(pass_total_, other.pass_total_));
}

void Partial::read_layer(const std::string &name, float *out) const {
    Film::layer_channels(name); // throws for an unknown name
    if (name == "radiance")
        sums_.mean_radiance(out);
    else if (name == "radius")
        sums_.mean_radius(out);
    else
        sums_.photon_sums(out);
}

} // namespace ppm
