// SPDX-License-Identifier: Apache-2.0
// Rays on which libppm's exact intersector disagrees with the reference: a miss, a false hit,
// or a hit farther from the reference root than the scene tolerance promises. Each is a
// candidate bug in libppm (or in the reference) and is listed for reproduction.
#pragma once

#include "driver.h"

#include <cstdio>
#include <vector>

namespace bench {

// `exact`: a run with its one-thread traces kept (normally the exact method's; any method's
// with --explain). Prints counts per set and up to `max_listed` rays per set with %.17g
// coordinates and the reference's roots.
void print_suspects(std::FILE *out, const std::vector<RaySet> &sets, const MethodResult &exact, double diagonal,
                    size_t max_listed);

} // namespace bench
