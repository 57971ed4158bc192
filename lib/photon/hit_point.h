// SPDX-License-Identifier: Apache-2.0
// Hit points (SPPM's visible points) as the photon pass sees them, and the visitor type the
// two search structures (HitPointTree, HitPointGrid) call for every hit point a photon lands in.
#pragma once

#include "math/vec3.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace ppm {

// Where a camera path stopped on a non-specular surface, with the gather radius of its pixel.
// The renderer keeps the rest (normal, BSDF, path weight) in a parallel array with the same
// indices, one entry per pixel (slot), so a slot whose path found no such surface holds an
// absent hit point: r2 < 0, which the search structures skip and no photon finds.
struct HitPoint {
    Vec3 position;
    double r2 = -1; // gather radius squared, finite; >= 0 when present
    bool present() const { return r2 >= 0; }
};

// The one definition of "the photon is inside the hit point's radius", shared by the search
// structures and the tests so they agree on photons exactly at the radius (they count).
inline double distance2(const Vec3 &a, const Vec3 &b) {
    const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    return dx * dx + dy * dy + dz * dz;
}
inline bool within_radius(double dist2, double r2) { return dist2 <= r2; }

// The box around the present points of an array, their largest r2 and their number.
struct HitPointBounds {
    Box3 box;
    double max_r2 = 0;
    std::size_t present = 0;

    void add(const HitPoint &p) {
        if (!p.present()) return;
        box.extend(p.position);
        max_r2 = std::max(max_r2, p.r2);
        ++present;
    }
    void add(const HitPointBounds &b) {
        box.extend(b.box);
        max_r2 = std::max(max_r2, b.max_r2);
        present += b.present;
    }
};
// In parallel on the calling task arena's threads.
HitPointBounds measure_hit_points(const HitPoint *points, std::size_t count);

// Called once per hit point containing the photon, with the hit point's index in the array
// the structure was built from and its squared distance to the photon. A function pointer
// and a context rather than std::function: nothing is allocated per query.
struct HitPointVisitor {
    void (*visit)(void *context, std::uint32_t index, double dist2);
    void *context;

    void operator()(std::uint32_t index, double dist2) const { visit(context, index, dist2); }

    // Wraps any callable f(std::uint32_t index, double dist2); f must outlive the visitor.
    template <class F> static HitPointVisitor of(F &f) {
        return {[](void *c, std::uint32_t index, double dist2) {
                    (*static_cast<std::remove_reference_t<F> *>(c))(index, dist2);
                },
                const_cast<void *>(static_cast<const void *>(&f))};
    }
};

} // namespace ppm
