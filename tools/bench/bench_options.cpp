// SPDX-License-Identifier: Apache-2.0
#include "bench_options.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace bench {

namespace {

std::string format(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

template <class T> CLI::Option *add_list(CLI::App &app, const std::string &name, std::vector<T> &out, T low, T high,
                                         bool none_allowed, const std::string &expected, const std::string &help) {
    auto parse = [&out, name, low, high, none_allowed, expected](const std::string &value) {
        const CLI::ValidationError bad(name, "'" + value + "': expected " + expected);
        out.clear();
        if (none_allowed && value == "none") return;
        std::istringstream in(value);
        for (std::string item; std::getline(in, item, ',');) {
            if (item.empty()) continue;
            T x{};
            // !(in range) rather than (out of range): NaN is out.
            if (!CLI::detail::lexical_cast(item, x) || !(x >= low && x <= high)) throw bad;
            out.push_back(x);
        }
        if (out.empty() && !none_allowed) throw bad;
    };
    return app.add_option_function<std::string>(name, parse, help)->type_name("LIST");
}

} // namespace

CLI::Option *add_number_list(CLI::App &app, const std::string &name, std::vector<int> &out, int low, int high,
                             bool none_allowed, const std::string &expected, const std::string &help) {
    return add_list(app, name, out, low, high, none_allowed, expected, help);
}

CLI::Option *add_number_list(CLI::App &app, const std::string &name, std::vector<double> &out, double low, double high,
                             bool none_allowed, const std::string &expected, const std::string &help) {
    return add_list(app, name, out, low, high, none_allowed, expected, help);
}

CLI::Validator real_in(double low, double high) {
    const std::string range = "[" + format(low) + ", " + format(high) + "]";
    return CLI::Validator(
        [low, high, range](std::string &input) {
            double x = 0;
            if (CLI::detail::lexical_cast(input, x) && x >= low && x <= high) return std::string();
            return "'" + input + "': expected a number in " + range;
        },
        "");
}

} // namespace bench
