// SPDX-License-Identifier: Apache-2.0
#include "scene/geometry.h"

#if defined(__SANITIZE_THREAD__)
#define PPM_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define PPM_TSAN 1
#endif
#endif
#ifdef PPM_TSAN
#include <sanitizer/tsan_interface.h>
#endif

namespace ppm {

#ifdef PPM_TSAN
namespace {
char embree_build_sync; // the synchronisation object of embree_build_joined: only its address is used
} // namespace
#endif

void write_embree_bounds(const Box3 &world, const EmbreeFrame &frame, RTCBounds &out) {
    const Vec3 lower = world.lower - frame.center - Vec3{1, 1, 1} * frame.box_padding;
    const Vec3 upper = world.upper - frame.center + Vec3{1, 1, 1} * frame.box_padding;
    // Round outwards: a box that shrank in the conversion could lose a grazing hit.
    out.lower_x = std::nextafter(static_cast<float>(lower.x), -INFINITY);
    out.lower_y = std::nextafter(static_cast<float>(lower.y), -INFINITY);
    out.lower_z = std::nextafter(static_cast<float>(lower.z), -INFINITY);
    out.upper_x = std::nextafter(static_cast<float>(upper.x), INFINITY);
    out.upper_y = std::nextafter(static_cast<float>(upper.y), INFINITY);
    out.upper_z = std::nextafter(static_cast<float>(upper.z), INFINITY);
#ifdef PPM_TSAN
    __tsan_release(&embree_build_sync);
#endif
}

void embree_build_joined() {
#ifdef PPM_TSAN
    __tsan_acquire(&embree_build_sync);
#endif
}

} // namespace ppm
