// SPDX-License-Identifier: Apache-2.0
#include "core/suggest.h"

#include <algorithm>

namespace ppm {

std::size_t edit_distance(const std::string &a, const std::string &b) {
    // Three rows of the dynamic programme: the transposition looks two rows back.
    std::vector<std::size_t> before(b.size() + 1), previous(b.size() + 1), current(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        current[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                current[j] = std::min(current[j], before[j - 2] + 1);
        }
        std::swap(before, previous);
        std::swap(previous, current);
    }
    return previous[b.size()];
}

std::string closest_name(const std::string &word, const std::vector<std::string> &known) {
    const std::size_t limit = std::max<std::size_t>(1, word.size() / 3);
    std::string best;
    std::size_t best_distance = limit + 1;
    for (const std::string &name : known) {
        const std::size_t distance = edit_distance(word, name);
        if (distance < best_distance) best = name, best_distance = distance;
    }
    return best;
}

std::string did_you_mean(const std::string &word, const std::vector<std::string> &known) {
    const std::string name = closest_name(word, known);
    return name.empty() ? std::string() : " (did you mean '" + name + "'?)";
}

} // namespace ppm
