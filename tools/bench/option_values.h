// Strict parsing of command-line option values, shared by the subcommands: a value is taken
// only if all of it parses and lies in the stated range, so "--rays 2k" is an error, not 2.
#pragma once

#include <string>
#include <vector>

namespace bench {

bool parse_integer(const std::string &text, long long low, long long high, long long &out);
bool parse_double(const std::string &text, double low, double high, double &out);

// The items of a comma-separated list; empty items are dropped.
std::vector<std::string> split_list(const std::string &text);

// A comma-separated list of integers in [low, high]; "none" gives an empty list.
bool parse_integer_list(const std::string &text, long long low, long long high, std::vector<int> &out);

// Reads the option at argv[i] and its value, written "--name=value" or "--name value" (then i
// moves past the value). False if the value is missing.
bool read_option(int argc, char **argv, int &i, std::string &option, std::string &value);

} // namespace bench
