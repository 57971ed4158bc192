// SPDX-License-Identifier: Apache-2.0
// Image textures: any file OpenImageIO reads, held as linear RGB floats and looked up with
// Mitsuba 3's `bitmap` filters (bilinear, nearest) and wrap modes (repeat, mirror, clamp).
//
// Colour: 8- and 16-bit integer images are taken as sRGB-encoded (PNG, JPEG, ...) and decoded
// to linear with the sRGB transfer function, unless the file's `oiio:ColorSpace` says linear;
// float and half images (EXR, HDR) are taken as linear unless it says sRGB. Grey images are
// spread to RGB; alpha is ignored.
//
// With `raw` (Mitsuba's bitmap `raw` = true) the stored values are taken as they are: no
// sRGB decoding for any format.
//
// Orientation follows Mitsuba 3: texture coordinate v = 0 is the image's top row and u = 0
// its left column.
#pragma once

#include "math/rgb.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace ppm {

// Mitsuba 3 bitmap `filter_type`: bilinear between texel centres (at half-integer positions
// u * width, v * height), or the texel under (u, v).
enum class TextureFilter : uint8_t { Bilinear, Nearest };
// Mitsuba 3 bitmap `wrap_mode` (applied to texel indices, as Dr.Jit's texture does): repeat
// tiles the image, mirror tiles it flipping every other tile, clamp repeats the edge texels.
enum class TextureWrap : uint8_t { Repeat, Mirror, Clamp };

class Texture {
public:
    // Throws ppm::Error: IO when the file cannot be opened or decoded (OpenImageIO's message
    // and the path), INVALID_ARGUMENT for an empty image, one over 2^28 pixels, or pixels
    // that are NaN, infinite or negative.
    static std::shared_ptr<const Texture> load(const std::string &path, bool raw = false);
    // From linear RGB values, row-major from the top row (tests and procedural textures).
    Texture(int width, int height, std::vector<float> rgb, std::string name);

    Rgb lookup(double u, double v, TextureFilter filter = TextureFilter::Bilinear,
               TextureWrap wrap = TextureWrap::Repeat) const;
    // Pixel (x, y) from the top-left, wrapped into the image.
    Rgb pixel(long x, long y) const { return texel(x, y, TextureWrap::Repeat); }

    int width() const { return width_; }
    int height() const { return height_; }
    const std::string &name() const { return name_; }
    // Largest channel value: textures scale reflectances, which must stay <= 1.
    float max_value() const { return max_value_; }

private:
    Rgb texel(long x, long y, TextureWrap wrap) const; // wraps x, y

    int width_ = 0, height_ = 0;
    std::vector<float> rgb_;
    std::string name_;
    float max_value_ = 0;
};

// sRGB electro-optical transfer function (IEC 61966-2-1): encoded value in [0, 1] to linear.
double srgb_to_linear(double encoded);

} // namespace ppm
