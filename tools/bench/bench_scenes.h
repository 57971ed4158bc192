// SPDX-License-Identifier: Apache-2.0
// The renderer's benchmark scenes, built through the public API:
//  - "smallppm": Hachisuka's smallppm Cornell box (walls are spheres of radius 1e5, a mirror
//    and a glass sphere, a small diffuse one, a point light of 2500 W/sr), same camera;
//  - "teapot-glass": the Newell teapot in glass standing in a diffuse Cornell box lit by an
//    area light on the ceiling.
#pragma once

#include <ppm/ppm.h>

#include "common/handle.h"

#include <string>

namespace bench {

struct BenchScene {
    ppm_tools::Scene scene;
    ppm_camera camera{};
};

// Throws std::runtime_error for an unknown name or a failed call. `teapot_path` is the .bpt.
BenchScene build_bench_scene(ppm_context context, const std::string &name, const std::string &teapot_path, int width,
                             int height);

} // namespace bench
