// SPDX-License-Identifier: Apache-2.0
#include "io/bpt_reader.h"

#include "core/error.h"
#include "io/text_file.h"
#include "math/limits.h"

#include <cerrno>
#include <cstdlib>

namespace ppm {

namespace {

// Walks the text token by token, keeping the line number for messages.
class Tokens {
public:
    Tokens(const std::string &text, const std::string &name) : text_(text), name_(name) {}

    // Next token, or empty at the end of the text.
    std::string next() {
        if (at_end()) return {};
        const size_t start = pos_;
        while (pos_ < text_.size() && !is_space(text_[pos_]) && text_[pos_] != '#') ++pos_;
        last_token_line_ = line_;
        return text_.substr(start, pos_ - start);
    }

    // At the end, messages name the line of the last token: the line that is incomplete,
    // not the empty line after the final newline.
    bool at_end() {
        skip_space_and_comments();
        const bool end = pos_ >= text_.size();
        token_line_ = end ? last_token_line_ : line_;
        return end;
    }

    [[noreturn]] void error(const std::string &what) const {
        fail(PPM_ERROR_PARSE, name_ + ":" + std::to_string(token_line_) + ": " + what);
    }

    double number(const char *what) {
        const std::string token = next();
        if (token.empty()) error(std::string("file ends where ") + what + " was expected");
        errno = 0;
        char *end = nullptr;
        const double value = std::strtod(token.c_str(), &end);
        if (end != token.c_str() + token.size()) error(std::string("'") + token + "' is not a number (" + what + ")");
        if (!std::isfinite(value)) // "nan", "inf" and overflow
            error(std::string(what) + " '" + token + "' is not a finite number");
        if (!within(value, kCoordinateLimit))
            error(std::string(what) + " '" + token + "' lies beyond +-" + format_number(kCoordinateLimit) +
                  " (the limit of scene coordinates)");
        return value;
    }

    long long integer(const char *what) {
        const std::string token = next();
        if (token.empty()) error(std::string("file ends where ") + what + " was expected");
        errno = 0;
        char *end = nullptr;
        const long long value = std::strtoll(token.c_str(), &end, 10);
        if (end != token.c_str() + token.size() || errno == ERANGE)
            error(std::string("'") + token + "' is not an integer (" + what + ")");
        return value;
    }

    size_t token_line() const { return token_line_; }

private:
    static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

    void skip_space_and_comments() {
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (c == '\n') ++line_;
            if (is_space(c)) {
                ++pos_;
                continue;
            }
            if (c == '#') {
                while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
                continue;
            }
            break;
        }
    }

    const std::string &text_;
    const std::string &name_;
    size_t pos_ = 0;
    size_t line_ = 1;
    size_t token_line_ = 1;
    size_t last_token_line_ = 1;
};

} // namespace

std::vector<BezierPatch> parse_bpt(const std::string &text, const std::string &name) {
    Tokens tokens(text, name);
    if (tokens.at_end()) tokens.error("empty file: expected the number of patches");
    const long long count = tokens.integer("number of patches");
    if (count <= 0) tokens.error("number of patches must be positive, not " + std::to_string(count));
    if (static_cast<unsigned long long>(count) > max_bpt_patches)
        tokens.error("number of patches " + std::to_string(count) + " exceeds the limit of " +
                     std::to_string(max_bpt_patches));

    std::vector<BezierPatch> patches;
    for (long long index = 0; index < count; ++index) {
        if (tokens.at_end())
            tokens.error("file ends after " + std::to_string(index) + " of " + std::to_string(count) + " patches");
        const long long degree_u = tokens.integer("degree in u");
        const size_t degree_line = tokens.token_line();
        const long long degree_v = tokens.integer("degree in v");
        if (degree_u != 3 || degree_v != 3 || tokens.token_line() != degree_line)
            tokens.error("patch " + std::to_string(index) +
                         ": degree line must be '3 3' (only bicubic patches are supported), found '" +
                         std::to_string(degree_u) + " " + std::to_string(degree_v) + "'");
        BezierPatch patch;
        for (int k = 0; k < 16; ++k) {
            for (int axis = 0; axis < 3; ++axis) {
                const char *what[] = {"x", "y", "z"};
                const std::string label =
                    "patch " + std::to_string(index) + " control point " + std::to_string(k) + " " + what[axis];
                patch.p[k][axis] = tokens.number(label.c_str());
            }
        }
        patches.push_back(patch);
    }
    if (!tokens.at_end())
        tokens.error("unexpected content after the " + std::to_string(count) + " patches the file announces: '" +
                     tokens.next() + "'");
    return patches;
}

std::vector<BezierPatch> read_bpt_file(const std::string &path) { return parse_bpt(read_text_file(path), path); }

} // namespace ppm
