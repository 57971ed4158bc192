// SPDX-License-Identifier: Apache-2.0
// Writing a file so that readers (and a crash) see the old or the new content, never a torn
// mix: the bytes go to a temporary file in the same folder, which is flushed and renamed.
#pragma once

#include <cstddef>
#include <string>

namespace ppm {

// Throws ppm::Error(IO) naming the path and the system's reason; leaves no temporary file.
void write_file_atomically(const std::string &path, const void *data, std::size_t size);

// Throws ppm::Error(IO) unless the folder `path` would be written into exists and this
// process may create files there: the check a long job makes before it starts.
void check_folder_writable(const std::string &path);

} // namespace ppm
