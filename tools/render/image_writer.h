// Writes the renderer's image through OpenImageIO, atomically: encoded in memory, written to a
// temporary file beside the target, synced and renamed over it. A viewer or a
// crash sees the previous image or the new one, never half of one.
#pragma once

#include <string>
#include <vector>

namespace ppm_render {

struct Layer {
    std::string name;        // channel name in the EXR ("radius", "photons")
    std::vector<float> data; // one float per pixel
};

struct Image {
    int width = 0, height = 0;
    std::vector<float> radiance; // linear RGB, 3 floats per pixel, rows from the top
    std::vector<Layer> layers;   // extra single-channel layers, EXR only
};

// True for extensions written as linear float (EXR, HDR, PFM); the rest get sRGB 8 bits.
bool is_float_format(const std::string &path);

// Throws std::runtime_error naming the path when OpenImageIO has no writer for its extension.
void check_image_format(const std::string &path);

// Throws std::runtime_error naming the path and OIIO's reason.
void write_image_atomically(const std::string &path, const Image &image, double exposure);

} // namespace ppm_render
