// SPDX-License-Identifier: Apache-2.0
// One pass's records in the bidirectional modes: the stored light vertices and the state that
// the light half (vcm_integrator.cpp) hands the camera half (vcm_camera_paths.cpp).
#pragma once

#include "integrator/vcm/light_vertex_grid.h"
#include "integrator/vcm/vcm_mis.h"
#include "math/rgb.h"
#include "math/vec3.h"
#include "shading/render_scene.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace ppm {

// A non-specular vertex of a light subpath, kept for connections and merges.
struct VcmLightVertex {
    SurfacePoint sp; // wo_local points back along the subpath, towards the light
    Rgb throughput;  // the subpath's weight up to here (flux per light subpath)
    SubpathMis mis;
    std::uint32_t path_length = 0; // segments from the light
};

// One pass's shared state: written while the light subpaths are traced, then only read by
// the camera subpaths.
struct VcmPassState {
    MisFactors mis;
    double radius = 0;
    double pixel_area = 0;         // of one pixel on the plane at unit distance along the view axis
    int max_length = 0;            // segments of a full path: max_depth scattering vertices + 1
    bool light_tracing = false;    // light vertices connect to the camera (not through a thin lens)
    std::uint32_t light_paths = 0; // light subpaths this pass (RenderSettings::paths_per_pass)
    // The stored light vertices live in block_vertices; vertices[k] points at the k-th in
    // subpath order (one copy of them, not two: they are most of the pass's memory).
    std::vector<const VcmLightVertex *> vertices;
    std::vector<std::uint32_t> path_start; // light subpath i's vertices: [path_start[i], path_start[i + 1])
    LightVertexGrid grid;                  // over the vertices, when merging
    std::vector<Rgb> splat;                // per pixel: light tracing's sum
    std::vector<Vec3> points;              // the vertices' positions, for the grid
    // What merging reads of a light vertex, in the grid's order: a query reads its buckets'
    // records one after the other instead of whole vertices at random.
    struct MergeRecord {
        Vec3 arriving; // world direction towards where the light came from
        Rgb throughput;
        double dvcm = 0, dvm = 0;
        std::uint32_t path_length = 0;
        float cos_arriving = 1; // |arriving . geometric normal| where the light vertex lies
    };
    std::vector<MergeRecord> merge_records;
    // Per block of light subpaths while they are traced (vcm_integrator.cpp).
    std::vector<std::vector<VcmLightVertex>> block_vertices;
    std::vector<std::vector<std::uint32_t>> block_counts;
    std::vector<std::vector<std::pair<std::uint32_t, Rgb>>> block_splats;
};

} // namespace ppm
