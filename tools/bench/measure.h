// SPDX-License-Identifier: Apache-2.0
// Timers and memory probes. The machine may be shared, so every timing is kept as both wall
// and process CPU time; single-threaded runs are judged by the latter.
#pragma once

#include <cstddef>
#include <cstdint>

namespace bench {

class Stopwatch {
public:
    Stopwatch() { restart(); }
    void restart();
    double wall_seconds() const;
    double cpu_seconds() const; // all threads of the process

private:
    double wall0_ = 0, cpu0_ = 0;
};

// Bytes of heap in use (malloc arenas plus malloc's own mmaps), 0 where unknown.
size_t heap_bytes();
// Resident set size of the process, 0 where unknown.
size_t resident_bytes();
// The 1-minute load average of the machine, -1 where unknown.
double load_average();

// Memory taken by a structure built between construction and take(): the larger of the heap
// and resident-set growth (allocators outside malloc show only in the latter, heap reuse only
// in the former). Rough, as its purpose is.
class MemoryDelta {
public:
    MemoryDelta() : heap0_(heap_bytes()), rss0_(resident_bytes()) {}
    size_t take() const;

private:
    size_t heap0_, rss0_;
};

} // namespace bench
