// SPDX-License-Identifier: Apache-2.0
// The benchmark's output: per-set tables on stdout, the markdown summary and stability
// tables, and the CSV the chart script reads.
#pragma once

#include "driver.h"

#include <cstdio>
#include <string>
#include <vector>

namespace bench {

// One table per ray set: every method's speed and accuracy.
void print_set_tables(std::FILE *out, const std::vector<RaySet> &sets, const std::vector<MethodResult> &runs);

// Markdown: one row per method with build, memory, speed on the random and camera rays and
// accuracy on them. Empty if neither set was traced.
std::string summary_markdown(const std::vector<RaySet> &sets, const std::vector<MethodResult> &runs);

// Markdown: miss rate and false-hit rate per ray set (columns) and method (rows).
std::string stability_markdown(const std::vector<RaySet> &sets, const std::vector<MethodResult> &runs);

// One row per (ray set, method). Throws on I/O errors.
void write_csv(const std::string &path, const std::vector<RaySet> &sets, const std::vector<MethodResult> &runs);

// Writes `text` to `path`. Throws on I/O errors.
void write_text(const std::string &path, const std::string &text);

} // namespace bench
