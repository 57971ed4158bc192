#include "image_writer.h"

#include "atomic_write.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ppm_render {

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

bool is_float_format(const std::string &path) {
    const std::string ext = lower_extension(path);
    return ext == "exr" || ext == "hdr" || ext == "pfm";
}

void check_image_format(const std::string &path) {
    if (lower_extension(path).empty())
        throw std::runtime_error(path + ": no file extension to tell the image format (.exr, .png, ...)");
    const auto out = OIIO::ImageOutput::create(path);
    if (!out) throw std::runtime_error(path + ": OpenImageIO cannot write this format: " + OIIO::geterror());
    if (!out->supports("ioproxy"))
        throw std::runtime_error(path + ": OpenImageIO cannot write this format to memory, which atomic writing needs");
}

// The image is encoded in memory and written by write_bytes_atomically, which checks every
// write, the sync and the close: OpenImageIO ignores a failure to close its file, so letting it
// write the temporary file could rename a truncated image over a good one.
void write_image_atomically(const std::string &path, const Image &image, double exposure) {
    check_image_format(path);
    const std::string ext = lower_extension(path);
    const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw std::runtime_error(path + ": OpenImageIO cannot write this format: " + OIIO::geterror());
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    bool ok = out->set_ioproxy(&memory);

    if (is_float_format(path)) {
        const bool with_layers = ext == "exr" && !image.layers.empty();
        const int channels = 3 + (with_layers ? static_cast<int>(image.layers.size()) : 0);
        OIIO::ImageSpec spec(image.width, image.height, channels, OIIO::TypeDesc::FLOAT);
        spec.channelnames = {"R", "G", "B"};
        if (with_layers)
            for (const Layer &layer : image.layers) spec.channelnames.push_back(layer.name);
        spec.attribute("oiio:ColorSpace", "linear");
        spec.attribute("compression", "zip");
        std::vector<float> pixels_out(pixels * channels);
        for (std::size_t p = 0; p < pixels; ++p) {
            for (int c = 0; c < 3; ++c) pixels_out[p * channels + c] = image.radiance[p * 3 + c];
            for (int l = 3; l < channels; ++l) pixels_out[p * channels + l] = image.layers[l - 3].data[p];
        }
        ok = ok && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels_out.data());
    } else {
        OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", "sRGB");
        const float scale = static_cast<float>(std::exp2(exposure));
        std::vector<unsigned char> pixels_out(pixels * 3);
        for (std::size_t i = 0; i < pixels * 3; ++i)
            pixels_out[i] = static_cast<unsigned char>(std::lround(255.0f * linear_to_srgb(image.radiance[i] * scale)));
        ok = ok && out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, pixels_out.data());
    }
    const std::string error = ok ? std::string() : out->geterror();
    ok = out->close() && ok;
    out.reset();
    if (!ok || encoded.empty())
        throw std::runtime_error(
            path + ": cannot encode the image: " + (error.empty() ? std::string("unknown error") : error));
    write_bytes_atomically(path, encoded.data(), encoded.size());
}

} // namespace ppm_render
