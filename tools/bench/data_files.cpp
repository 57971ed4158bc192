// SPDX-License-Identifier: Apache-2.0
#include "data_files.h"

#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace bench {

namespace fs = std::filesystem;

std::string data_file(const std::string &name) {
    std::error_code error;
    // /proc/self/exe rather than argv[0]: it holds wherever the program was started from, and
    // through symbolic links. Without it, the folder is relative to the current directory,
    // which the error of input_or_data_file then names.
    const fs::path exe = fs::canonical("/proc/self/exe", error);
    const fs::path folder = error ? fs::path(PPM_BENCH_DATA_FROM_EXE) : exe.parent_path() / PPM_BENCH_DATA_FROM_EXE;
    return (folder / name).lexically_normal().string();
}

std::string input_or_data_file(const std::string &path, const std::string &name, const std::string &option) {
    if (!path.empty()) return path;
    const std::string file = data_file(name);
    std::error_code error;
    if (!fs::is_regular_file(file, error))
        throw std::runtime_error("no " + option + " given, and its default " + file +
                                 " (the data folder beside ppm-bench) does not exist; pass " + option + " FILE");
    return file;
}

} // namespace bench
