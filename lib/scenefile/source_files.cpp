// SPDX-License-Identifier: Apache-2.0
#include "scenefile/source_files.h"

#include <algorithm>

namespace ppm {

std::size_t SourceFiles::add(const std::string &path, std::string text) {
    File file;
    file.path = path;
    file.base = next_base_;
    file.line_starts.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i)
        if (text[i] == '\n') file.line_starts.push_back(i + 1);
    next_base_ += text.size() + 1;
    file.text = std::move(text);
    files_.push_back(std::move(file));
    return files_.back().base;
}

std::string SourceFiles::location(std::size_t position) const {
    for (const File &file : files_) {
        if (position < file.base || position > file.base + file.text.size()) continue;
        const std::size_t offset = position - file.base;
        const auto line = std::upper_bound(file.line_starts.begin(), file.line_starts.end(), offset) - 1;
        return file.path + ":" + std::to_string(line - file.line_starts.begin() + 1) + ":" +
               std::to_string(offset - *line + 1);
    }
    return files_.empty() ? std::string("<no file>") : files_.front().path;
}

} // namespace ppm
