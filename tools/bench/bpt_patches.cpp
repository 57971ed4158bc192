// SPDX-License-Identifier: Apache-2.0
#include "bpt_patches.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace bench {

namespace {

// Whitespace-separated tokens with the line each came from, for error messages.
class Tokens {
public:
    Tokens(std::istream &in, const std::string &path) : in_(in), path_(path) {}

    double number(const char *what) {
        std::string token = next(what);
        char *end = nullptr;
        const double value = std::strtod(token.c_str(), &end);
        if (end == token.c_str() || *end != '\0' || !std::isfinite(value))
            fail(std::string("expected a finite number for ") + what + ", got '" + token + "'");
        return value;
    }

    [[noreturn]] void fail(const std::string &message) const {
        throw std::runtime_error(path_ + ":" + std::to_string(line_) + ": " + message);
    }

private:
    std::string next(const char *what) {
        std::string token;
        while (!(words_ >> token)) {
            std::string text;
            if (!std::getline(in_, text)) fail(std::string("file ends before ") + what);
            ++line_;
            words_.clear();
            words_.str(text);
        }
        return token;
    }

    std::istream &in_;
    std::string path_;
    std::istringstream words_;
    int line_ = 0;
};

} // namespace

std::vector<double> read_bpt_patches(const std::string &path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    Tokens tokens(in, path);
    const double count = tokens.number("the patch count");
    if (count < 1 || count > 1e7 || count != std::floor(count))
        tokens.fail("patch count must be an integer in [1, 10000000]");
    const size_t patch_count = static_cast<size_t>(count);
    std::vector<double> control_points;
    control_points.reserve(patch_count * 48);
    for (size_t p = 0; p < patch_count; ++p) {
        if (tokens.number("the u degree") != 3 || tokens.number("the v degree") != 3)
            tokens.fail("patch " + std::to_string(p) + " is not bicubic ('3 3')");
        for (int k = 0; k < 48; ++k) control_points.push_back(tokens.number("a coordinate"));
    }
    return control_points;
}

} // namespace bench
