// SPDX-License-Identifier: Apache-2.0
#include "io/text_file.h"

#include "core/error.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <sys/stat.h>

namespace ppm {

std::string read_text_file(const std::string &path) {
    struct stat info {};
    if (stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode))
        fail(PPM_ERROR_IO, path + ": is a directory, not a file");
    std::unique_ptr<FILE, int (*)(FILE *)> file(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!file) fail(PPM_ERROR_IO, path + ": cannot open: " + std::strerror(errno));
    std::string text;
    char buffer[1 << 16];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, n);
    if (std::ferror(file.get())) fail(PPM_ERROR_IO, path + ": read error: " + std::strerror(errno));
    return text;
}

} // namespace ppm
