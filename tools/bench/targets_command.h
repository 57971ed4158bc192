// SPDX-License-Identifier: Apache-2.0
// `ppm-bench targets`: checks the exact intersector's speed and memory targets against the
// uniform mesh in Embree and CGAL, timing the methods in interleaved rounds.
#pragma once

#include "targets_args.h"

namespace bench {

// Returns the process exit code: 0 success (whatever the verdicts), 2 runtime error.
int run_targets_command(TargetsOptions options);

} // namespace bench
