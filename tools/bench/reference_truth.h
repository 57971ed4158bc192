// SPDX-License-Identifier: Apache-2.0
// Ground truth of the benchmark: every ray of every set is answered by the independent
// long-double reference intersector of the tests (tools/reference/reference_intersector.*:
// world-space De Casteljau subdivision and long-double Newton, sharing no code with libppm).
#pragma once

#include "reference_intersector.h"

#include <ppm/ppm.h>

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

// What the reference says about one ray.
enum class TruthKind : uint8_t {
    none,      // no root, not even a tangent touch within 2e-9 of the diagonal
    hit,       // a robust root: the ray dips through the surface deeper than 1e-15 of the
               // diagonal, or crosses a collapsed edge; every method should hit it
    ambiguous, // only tangent touches or roots too shallow for double precision to resolve:
               // a hit (at one of them) and a miss are both right
    undecided  // the reference hit its work bound: the ray is left out of every statistic
};

// A reference root: every root of the ray in [tnear, tfar], in order of t (roots of several
// patches at one point, on a seam, are all kept).
struct TruthRoot {
    double t;        // along the ray; the ray's direction is unit, so a distance
    float normal[3]; // unit normal there (the limit normal at a collapsed edge)
    uint32_t patch;
    bool robust;
};

struct Truth {
    static constexpr uint32_t no_root = 0xFFFFFFFFu;
    std::vector<TruthKind> kind;        // per ray
    std::vector<uint32_t> first;        // roots of ray i: roots[first[i] .. first[i + 1])
    std::vector<uint32_t> first_robust; // index into roots of ray i's first robust root, or no_root
    std::vector<TruthRoot> roots;

    size_t size() const { return kind.size(); }
    const TruthRoot *begin(size_t i) const { return roots.data() + first[i]; }
    const TruthRoot *end(size_t i) const { return roots.data() + first[i + 1]; }
    const TruthRoot *robust(size_t i) const {
        return first_robust[i] == no_root ? nullptr : roots.data() + first_robust[i];
    }
};

// One line naming the reference and its settings, for the output.
std::string reference_description(const ref::Intersector &reference);

// The reference's answer for each ray, on `threads` threads.
Truth compute_truth(const ref::Intersector &reference, const std::vector<ppm_ray> &rays, int threads);

// Unit normal of a reference patch at (u, v), the limit normal where dS/du x dS/dv vanishes
// (evaluated a hair inside the patch). Returns false if no normal can be found.
bool reference_normal(const ref::Patch &patch, ref::real u, ref::real v, ref::real n[3]);

} // namespace bench
