// SPDX-License-Identifier: Apache-2.0
// A method's trace judged against the reference's truth for the same rays.
#pragma once

#include "method.h"
#include "reference_truth.h"

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

// Distance (relative to the diagonal) beyond which a hit is not on the surface the reference
// found: see statistics_definitions().
constexpr double false_hit_distance = 1e-3;

// What one ray's answer was, against the reference.
enum class Outcome : uint8_t {
    correct,   // matched the ray's first surface, or a correct miss
    ambiguous, // matched only a tangent / too-shallow root, or missed a ray that has only such
               // roots: anything goes there
    miss,      // the reference has a robust root, the method reports nothing
    false_hit, // a hit on no surface the ray meets first (see statistics_definitions())
    undecided  // the reference hit its work bound: left out
};

struct Stats {
    size_t rays = 0, undecided = 0;
    size_t reference_hits = 0, ambiguous = 0; // truth kinds
    size_t hits = 0, misses = 0, false_hits = 0, matched = 0;
    size_t over_tolerance = 0;                     // matched with |dt| above the given accuracy bound
    double dt_median = 0, dt_p999 = 0, dt_max = 0; // |dt| / diagonal over matched hits
    double ng_median = 0, ng_p999 = 0, ng_max = 0; // geometric normal error, degrees
    double ns_median = 0, ns_max = 0;              // shading normal error, degrees

    size_t decided() const { return rays - undecided; }
    double miss_rate() const { return reference_hits ? double(misses) / double(reference_hits) : 0.0; }
    double false_hit_rate() const { return decided() ? double(false_hits) / double(decided()) : 0.0; }
};

// Judges ray i of `rays` (unit directions); on a hit, *dt (relative to the diagonal) and
// *match are set to the hit's distance from the reference root it is attributed to and that
// root.
Outcome judge(const Trace &trace, const std::vector<ppm_ray> &rays, const Truth &truth, size_t i, double diagonal,
              double *dt = nullptr, const TruthRoot **match = nullptr);

// `accuracy` (relative to the diagonal; 0 = none) counts matched hits with a larger |dt|.
Stats evaluate(const Trace &trace, const std::vector<ppm_ray> &rays, const Truth &truth, double diagonal,
               double accuracy);

// Angle in degrees between two directions as unoriented lines; 90 if either is zero.
double normal_angle(const float *a, const float *b);

// Angle in degrees between normal `n` of a hit attributed to `match` (a root of ray i) and
// the nearest of the surface normals at that point: where patches meet at a seam, a corner
// or a crease, every patch's normal there is a right answer. -1 if the reference has none.
double normal_error(const float *n, const Truth &truth, size_t i, const TruthRoot *match, double diagonal);

// Definitions of every statistic, printed with the results.
std::string statistics_definitions();

} // namespace bench
