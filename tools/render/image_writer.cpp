// SPDX-License-Identifier: Apache-2.0
#include "image_writer.h"

#include <ppm/ppm.h>

#include <stdexcept>

namespace ppm_render {

void check_image_format(const std::string &path) {
    if (ppm_image_check_path(path.c_str()) != PPM_OK) throw std::runtime_error(ppm_last_error_message());
}

void write_image_atomically(const std::string &path, const Image &image, double exposure) {
    std::vector<ppm_image_layer> layers;
    for (const Layer &layer : image.layers) layers.push_back(ppm_image_layer{layer.name.c_str(), layer.data.data()});
    if (ppm_image_write(path.c_str(), image.radiance.data(), static_cast<uint32_t>(image.width),
                        static_cast<uint32_t>(image.height), layers.data(), layers.size(), exposure) != PPM_OK)
        throw std::runtime_error(ppm_last_error_message());
}

} // namespace ppm_render
