// SPDX-License-Identifier: Apache-2.0
// The image of a render (radiance and extra layers) as ppm-render and ppm-merge write it,
// through libppm's atomic image writer (ppm_image_write).
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

// Throws std::runtime_error with libppm's message (naming the path) for a format it cannot write.
void check_image_format(const std::string &path);

// Throws std::runtime_error naming the path and the reason.
void write_image_atomically(const std::string &path, const Image &image, double exposure);

} // namespace ppm_render
