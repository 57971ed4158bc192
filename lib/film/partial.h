// SPDX-License-Identifier: Apache-2.0
// A partial render: the pass sums of some passes of a pass-independent render, with the
// identity of the render they belong to, saved to and read from a versioned, checksummed
// binary file. Partials of the same render with disjoint passes merge exactly (PassSums), so
// a render split over processes or machines gives the same bits as one process.
//
// File layout (native byte order, which the header records):
//   "PPMPART\0", u32 version, u32 byte-order mark 0x01020304
//   identity: u32 width, u32 height, u32 mode, u32 direct_lighting, u64 seed,
//             f64 initial_radius, f64 initial_radius_pixels, f64 alpha, u64 photons_per_pass,
//             u32 max_depth, u32 glossy_gather_alpha (float bits; 0 = the default 0.2, as
//             files before the setting wrote), u64 camera hash, u64 scene hash
//   u64 pass_total (the render's planned pass count; 0: not given), u64 photons emitted,
//   u64 rejected values, u64 range count n, n x (u64 first, u64 end) pass ranges
//   u64 pixel count, u64 compressed size c, c bytes: zlib of the pixel records, each
//   3 x i128 radiance sums, i128 radius sum, u64 photon sum (72 bytes)
//   u64 FNV-1a hash of every byte before it
#pragma once

#include "core/ref_counted.h"
#include "film/pass_sums.h"

#include <cstdint>
#include <string>
#include <vector>

namespace ppm {

// What must agree for two partials to belong to the same render.
struct RenderIdentity {
    std::uint32_t width = 0, height = 0, mode = 0, direct_lighting = 0;
    std::uint64_t seed = 0;
    double initial_radius = 0, initial_radius_pixels = 0, alpha = 0;
    std::uint64_t photons_per_pass = 0;
    std::uint32_t max_depth = 0;
    std::uint32_t glossy_gather_alpha_bits = 0; // see glossy_gather_alpha_bits() below
    std::uint64_t camera_hash = 0, scene_hash = 0;

    // "" if equal, else what differs: "its seed is 3, the other's is 4".
    std::string difference(const RenderIdentity &other) const;
};

// The setting as the identity records it: the bits of the float nearest to it, 0 for the
// default (so that partials written before the setting existed keep their identity).
std::uint32_t glossy_gather_alpha_bits(double value);
double glossy_gather_alpha(const RenderIdentity &id);

class Partial : public RefCounted {
public:
    Partial(RenderIdentity identity, PassSums sums, std::string origin)
        : identity_(identity), sums_(std::move(sums)), origin_(std::move(origin)) {}

    // Throws ppm::Error: IO (cannot read), PARSE naming `origin` (not a partial, another
    // version, truncated, corrupt, numbers no render could make).
    static Partial *load(const std::string &path);
    static Partial *parse(const char *data, std::size_t size, const std::string &origin);

    std::vector<char> serialize() const;
    // serialize()'s bytes, kept until the partial changes.
    const std::vector<char> &serialized() const;
    void save(const std::string &path) const; // atomically; throws IO

    // Adds `other`'s passes. Throws INVALID_ARGUMENT naming both origins when the identities
    // differ or the passes overlap (the first shared range named); this partial is then unchanged.
    void merge(const Partial &other);
    // Throws INVALID_ARGUMENT as merge() would, without merging.
    void check_mergeable(const RenderIdentity &identity, const PassSet &passes, const std::string &origin) const;

    const RenderIdentity &identity() const { return identity_; }
    const PassSums &sums() const { return sums_; }
    const std::string &origin() const { return origin_; }
    std::uint64_t pass_total() const { return pass_total_; }
    void set_pass_total(std::uint64_t total) {
        pass_total_ = total;
        serialized_.clear();
    }

    // The image layers as Film::read_layer gives them ("radiance", "radius", "photons").
    void read_layer(const std::string &name, float *out) const;

private:
    RenderIdentity identity_;
    PassSums sums_;
    std::string origin_; // the file it came from, for messages
    std::uint64_t pass_total_ = 0;
    mutable std::vector<char> serialized_;
};

} // namespace ppm
