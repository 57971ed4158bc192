#include "option_values.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace bench {

bool parse_integer(const std::string &text, long long low, long long high, long long &out) {
    if (text.empty()) return false;
    char *end = nullptr;
    errno = 0;
    const long long value = std::strtoll(text.c_str(), &end, 10);
    if (errno != 0 || *end != '\0' || value < low || value > high) return false;
    out = value;
    return true;
}

bool parse_double(const std::string &text, double low, double high, double &out) {
    if (text.empty()) return false;
    char *end = nullptr;
    errno = 0;
    const double value = std::strtod(text.c_str(), &end);
    if (errno != 0 || *end != '\0' || !std::isfinite(value) || value < low || value > high) return false;
    out = value;
    return true;
}

std::vector<std::string> split_list(const std::string &text) {
    std::vector<std::string> items;
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) items.push_back(item);
    return items;
}

bool parse_integer_list(const std::string &text, long long low, long long high, std::vector<int> &out) {
    out.clear();
    if (text == "none") return true;
    for (const std::string &item : split_list(text)) {
        long long n = 0;
        if (!parse_integer(item, low, high, n)) return false;
        out.push_back(int(n));
    }
    return true;
}

bool read_option(int argc, char **argv, int &i, std::string &option, std::string &value) {
    option = argv[i];
    const size_t equals = option.find('=');
    if (equals != std::string::npos) {
        value = option.substr(equals + 1);
        option.resize(equals);
        return true;
    }
    if (i + 1 >= argc) return false;
    value = argv[++i];
    return true;
}

bool report_bad_value(const char *command, const std::string &option, const std::string &value, const char *expected) {
    std::fprintf(stderr, "%s: %s '%s': expected %s\n", command, option.c_str(), value.c_str(), expected);
    return false;
}

} // namespace bench
