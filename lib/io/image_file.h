// SPDX-License-Identifier: Apache-2.0
// Writes images through OpenImageIO, atomically: encoded in memory, then written by
// write_file_atomically, so a viewer or a crash sees the previous image or the new one, never
// half of one. EXR, HDR and PFM get linear float radiance (EXR also extra single-channel
// layers); every other format 8-bit sRGB, scaled by 2^exposure.
#pragma once

#include <string>
#include <vector>

namespace ppm {

struct ImageLayer {
    std::string name;  // channel name in the EXR ("radius", "photons")
    const float *data; // one float per pixel
};

// True for extensions written as linear float (EXR, HDR, PFM).
bool is_float_image_format(const std::string &path);

// Throws ppm::Error(INVALID_ARGUMENT) naming the path when it has no extension or OpenImageIO
// has no writer for it that can write to memory.
void check_image_format(const std::string &path);

// `radiance`: linear RGB, 3 floats per pixel, rows from the top. Throws INVALID_ARGUMENT (bad
// format or size) or IO naming the path and the reason.
void write_image(const std::string &path, const float *radiance, int width, int height,
                 const std::vector<ImageLayer> &layers, double exposure);

} // namespace ppm
