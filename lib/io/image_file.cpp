// SPDX-License-Identifier: Apache-2.0
#include "io/image_file.h"

#include "core/error.h"
#include "io/atomic_file.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

namespace ppm {

namespace {

std::string lower_extension(const std::string &path) {
    const std::size_t slash = path.rfind('/');
    const std::size_t dot = path.rfind('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

// The sRGB transfer function (IEC 61966-2-1).
float linear_to_srgb(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

} // namespace

bool is_float_image_format(const std::string &path) {
    const std::string ext = lower_extension(path);
    return ext == "exr" || ext == "hdr" || ext == "pfm";
}

void check_image_format(const std::string &path) {
    if (lower_extension(path).empty())
        invalid_argument(path + ": no file extension to tell the image format (.exr, .png, ...)");
    const auto out = OIIO::ImageOutput::create(path);
    if (!out) invalid_argument(path + ": OpenImageIO cannot write this format: " + OIIO::geterror());
    if (!out->supports("ioproxy"))
        invalid_argument(path + ": OpenImageIO cannot write this format to memory, which atomic writing needs");
}

// The image is encoded in memory and written by write_file_atomically, which checks every
// write, the sync and the close: OpenImageIO ignores a failure to close its file, so letting it
// write the temporary file could rename a truncated image over a good one.
void write_image(const std::string &path, const float *radiance, int width, int height,
                 const std::vector<ImageLayer> &layers, double exposure) {
    check_image_format(path);
    if (width <= 0 || height <= 0 || static_cast<std::uint64_t>(width) * height > (std::uint64_t(1) << 28))
        invalid_argument(path + ": image size " + std::to_string(width) + " x " + std::to_string(height) +
                         " is not in 1 .. 2^28 pixels");
    if (!std::isfinite(exposure) || std::fabs(exposure) > 100)
        invalid_argument(path + ": exposure " + format_number(exposure) + " is not in [-100, 100] stops");
    const std::string ext = lower_extension(path);
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    auto out = OIIO::ImageOutput::create(path);
    if (!out) invalid_argument(path + ": OpenImageIO cannot write this format: " + OIIO::geterror());
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    bool ok = out->set_ioproxy(&memory);

    if (is_float_image_format(path)) {
        const bool with_layers = ext == "exr" && !layers.empty();
        const int channels = 3 + (with_layers ? static_cast<int>(layers.size()) : 0);
        OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
        spec.channelnames = {"R", "G", "B"};
        if (with_layers)
            for (const ImageLayer &layer : layers) spec.channelnames.push_back(layer.name);
        spec.attribute("oiio:ColorSpace", "linear");
        spec.attribute("compression", "zip");
        std::vector<float> pixels_out(pixels * channels);
        for (std::size_t p = 0; p < pixels; ++p) {
            for (int c = 0; c < 3; ++c) pixels_out[p * channels + c] = radiance[p * 3 + c];
            for (int l = 3; l < channels; ++l) pixels_out[p * channels + l] = layers[l - 3].data[p];
        }
        ok = ok && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels_out.data());
    } else {
        OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", "sRGB");
        const float scale = static_cast<float>(std::exp2(exposure));
        std::vector<unsigned char> pixels_out(pixels * 3);
        for (std::size_t i = 0; i < pixels * 3; ++i)
            pixels_out[i] = static_cast<unsigned char>(std::lround(255.0f * linear_to_srgb(radiance[i] * scale)));
        ok = ok && out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, pixels_out.data());
    }
    const std::string error = ok ? std::string() : out->geterror();
    ok = out->close() && ok;
    out.reset();
    if (!ok || encoded.empty())
        fail(PPM_ERROR_IO,
             path + ": cannot encode the image: " + (error.empty() ? std::string("unknown error") : error));
    write_file_atomically(path, encoded.data(), encoded.size());
}

} // namespace ppm
