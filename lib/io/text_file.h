// SPDX-License-Identifier: Apache-2.0
// Whole-file reading with errors that name the file.
#pragma once

#include <string>

namespace ppm {

// Throws ppm::Error(IO) naming the path and the system's reason.
std::string read_text_file(const std::string &path);

} // namespace ppm
