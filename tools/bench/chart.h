// SPDX-License-Identifier: Apache-2.0
// Runs plot_bench.py (tools/bench/, copied to the data folder: data_files.h) on the CSV when python3 with matplotlib is available.
#pragma once

#include <string>

namespace bench {

// Writes <dir>/intersect.png and <dir>/intersect.svg from the CSV. Returns false (after
// printing a note to stderr saying what is missing and the command to run by hand) when no
// python3 with matplotlib is found or the script fails.
bool draw_chart(const std::string &csv_path, const std::string &dir);

} // namespace bench
