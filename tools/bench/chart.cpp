// SPDX-License-Identifier: Apache-2.0
#include "chart.h"

#include "data_files.h"

#include <cstdio>
#include <cstdlib>
#include <sys/stat.h>
#include <vector>

namespace bench {

namespace {

// The argument quoted for /bin/sh.
std::string quoted(const std::string &text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

bool exists(const std::string &path) {
    struct stat st;
    return stat(path.c_str(), &st) == 0;
}

} // namespace

bool draw_chart(const std::string &csv_path, const std::string &dir) {
    const std::string script = data_file("plot_bench.py");
    const std::string by_hand = "python3 " + quoted(script) + " --csv " + quoted(csv_path) + " --out " + quoted(dir);
    if (!exists(script)) {
        std::fprintf(stderr, "ppm-bench intersect: note: no chart: %s is missing; with the script, run: %s\n",
                     script.c_str(), by_hand.c_str());
        return false;
    }
    // PPM_BENCH_PYTHON first, then python3 on the PATH, then the system's (Debian's
    // python3-matplotlib installs for /usr/bin/python3, which a pyenv or venv may hide).
    std::vector<std::string> candidates;
    if (const char *env = std::getenv("PPM_BENCH_PYTHON")) candidates.push_back(env);
    candidates.push_back("python3");
    candidates.push_back("/usr/bin/python3");
    for (const std::string &python : candidates) {
        const std::string probe = quoted(python) + " -c 'import matplotlib' >/dev/null 2>&1";
        if (std::system(probe.c_str()) != 0) continue;
        const std::string command =
            quoted(python) + " " + quoted(script) + " --csv " + quoted(csv_path) + " --out " + quoted(dir);
        std::fprintf(stderr, "chart: %s\n", command.c_str());
        if (std::system(command.c_str()) == 0) return true;
        std::fprintf(stderr, "ppm-bench intersect: note: the chart script failed (command above)\n");
        return false;
    }
    std::fprintf(stderr,
                 "ppm-bench intersect: note: no chart drawn: no python3 with matplotlib found (tried "
                 "$PPM_BENCH_PYTHON, python3, /usr/bin/python3; on Debian: apt-get install python3-matplotlib).\n"
                 "  The CSV is written; draw the chart later with: %s\n",
                 by_hand.c_str());
    return false;
}

} // namespace bench
