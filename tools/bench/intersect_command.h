// SPDX-License-Identifier: Apache-2.0
// `ppm-bench intersect`: builds every requested structure, traces the ray sets, reports.
#pragma once

#include "intersect_args.h"

namespace bench {

// Returns the process exit code: 0 success, 1 no rays to trace, 2 runtime error.
int run_intersect_command(IntersectOptions options);

} // namespace bench
