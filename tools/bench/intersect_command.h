// `ppm-bench intersect`: builds every requested structure, traces the ray sets, reports.
#pragma once

namespace bench {

// argv[first..argc) are the subcommand's options. Returns the process exit code:
// 0 success, 1 usage error, 2 runtime error.
int run_intersect_command(int argc, char **argv, int first);

} // namespace bench
