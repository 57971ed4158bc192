// SPDX-License-Identifier: Apache-2.0
// The text of the files a scene was read from, and the "path:line:column" of any byte in
// them. A position is one number across all the files: file k's bytes are numbered from
// base(k) on, and 0 is no position at all.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace ppm {

class SourceFiles {
public:
    // Adds a file and returns its base.
    std::size_t add(const std::string &path, std::string text);
    const std::string &text(std::size_t file) const { return files_[file].text; }
    const std::string &path(std::size_t file) const { return files_[file].path; }
    std::size_t count() const { return files_.size(); }
    // "path:line:column" of a position; the first file's path alone for a position outside
    // every file.
    std::string location(std::size_t position) const;

private:
    struct File {
        std::string path;
        std::string text;
        std::size_t base = 0;
        std::vector<std::size_t> line_starts;
    };
    std::vector<File> files_;
    std::size_t next_base_ = 1;
};

} // namespace ppm
