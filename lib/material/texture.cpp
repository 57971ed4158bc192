// SPDX-License-Identifier: Apache-2.0
#include "material/texture.h"

#include "core/error.h"

#include <OpenImageIO/imageio.h>

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>

namespace ppm {

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

namespace {

bool colorspace_is(const std::string &colorspace, const char *name) {
    return std::equal(colorspace.begin(), colorspace.end(), name, name + std::strlen(name),
                      [](char a, char b) { return std::tolower(a) == std::tolower(b); });
}

bool is_srgb_encoded(const OIIO::ImageSpec &spec) {
    const std::string colorspace = spec.get_string_attribute("oiio:ColorSpace");
    if (colorspace_is(colorspace, "sRGB")) return true;
    if (colorspace_is(colorspace, "linear") || colorspace_is(colorspace, "scene_linear") ||
        colorspace_is(colorspace, "lin_srgb"))
        return false;
    const OIIO::TypeDesc::BASETYPE base = static_cast<OIIO::TypeDesc::BASETYPE>(spec.format.basetype);
    return base != OIIO::TypeDesc::FLOAT && base != OIIO::TypeDesc::HALF && base != OIIO::TypeDesc::DOUBLE;
}

// OpenImageIO 2.4's PNG reader, on a file that ends early, lets libpng print "libpng error:
// ... hit end of file" on stderr and leaks the message (its read callback holds a std::string
// across libpng's longjmp). So a PNG is walked chunk by chunk first: every chunk up to IEND
// must lie inside the file, and then libpng never reads past its end. Other formats, and
// PNGs with bad content, are left to OpenImageIO.
void check_png_is_complete(const std::string &path) {
    std::unique_ptr<std::FILE, int (*)(std::FILE *)> file(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!file) return; // OpenImageIO names the problem
    unsigned char header[8];
    if (std::fread(header, 1, sizeof header, file.get()) != sizeof header ||
        std::memcmp(header, "\x89PNG\r\n\x1a\n", sizeof header) != 0 || std::fseek(file.get(), 0, SEEK_END) != 0)
        return;
    const long long size = std::ftell(file.get());
    const auto truncated = [&](const std::string &what) {
        fail(PPM_ERROR_IO,
             "texture '" + path + "' is a truncated PNG: " + what + ", the file ends at byte " + std::to_string(size));
    };
    for (long long offset = 8;;) {
        if (offset + 8 > size || std::fseek(file.get(), static_cast<long>(offset), SEEK_SET) != 0 ||
            std::fread(header, 1, sizeof header, file.get()) != sizeof header)
            truncated("no IEND chunk");
        const long long length = static_cast<long long>(header[0]) << 24 | header[1] << 16 | header[2] << 8 | header[3];
        const std::string type(reinterpret_cast<const char *>(header + 4), 4);
        const bool named =
            std::all_of(type.begin(), type.end(), [](char c) { return std::isalpha(static_cast<unsigned char>(c)); });
        // Length, type, data and CRC.
        const long long end = offset + 12 + length;
        if (end > size)
            truncated("the chunk " + (named ? type + " " : std::string()) + "at byte " + std::to_string(offset) +
                      " runs to byte " + std::to_string(end));
        if (type == "IEND") return;
        offset = end;
    }
}

// OpenEXR 3.1 allocates (and zero-fills) every header attribute at the size the file states
// before reading it, so 23 bytes can make it take 2 GB. The first header is walked first:
// every attribute (name, type, 32-bit size, value) must lie inside the file. Anything this
// walk cannot follow is left to OpenEXR.
void check_exr_header_fits(const std::string &path) {
    std::unique_ptr<std::FILE, int (*)(std::FILE *)> file(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!file) return;
    // A header is a few kilobytes at most; reading 64 KiB covers it.
    std::string bytes(1 << 16, '\0');
    bytes.resize(std::fread(&bytes[0], 1, bytes.size(), file.get()));
    if (bytes.size() < 8 || bytes.compare(0, 4, "v/1\x01") != 0 || std::fseek(file.get(), 0, SEEK_END) != 0) return;
    const long long size = std::ftell(file.get());
    std::size_t at = 8;
    const auto skip_string = [&]() {
        const std::size_t end = bytes.find('\0', at);
        if (end == std::string::npos || end - at > 255) return false;
        at = end + 1;
        return true;
    };
    while (at < bytes.size() && bytes[at] != '\0') {
        const std::size_t name_at = at;
        if (!skip_string() || !skip_string() || at + 4 > bytes.size()) return;
        std::int32_t length;
        std::memcpy(&length, &bytes[at], sizeof length); // little-endian, as on every host we build for
        at += 4;
        if (length < 0 || static_cast<long long>(at) + length > size)
            fail(PPM_ERROR_IO, "texture '" + path + "' is a corrupt or truncated OpenEXR file: its header attribute '" +
                                   std::string(bytes.c_str() + name_at) + "' claims " + std::to_string(length) +
                                   " bytes, the file has " + std::to_string(size));
        at += static_cast<std::size_t>(length);
    }
}

// The largest ratio of decoded to stored bytes of the codecs image files use: DEFLATE (PNG,
// EXR's ZIP) expands at most 1032:1; RLE, PIZ and JPEG less.
// Below kMaxTrustedDecode any header is believed: packed 1-bit or palette PNGs and GIF's LZW
// can expand further than DEFLATE's bound on 8-bit samples.
constexpr double kMaxExpansion = 1032;
constexpr double kMaxTrustedDecode = 256.0 * 1024 * 1024;

} // namespace

std::shared_ptr<const Texture> Texture::load(const std::string &path, bool raw) {
    check_png_is_complete(path);
    check_exr_header_fits(path);
    auto input = OIIO::ImageInput::open(path);
    if (!input) fail(PPM_ERROR_IO, "texture '" + path + "': " + OIIO::geterror());
    const OIIO::ImageSpec &spec = input->spec();
    const long long pixels = static_cast<long long>(spec.width) * spec.height;
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) invalid_argument("texture '" + path + "' is empty");
    if (pixels > (1ll << 28))
        invalid_argument("texture '" + path + "' has " + std::to_string(pixels) +
                         " pixels, more than the limit of 2^28");
    // A header can claim any size: the decoded image must be one the file's bytes can hold,
    // so that a few bytes never make us allocate gigabytes.
    struct stat info {};
    const double file_bytes = stat(path.c_str(), &info) == 0 ? static_cast<double>(info.st_size) : 0;
    const double decoded_bytes = static_cast<double>(pixels) * spec.nchannels * spec.format.size();
    if (decoded_bytes > kMaxTrustedDecode && decoded_bytes > kMaxExpansion * std::max(file_bytes, 1.0))
        fail(PPM_ERROR_PARSE, "texture '" + path + "': its header claims " + std::to_string(spec.width) + " x " +
                                  std::to_string(spec.height) + " pixels, more than its " +
                                  std::to_string(static_cast<long long>(file_bytes)) + " bytes can hold");
    const int channels = std::min(spec.nchannels, 3);
    std::vector<float> data, rgb;
    allocate_or_fail("texture '" + path + "' of " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                         " pixels",
                     static_cast<std::uint64_t>(pixels) * (channels + 3) * sizeof(float), [&] {
                         data.resize(static_cast<size_t>(pixels) * channels);
                         rgb.resize(static_cast<size_t>(pixels) * 3);
                     });
    if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, data.data()))
        fail(PPM_ERROR_IO, "texture '" + path + "': " + input->geterror());
    const bool srgb = !raw && is_srgb_encoded(spec);
    for (long long i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) {
            const float value = data[i * channels + std::min(c, channels - 1)];
            if (!std::isfinite(value) || value < 0)
                invalid_argument("texture '" + path + "' has a NaN, infinite or negative value at pixel (" +
                                 std::to_string(i % spec.width) + ", " + std::to_string(i / spec.width) + ")");
            rgb[i * 3 + c] = srgb ? static_cast<float>(srgb_to_linear(std::min(value, 1.0f))) : value;
        }
    return std::make_shared<Texture>(spec.width, spec.height, std::move(rgb), path);
}

Texture::Texture(int width, int height, std::vector<float> rgb, std::string name)
    : width_(width), height_(height), rgb_(std::move(rgb)), name_(std::move(name)) {
    if (width <= 0 || height <= 0 || rgb_.size() != static_cast<size_t>(width) * height * 3)
        invalid_argument("texture '" + name_ + "': size does not match its data");
    for (float value : rgb_) max_value_ = std::max(max_value_, value);
}

namespace {

// Texel index i wrapped into [0, n).
long wrap_index(long i, long n, TextureWrap wrap) {
    switch (wrap) {
    case TextureWrap::Clamp: return std::clamp(i, 0l, n - 1);
    case TextureWrap::Mirror: {
        long m = i % (2 * n);
        if (m < 0) m += 2 * n;
        return m < n ? m : 2 * n - 1 - m;
    }
    case TextureWrap::Repeat:
    default: {
        const long m = i % n;
        return m < 0 ? m + n : m;
    }
    }
}

// Moves a coordinate by whole periods of the wrap (1 for repeat, 2 for mirror) so that large
// coordinates keep their precision; clamp only needs it bounded.
double reduce(double u, TextureWrap wrap) {
    switch (wrap) {
    case TextureWrap::Clamp: return std::clamp(u, -1.0, 2.0);
    case TextureWrap::Mirror: return u - 2 * std::floor(u / 2);
    case TextureWrap::Repeat:
    default: return u - std::floor(u);
    }
}

} // namespace

Rgb Texture::texel(long x, long y, TextureWrap wrap) const {
    x = wrap_index(x, width_, wrap);
    y = wrap_index(y, height_, wrap);
    const float *p = &rgb_[(static_cast<size_t>(y) * width_ + x) * 3];
    return {p[0], p[1], p[2]};
}

Rgb Texture::lookup(double u, double v, TextureFilter filter, TextureWrap wrap) const {
    if (!std::isfinite(u) || !std::isfinite(v)) return texel(0, 0, wrap);
    u = reduce(u, wrap);
    v = reduce(v, wrap);
    if (filter == TextureFilter::Nearest)
        return texel(static_cast<long>(std::floor(u * width_)), static_cast<long>(std::floor(v * height_)), wrap);
    // Texel centres sit at half-integer positions.
    const double x = u * width_ - 0.5, y = v * height_ - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const long x0 = static_cast<long>(fx), y0 = static_cast<long>(fy);
    const double ax = x - fx, ay = y - fy;
    return texel(x0, y0, wrap) * ((1 - ax) * (1 - ay)) + texel(x0 + 1, y0, wrap) * (ax * (1 - ay)) +
           texel(x0, y0 + 1, wrap) * ((1 - ax) * ay) + texel(x0 + 1, y0 + 1, wrap) * (ax * ay);
}

} // namespace ppm
