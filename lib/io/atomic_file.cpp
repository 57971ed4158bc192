// SPDX-License-Identifier: Apache-2.0
#include "io/atomic_file.h"

#include "core/error.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace ppm {

void write_file_atomically(const std::string &path, const void *data, std::size_t size) {
    std::string temp_name = path + ".tmp-XXXXXX";
    std::vector<char> temp(temp_name.begin(), temp_name.end());
    temp.push_back('\0');
    const int fd = mkstemp(temp.data());
    if (fd < 0) fail(PPM_ERROR_IO, path + ": cannot create a temporary file beside it: " + std::strerror(errno));
    temp_name = temp.data();
    const auto give_up = [&](const char *what) {
        const int error = errno;
        close(fd);
        std::remove(temp_name.c_str());
        fail(PPM_ERROR_IO, path + ": " + what + ": " + std::strerror(error));
    };
    const char *bytes = static_cast<const char *>(data);
    for (std::size_t written = 0; written < size;) {
        const ssize_t n = write(fd, bytes + written, size - written);
        if (n < 0) {
            if (errno == EINTR) continue;
            give_up("write error");
        }
        if (n == 0) { // no progress and no error: a device that takes nothing more
            errno = ENOSPC;
            give_up("write error");
        }
        written += static_cast<std::size_t>(n);
    }
    // mkstemp creates the file 0600; make it an ordinary readable file (reading the umask
    // would mean changing it, which is not thread safe).
    if (fchmod(fd, 0644) != 0) give_up("cannot set permissions");
    if (fsync(fd) != 0) give_up("cannot flush to disk");
    if (close(fd) != 0) {
        const int error = errno;
        std::remove(temp_name.c_str());
        fail(PPM_ERROR_IO, path + ": write error: " + std::strerror(error));
    }
    if (std::rename(temp_name.c_str(), path.c_str()) != 0) {
        const int error = errno;
        std::remove(temp_name.c_str());
        fail(PPM_ERROR_IO, path + ": cannot replace it: " + std::strerror(error));
    }
    // The rename is durable only once the folder's entry is on disk. Best effort: the file is
    // already complete and in place, and some file systems cannot sync a folder.
    const std::size_t slash = path.rfind('/');
    const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
    const int folder_fd = open(folder.c_str(), O_RDONLY | O_DIRECTORY);
    if (folder_fd >= 0) {
        fsync(folder_fd);
        close(folder_fd);
    }
}

void check_folder_writable(const std::string &path) {
    const std::size_t slash = path.rfind('/');
    const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
    struct stat info;
    if (stat(folder.c_str(), &info) != 0)
        fail(PPM_ERROR_IO, path + ": the folder " + folder + " cannot be used: " + std::strerror(errno));
    if (!S_ISDIR(info.st_mode)) fail(PPM_ERROR_IO, path + ": " + folder + " is not a folder");
    // Creating the temporary file needs write and search permission on the folder.
    if (access(folder.c_str(), W_OK | X_OK) != 0)
        fail(PPM_ERROR_IO, path + ": cannot write into the folder " + folder + ": " + std::strerror(errno));
}

} // namespace ppm
