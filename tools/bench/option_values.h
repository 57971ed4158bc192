// Strict parsing of command-line option values, shared by the subcommands: a value is taken
// only if all of it parses and lies in the stated range, so "--rays 2k" is an error, not 2.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstring>
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

enum class ParseResult { run, help, error };

// Prints "<command>: <option> '<value>': expected <expected>" and returns false.
bool report_bad_value(const char *command, const std::string &option, const std::string &value, const char *expected);

enum class OptionMatch { taken, invalid, other };

// The options of the model and its ray sets that every subcommand shares, for any options
// struct with these members: bpt_path, rays, width, height, min_seconds, seed. `other` leaves
// the option to the caller.
template <class Options>
OptionMatch apply_ray_set_option(const char *command, const std::string &option, const std::string &value, Options &o) {
    auto bad = [&](const char *expected) {
        report_bad_value(command, option, value, expected);
        return OptionMatch::invalid;
    };
    long long n = 0;
    if (option == "--bpt") {
        o.bpt_path = value;
    } else if (option == "--rays") {
        if (!parse_integer(value, 0, 100000000, n)) return bad("an integer in [0, 1e8]");
        o.rays = size_t(n);
    } else if (option == "--width" || option == "--height") {
        if (!parse_integer(value, 0, 16384, n)) return bad("an integer in [0, 16384]");
        (option == "--width" ? o.width : o.height) = int(n);
    } else if (option == "--min-time") {
        if (!parse_double(value, 0, 60, o.min_seconds)) return bad("seconds in [0, 60]");
    } else if (option == "--seed") {
        if (!parse_integer(value, 0, INT64_MAX, n)) return bad("a non-negative integer");
        o.seed = uint64_t(n);
    } else {
        return OptionMatch::other;
    }
    return OptionMatch::taken;
}

// Reads every option from argv[first] on, handing each to apply(option, value), which
// reports its own errors and returns false on one. -h or --help ends the reading with
// `help`; a missing value is reported as "<command>: <option> needs a value".
template <class Apply> ParseResult read_options(const char *command, int argc, char **argv, int first, Apply &&apply) {
    for (int i = first; i < argc; ++i) {
        if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help")) return ParseResult::help;
        std::string option, value;
        if (!read_option(argc, argv, i, option, value)) {
            std::fprintf(stderr, "%s: %s needs a value\n", command, option.c_str());
            return ParseResult::error;
        }
        if (!apply(option, value)) return ParseResult::error;
    }
    return ParseResult::run;
}

} // namespace bench
