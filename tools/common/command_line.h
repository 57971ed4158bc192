// SPDX-License-Identifier: Apache-2.0
// The command-line conventions of libppm's tools, on CLI11: `-h`/`--help` prints the usage
// and `--version` the library version, both with exit status 0; a usage error (an unknown
// option, a missing or malformed value) prints "TOOL: what" and a pointer to --help and
// gives exit status 1; runtime errors (bad input files, unwritable outputs) are the tool's
// own, with exit status 2.
#pragma once

#include <ppm/ppm.h>

#include <CLI/CLI.hpp>

#include <iostream>
#include <stdexcept>
#include <string>

namespace ppm_tools {

enum ExitStatus { kExitOk = 0, kExitUsage = 1, kExitRuntime = 2 };

// A usage error found after parsing (options that exclude each other, a value that only
// makes sense with another option); reported like CLI11's own.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// An application with the tools' help layout and the --version flag.
inline void configure(CLI::App &app, const std::string &footer) {
    app.set_version_flag(
        "--version", [] { return std::string(ppm_version_string()); }, "print the libppm version and exit");
    app.set_help_flag("-h,--help", "print this help and exit");
    app.footer(footer);
    app.get_formatter()->column_width(24);
    app.get_formatter()->label("REQUIRED", "(required)");
    app.get_formatter()->label("Excludes", "excludes");
}

inline int report_usage_error(const CLI::App &app, const std::string &what) {
    std::cerr << app.get_name() << ": " << what << "\n(" << app.get_name() << " --help lists the options)\n";
    return kExitUsage;
}

// Parses the command line. Returns -1 when the tool should go on, otherwise the exit status
// to return at once (0 after printing the help or version, 1 after a usage error).
inline int parse(CLI::App &app, int argc, char **argv) {
    try {
        app.parse(argc, argv);
        return -1;
    } catch (const CLI::CallForHelp &) {
        std::cout << app.help();
        return kExitOk;
    } catch (const CLI::CallForVersion &e) {
        std::cout << e.what() << "\n";
        return kExitOk;
    } catch (const CLI::ParseError &e) {
        return report_usage_error(app, e.what());
    }
}

} // namespace ppm_tools
