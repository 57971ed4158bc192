// SPDX-License-Identifier: Apache-2.0
// Option values of ppm-bench's subcommands that CLI11 (tools/common/command_line.h) does not
// check alone: comma-separated number lists and finite ranges of reals. A value is taken only
// if all of it parses and lies in range, so "--rays 2k" and "--angles 1e-3,x" are errors.
#pragma once

#include "common/command_line.h"

#include <string>
#include <vector>

namespace bench {

// A comma-separated list of numbers in [low, high] (empty items dropped) that replaces the
// default list; with `none_allowed`, "none" or an empty value gives an empty list, otherwise an
// empty list is an error. `expected` completes "--option 'value': expected ...".
CLI::Option *add_number_list(CLI::App &app, const std::string &name, std::vector<int> &out, int low, int high,
                             bool none_allowed, const std::string &expected, const std::string &help);
CLI::Option *add_number_list(CLI::App &app, const std::string &name, std::vector<double> &out, double low, double high,
                             bool none_allowed, const std::string &expected, const std::string &help);

// A real in [low, high]; unlike CLI::Range, it refuses NaN and prints the bounds as %g.
CLI::Validator real_in(double low, double high);

} // namespace bench
