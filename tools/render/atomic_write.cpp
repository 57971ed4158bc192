#include "atomic_write.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace ppm_render {

void write_bytes_atomically(const std::string &path, const void *data, std::size_t size) {
    // A hidden name beside the target, so that the rename stays within one file system.
    const std::size_t slash = path.rfind('/');
    const std::string folder = slash == std::string::npos ? "" : path.substr(0, slash + 1);
    const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    std::string temp_name = folder + "." + name + ".tmp-XXXXXX";
    std::vector<char> temp(temp_name.begin(), temp_name.end());
    temp.push_back('\0');
    const int fd = mkstemp(temp.data());
    if (fd < 0) throw std::runtime_error(path + ": cannot create a temporary file beside it: " + std::strerror(errno));
    temp_name = temp.data();
    const auto give_up = [&](const char *what, int error) {
        std::remove(temp_name.c_str());
        throw std::runtime_error(path + ": " + what + ": " + std::strerror(error));
    };
    const auto close_and_give_up = [&](const char *what) {
        const int error = errno;
        close(fd);
        give_up(what, error);
    };
    const char *bytes = static_cast<const char *>(data);
    for (std::size_t written = 0; written < size;) {
        const ssize_t n = write(fd, bytes + written, size - written);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) close_and_give_up("write error");
        if (n == 0) {
            errno = ENOSPC; // a write that makes no progress would loop forever
            close_and_give_up("write error");
        }
        written += static_cast<std::size_t>(n);
    }
    // mkstemp creates the file 0600; images are ordinary readable files.
    if (fchmod(fd, 0644) != 0) close_and_give_up("cannot set permissions");
    // Synced before the rename, so that after a system crash the name holds complete data.
    if (fsync(fd) != 0) close_and_give_up("cannot flush to disk");
    if (close(fd) != 0) give_up("write error", errno);
    if (std::rename(temp_name.c_str(), path.c_str()) != 0) give_up("cannot replace it", errno);
    // The rename is durable once the folder's entry is on disk; best effort, as the file is
    // already complete and in place.
    const int folder_fd = open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY);
    if (folder_fd >= 0) {
        fsync(folder_fd);
        close(folder_fd);
    }
}

} // namespace ppm_render
