// `ppm-bench targets`: checks the exact intersector's speed and memory targets against the
// uniform mesh in Embree and CGAL, timing the methods in interleaved rounds.
#pragma once

namespace bench {

// argv[first..argc) are the subcommand's options. Returns the process exit code:
// 0 success (whatever the verdicts), 1 usage error, 2 runtime error.
int run_targets_command(int argc, char **argv, int first);

} // namespace bench
