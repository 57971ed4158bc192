// SPDX-License-Identifier: Apache-2.0
#include "image_writer.h"

#include <ppm/ppm.h>

#include "common/status.h"

namespace ppm_render {

void check_image_format(const std::string &path) { ppm_tools::check(ppm_image_check_path(path.c_str())); }

void write_image_atomically(const std::string &path, const Image &image, double exposure) {
    std::vector<ppm_image_layer> layers;
    for (const Layer &layer : image.layers) layers.push_back(ppm_image_layer{layer.name.c_str(), layer.data.data()});
    ppm_tools::check(ppm_image_write(path.c_str(), image.radiance.data(), static_cast<uint32_t>(image.width),
                                     static_cast<uint32_t>(image.height), layers.data(), layers.size(), exposure));
}

} // namespace ppm_render
