// SPDX-License-Identifier: Apache-2.0
// The C API of image files (ppm.h, "Images").
#include "api/api_support.h"
#include "io/atomic_file.h"
#include "io/image_file.h"

#include <vector>

using namespace ppm::api;

extern "C" {

ppm_status ppm_image_check_path(const char *path) {
    return guarded(nullptr, [&] {
        require(path, "path");
        ppm::check_image_format(path);
        ppm::check_folder_writable(path);
    });
}

ppm_status ppm_image_write(const char *path, const float *radiance, uint32_t width, uint32_t height,
                           const ppm_image_layer *layers, size_t layer_count, double exposure) {
    return guarded(nullptr, [&] {
        require(path, "path");
        require(radiance, "radiance");
        if (layer_count > 0) require(layers, "layers");
        if (width > (1u << 28) || height > (1u << 28))
            ppm::invalid_argument(std::string(path) + ": image size " + std::to_string(width) + " x " +
                                  std::to_string(height) + " is not in 1 .. 2^28 pixels");
        std::vector<ppm::ImageLayer> list;
        for (size_t i = 0; i < layer_count; ++i) {
            require(layers[i].name, "layers[i].name");
            require(layers[i].data, "layers[i].data");
            list.push_back(ppm::ImageLayer{layers[i].name, layers[i].data});
        }
        ppm::write_image(path, radiance, static_cast<int>(width), static_cast<int>(height), list, exposure);
    });
}

} // extern "C"
