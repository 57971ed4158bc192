// SPDX-License-Identifier: Apache-2.0
// "Did you mean" for misspelled names: the closest known name by edit distance, when it is
// close enough to be a likely typo.
#pragma once

#include <string>
#include <vector>

namespace ppm {

// Levenshtein distance with adjacent transpositions counting as one edit ("optimal string
// alignment"), case-sensitive.
std::size_t edit_distance(const std::string &a, const std::string &b);

// The known name nearest to `word` if at most max(1, |word| / 3) edits away (ties: the first
// listed), else "".
std::string closest_name(const std::string &word, const std::vector<std::string> &known);

// " (did you mean 'name'?)" for the closest name, else "": to append to an error message.
std::string did_you_mean(const std::string &word, const std::vector<std::string> &known);

} // namespace ppm
