// SPDX-License-Identifier: Apache-2.0
// The records the renderer's parts hand each other: what a camera path leaves at a slot, what
// a photon needs of it, and a photon landing where it may be gathered.
#pragma once

#include "material/bsdf.h"
#include "math/frame.h"
#include "math/rgb.h"
#include "math/vec3.h"

namespace ppm {

// What a camera path left at one slot (a pixel in SPPM, a split path in PPM) in one pass.
struct VisiblePoint {
    bool valid = false;
    Vec3 p;
    Vec3 normal; // geometric normal on the camera's side: photons from behind are rejected
    double p_error = 0;
    Frame frame; // shading frame
    Vec3 wo_local;
    Bsdf bsdf;  // black until a point is stored
    Rgb weight; // camera path throughput up to this point
    double initial_r2 = 0;
};

// What a photon landing within a hit point's radius needs of its visible point, packed into
// one cache line (a VisiblePoint is about 250 bytes, and the photon pass reads these at
// random). The normals only decide sides and cosines, so single precision does.
struct alignas(64) GatherPoint {
    float normal[3];         // geometric, on the camera's side: photons from behind are rejected
    float shading_normal[3]; // on the side of wo: a photon's cos(wi) is -dot(it, direction)
    FixedWoLobe lobe;        // the camera path's weight times the BSDF at this wo

    static double dot(const float n[3], const Vec3 &d) { return n[0] * d.x + n[1] * d.y + n[2] * d.z; }
    static bool shading_is_geometric(const GatherPoint &g) {
        return g.normal[0] == g.shading_normal[0] && g.normal[1] == g.shading_normal[1] &&
               g.normal[2] == g.shading_normal[2];
    }
};
static_assert(sizeof(GatherPoint) == 64, "a gather point fills one cache line");

// What a photon needs of a visible point whose lobe depends on the whole of wi (a rough
// conductor, FixedWoLobe::needs_full_eval): f = bsdf.eval(wo_local, frame.to_local(wi)).
// Kept aside from the gather points (a few hundred bytes, only for scenes that have such
// lobes).
struct FullLobe {
    Frame frame;
    Vec3 wo_local;
    Bsdf bsdf;
};

// A photon arriving at a surface where it may be gathered, buffered so that a batch of them
// can be gathered in spatial order (hit points then stay in cache).
struct PhotonHit {
    Vec3 position;
    Vec3 direction; // of travel, unit
    Rgb flux;
    float cos_landing = 1; // |direction . geometric normal| where the photon landed
};

} // namespace ppm
