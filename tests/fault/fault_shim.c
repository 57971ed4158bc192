/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Fault injection for file writes: a shared library that wraps the C library's write, flush,
 * sync, close and rename calls and makes them fail like a full or broken disk, so that tests
 * can check what libppm and ppm-render do then. Loaded with LD_PRELOAD (tools) or linked into
 * a test executable (before libc, so its definitions win).
 *
 * Only regular files whose path contains PPM_FAULT_PATH are affected (default: every regular
 * file); terminals, pipes and sockets pass through untouched. Environment:
 *   PPM_FAULT_OPS    comma list of the calls that count: write (write, pwrite, writev, fwrite,
 *                    fputc, fputs), flush (fflush), fsync (fsync, fdatasync), close (close,
 *                    fclose), rename (rename, renameat). Default: write.
 *   PPM_FAULT_NTH    the Nth counted call (1-based) and every later one fails.
 *   PPM_FAULT_BYTES  writes fail once N bytes have been written in all (the write that
 *                    crosses N is cut short there, as a disk filling up does).
 *   PPM_FAULT_ERRNO  ENOSPC (default), EIO, EDQUOT or EFBIG.
 *   PPM_FAULT_ACTION fail (default) or kill: SIGKILL the process at the faulting call instead
 *                    (before a sync, close or rename takes effect; a write crossing the byte
 *                    budget writes its first part, then kills), a crash at a chosen moment.
 *   PPM_FAULT_LOG    a file that gets one line per counted call ("N op path bytes"), to learn
 *                    how many calls a run makes.
 * Without PPM_FAULT_NTH and PPM_FAULT_BYTES nothing fails (counting and logging only).
 * Closing calls still release the descriptor or stream when they report a failure.
 * ppm_fault_reset() re-reads the environment and restarts the counts (for in-process tests).
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/uio.h>
#include <unistd.h>

enum { OP_WRITE = 1, OP_FLUSH = 2, OP_FSYNC = 4, OP_CLOSE = 8, OP_RENAME = 16 };

static struct {
    int ops;
    long long nth;   /* 0: no call-count fault */
    long long bytes; /* -1: no byte budget */
    int error;
    int kill;
    char path[PATH_MAX];
    char log[PATH_MAX];
} config;

static long long calls;   /* counted calls so far */
static long long written; /* bytes written to matching files so far */
static int configured;

static const char *op_name(int op) {
    switch (op) {
    case OP_WRITE: return "write";
    case OP_FLUSH: return "flush";
    case OP_FSYNC: return "fsync";
    case OP_CLOSE: return "close";
    default: return "rename";
    }
}

static void copy_env(char *out, size_t size, const char *name) {
    const char *value = getenv(name);
    out[0] = '\0';
    if (value) {
        strncpy(out, value, size - 1);
        out[size - 1] = '\0';
    }
}

void ppm_fault_reset(void) {
    const char *ops = getenv("PPM_FAULT_OPS");
    const char *nth = getenv("PPM_FAULT_NTH");
    const char *bytes = getenv("PPM_FAULT_BYTES");
    const char *error = getenv("PPM_FAULT_ERRNO");
    const char *action = getenv("PPM_FAULT_ACTION");
    config.ops = 0;
    if (!ops || !*ops) ops = "write";
    if (strstr(ops, "write")) config.ops |= OP_WRITE;
    if (strstr(ops, "flush")) config.ops |= OP_FLUSH;
    if (strstr(ops, "fsync")) config.ops |= OP_FSYNC;
    if (strstr(ops, "close")) config.ops |= OP_CLOSE;
    if (strstr(ops, "rename")) config.ops |= OP_RENAME;
    config.nth = nth && *nth ? atoll(nth) : 0;
    config.bytes = bytes && *bytes ? atoll(bytes) : -1;
    config.error = ENOSPC;
    if (error && strcmp(error, "EIO") == 0) config.error = EIO;
    if (error && strcmp(error, "EDQUOT") == 0) config.error = EDQUOT;
    if (error && strcmp(error, "EFBIG") == 0) config.error = EFBIG;
    config.kill = action && strcmp(action, "kill") == 0;
    copy_env(config.path, sizeof config.path, "PPM_FAULT_PATH");
    copy_env(config.log, sizeof config.log, "PPM_FAULT_LOG");
    __atomic_store_n(&calls, 0, __ATOMIC_SEQ_CST);
    __atomic_store_n(&written, 0, __ATOMIC_SEQ_CST);
    configured = 1;
}

__attribute__((constructor)) static void init(void) { ppm_fault_reset(); }

static void *real(const char *name) {
    void *f = dlsym(RTLD_NEXT, name);
    if (!f) abort();
    return f;
}
#define REAL(name) ((__typeof__(&name))real(#name))

/* The path of a descriptor if it is a regular file, else "" (not to be faulted). */
static void fd_path(int fd, char *out, size_t size) {
    struct stat st;
    out[0] = '\0';
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) return;
    char link[64];
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    const ssize_t n = readlink(link, out, size - 1);
    out[n > 0 ? n : 0] = '\0';
}

static int matches(const char *path) {
    return configured && path[0] != '\0' && (config.path[0] == '\0' || strstr(path, config.path) != NULL);
}

static void log_call(long long n, int op, const char *path, size_t size) {
    if (config.log[0] == '\0') return;
    char line[PATH_MAX + 64];
    const int length = snprintf(line, sizeof line, "%lld %s %s %zu\n", n, op_name(op), path, size);
    /* Raw system calls: the log must not count or fault itself. */
    const int fd = (int)syscall(SYS_openat, AT_FDCWD, config.log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd < 0) return;
    if (length > 0) (void)syscall(SYS_write, fd, line, (size_t)length);
    (void)syscall(SYS_close, fd);
}

static int fault_now(void) {
    if (config.kill) kill(getpid(), SIGKILL);
    errno = config.error;
    return 1;
}

/* Counts a call on `path`; returns 1 if it must fail (errno set). For writes, *size is
 * lowered to what fits in the byte budget; 0 with a nonzero request means fail. */
static int check(int op, const char *path, size_t *size) {
    if (!matches(path) || !(config.ops & op)) return 0;
    const long long n = __atomic_add_fetch(&calls, 1, __ATOMIC_SEQ_CST);
    log_call(n, op, path, size ? *size : 0);
    if (config.nth > 0 && n >= config.nth) return fault_now();
    if (op == OP_WRITE && size && config.bytes >= 0) {
        const long long before = __atomic_fetch_add(&written, (long long)*size, __ATOMIC_SEQ_CST);
        if (before + (long long)*size > config.bytes) {
            const long long room = config.bytes > before ? config.bytes - before : 0;
            if (room == 0) return fault_now();
            *size = (size_t)room;
        }
    }
    return 0;
}

static int check_fd(int op, int fd, size_t *size) {
    char path[PATH_MAX];
    fd_path(fd, path, sizeof path);
    return check(op, path, size);
}

static int check_stream(int op, FILE *stream, size_t *size) { return stream ? check_fd(op, fileno(stream), size) : 0; }

/* After a write cut short by the byte budget: in kill mode the process dies with the first
 * part written, as a crash in the middle of a write leaves it. */
static ssize_t cut_short(ssize_t written) {
    if (config.kill) kill(getpid(), SIGKILL);
    return written;
}

ssize_t write(int fd, const void *data, size_t size) {
    size_t allowed = size;
    if (check_fd(OP_WRITE, fd, &allowed)) return -1;
    const ssize_t n = REAL(write)(fd, data, allowed);
    return allowed < size ? cut_short(n) : n;
}

ssize_t pwrite(int fd, const void *data, size_t size, off_t offset) {
    size_t allowed = size;
    if (check_fd(OP_WRITE, fd, &allowed)) return -1;
    const ssize_t n = REAL(pwrite)(fd, data, allowed, offset);
    return allowed < size ? cut_short(n) : n;
}

ssize_t pwrite64(int fd, const void *data, size_t size, off_t offset) {
    size_t allowed = size;
    if (check_fd(OP_WRITE, fd, &allowed)) return -1;
    const ssize_t n = REAL(pwrite64)(fd, data, allowed, offset);
    return allowed < size ? cut_short(n) : n;
}

ssize_t writev(int fd, const struct iovec *iov, int count) {
    size_t total = 0;
    for (int i = 0; i < count; ++i) total += iov[i].iov_len;
    size_t allowed = total;
    if (check_fd(OP_WRITE, fd, &allowed)) return -1;
    if (allowed == total) return REAL(writev)(fd, iov, count);
    /* Cut short: the first `allowed` bytes go out as one plain write. */
    size_t done = 0;
    for (int i = 0; i < count && done < allowed; ++i) {
        size_t part = iov[i].iov_len < allowed - done ? iov[i].iov_len : allowed - done;
        const ssize_t n = REAL(write)(fd, iov[i].iov_base, part);
        if (n < 0) return done > 0 ? (ssize_t)done : -1;
        done += (size_t)n;
        if ((size_t)n < part) break;
    }
    return cut_short((ssize_t)done);
}

size_t fwrite(const void *data, size_t size, size_t count, FILE *stream) {
    if (size == 0 || count == 0) return REAL(fwrite)(data, size, count, stream);
    size_t allowed = size * count;
    if (check_stream(OP_WRITE, stream, &allowed)) return 0;
    const size_t items = allowed / size;
    if (items == count) return REAL(fwrite)(data, size, count, stream);
    const size_t done = items > 0 ? REAL(fwrite)(data, size, items, stream) : 0;
    if (config.kill) {
        REAL(fflush)(stream);
        kill(getpid(), SIGKILL);
    }
    errno = config.error;
    return done;
}

int fputc(int c, FILE *stream) {
    size_t allowed = 1;
    if (check_stream(OP_WRITE, stream, &allowed) || allowed == 0) return EOF;
    return REAL(fputc)(c, stream);
}

int fputs(const char *text, FILE *stream) {
    size_t allowed = strlen(text);
    const size_t length = allowed;
    if (check_stream(OP_WRITE, stream, &allowed)) return EOF;
    if (allowed == length) return REAL(fputs)(text, stream);
    if (allowed > 0) REAL(fwrite)(text, 1, allowed, stream);
    if (config.kill) {
        REAL(fflush)(stream);
        kill(getpid(), SIGKILL);
    }
    errno = config.error;
    return EOF;
}

int fflush(FILE *stream) {
    if (check_stream(OP_FLUSH, stream, NULL)) return EOF;
    return REAL(fflush)(stream);
}

int fsync(int fd) {
    if (check_fd(OP_FSYNC, fd, NULL)) return -1;
    return REAL(fsync)(fd);
}

int fdatasync(int fd) {
    if (check_fd(OP_FSYNC, fd, NULL)) return -1;
    return REAL(fdatasync)(fd);
}

int close(int fd) {
    char path[PATH_MAX];
    fd_path(fd, path, sizeof path);
    const int failed = check(OP_CLOSE, path, NULL);
    const int error = errno;
    const int status = REAL(close)(fd);
    if (failed) {
        errno = error;
        return -1;
    }
    return status;
}

int fclose(FILE *stream) {
    char path[PATH_MAX] = "";
    if (stream) fd_path(fileno(stream), path, sizeof path);
    const int failed = check(OP_CLOSE, path, NULL);
    const int error = errno;
    const int status = REAL(fclose)(stream);
    if (failed) {
        errno = error;
        return EOF;
    }
    return status;
}

static int check_rename(const char *from, const char *to) {
    char a[PATH_MAX], b[PATH_MAX];
    if (!realpath(from, a)) snprintf(a, sizeof a, "%s", from);
    /* The target may not exist yet: resolve its folder's name only through the match. */
    snprintf(b, sizeof b, "%s", to);
    if (matches(a)) {
        struct stat st;
        if (stat(a, &st) == 0 && S_ISREG(st.st_mode)) return check(OP_RENAME, a, NULL);
    }
    if (matches(b)) return check(OP_RENAME, b, NULL);
    return 0;
}

int rename(const char *from, const char *to) {
    if (check_rename(from, to)) return -1;
    return REAL(rename)(from, to);
}

int renameat(int from_dir, const char *from, int to_dir, const char *to) {
    if (from_dir == AT_FDCWD && to_dir == AT_FDCWD && check_rename(from, to)) return -1;
    return REAL(renameat)(from_dir, from, to_dir, to);
}
