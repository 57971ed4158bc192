// SPDX-License-Identifier: Apache-2.0
#include "measure.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <unistd.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace bench {

namespace {

double clock_seconds(clockid_t id) {
    timespec ts;
    clock_gettime(id, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

} // namespace

void Stopwatch::restart() {
    wall0_ = clock_seconds(CLOCK_MONOTONIC);
    cpu0_ = clock_seconds(CLOCK_PROCESS_CPUTIME_ID);
}

double Stopwatch::wall_seconds() const { return clock_seconds(CLOCK_MONOTONIC) - wall0_; }
double Stopwatch::cpu_seconds() const { return clock_seconds(CLOCK_PROCESS_CPUTIME_ID) - cpu0_; }

size_t heap_bytes() {
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
    const struct mallinfo2 info = mallinfo2();
    return info.uordblks + info.hblkhd;
#else
    return 0;
#endif
}

size_t resident_bytes() {
    std::FILE *f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0;
    unsigned long size = 0, resident = 0;
    const int read = std::fscanf(f, "%lu %lu", &size, &resident);
    std::fclose(f);
    return read == 2 ? resident * size_t(sysconf(_SC_PAGESIZE)) : 0;
}

double load_average() {
    std::FILE *f = std::fopen("/proc/loadavg", "r");
    if (!f) return -1;
    double load = -1;
    if (std::fscanf(f, "%lf", &load) != 1) load = -1;
    std::fclose(f);
    return load;
}

size_t MemoryDelta::take() const {
    const size_t heap = heap_bytes(), rss = resident_bytes();
    return std::max(heap > heap0_ ? heap - heap0_ : 0, rss > rss0_ ? rss - rss0_ : 0);
}

} // namespace bench
