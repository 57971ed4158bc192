// SPDX-License-Identifier: Apache-2.0
// ppm-bench's data files (the teapot of the default --bpt, the chart script) live in the data
// folder beside the executable, PPM_BENCH_DATA_FROM_EXE from its directory (../share/ppm):
// installed, that is <prefix>/share/ppm; in the build tree, tools/bench/CMakeLists.txt copies
// them to build/tools/share/ppm. So no path of the build machine is baked into the binary.
#pragma once

#include <string>

namespace bench {

// <directory of the executable>/PPM_BENCH_DATA_FROM_EXE/name, whether or not it exists.
std::string data_file(const std::string &name);

// `path` if given (not empty), otherwise data_file(name), which must then exist: a
// std::runtime_error names the path searched and tells to pass `option`.
std::string input_or_data_file(const std::string &path, const std::string &name, const std::string &option);

} // namespace bench
