// Rays on which the exact intersector disagrees with every mesh by more than tessellation
// error explains: candidates for bugs in libppm (or in the baselines).
#pragma once

#include "method.h"

#include <cstdio>
#include <vector>

namespace bench {

// Classifies each ray of each set in which all mesh runs agree with each other:
//  - exact miss:      every mesh hits, the exact intersector misses;
//  - exact false hit: the exact intersector hits, every mesh misses;
//  - exact wrong t:   all hit, the meshes agree within 1e-3 diagonal, and the exact hit is
//                     off their hit by more than 1e-3 diagonal along the exact normal
//                     (|dt| |cos| > 1e-3 diagonal, as tessellation error is an offset along
//                     the normal).
// A case counts as explained when the exact or the finest mesh hit is grazing (|cos| < 0.05
// with the normal) or lies within 0.02 of a patch edge in (u, v) (free boundaries move with
// tessellation).
// Prints counts, up to `max_listed` unexplained rays per class with %.17g coordinates, and a
// sample of two explained ones per class.
void print_suspects(std::FILE *out, const std::vector<RaySet> &sets, const std::vector<MethodRun> &runs,
                    const MethodRun &exact, double diagonal, size_t max_listed);

} // namespace bench
