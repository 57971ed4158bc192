// Replacing a file so that readers (and a crash) see the old or the new content, never a torn
// mix: the bytes go to a temporary file in the same folder, which is synced and renamed.
#pragma once

#include <cstddef>
#include <string>

namespace ppm_render {

// Throws std::runtime_error naming the path and the system's reason; on failure `path` is
// untouched and no temporary file is left.
void write_bytes_atomically(const std::string &path, const void *data, std::size_t size);

} // namespace ppm_render
