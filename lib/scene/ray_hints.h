// SPDX-License-Identifier: Apache-2.0
// What a caller knows about a ray before it is traced, so that a query can skip work. Hints
// never change an answer: a query that ignored them would return the same hit or the same
// occlusion. The scene turns them into Embree ray masks and the patch callbacks' skip of the
// root a ray starts on, and reads nothing else into them; what they mean to the caller (a
// shadow ray's light, a photon's last bounce) stays with the caller.
#pragma once

#include <ppm/ppm.h>

#include <cstdint>

namespace ppm {

struct RayHints {
    // The hit the ray was spawned from (spawn_ray), or null. A flat geometry is then hidden
    // from the ray by its mask, and a patch skips the root the ray starts on. May point to the
    // hit the query writes.
    const ppm_hit *leaving = nullptr;
    // A geometry the ray cannot meet within [tnear, tfar] (a shadow ray that stops short of the
    // light it runs to), or PPM_INVALID_ID. Skipped by its mask if it has a mask bit of its own
    // (Scene::prefer_mask_bit), otherwise tested as usual.
    uint32_t skip_geometry = PPM_INVALID_ID;
};

} // namespace ppm
