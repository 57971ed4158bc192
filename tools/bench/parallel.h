// SPDX-License-Identifier: Apache-2.0
// A minimal parallel loop over plain std::threads: the baselines (Embree triangles, CGAL,
// Newton) and the reference are driven by the bench's own threads, so their all-thread
// numbers do not depend on anyone's task scheduler but their own.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace bench {

// Hardware threads, at least 1.
inline int hardware_threads() { return std::max(1, int(std::thread::hardware_concurrency())); }

// Calls work(begin, end) on chunks of [0, n) of `chunk` items, from `threads` threads (the
// caller's one among them). The first exception thrown by any call is rethrown here.
template <class Work> void parallel_chunks(size_t n, int threads, size_t chunk, Work &&work) {
    if (n == 0) return;
    chunk = std::max<size_t>(chunk, 1);
    threads = int(std::min<size_t>(size_t(std::max(threads, 1)), (n + chunk - 1) / chunk));
    if (threads <= 1) {
        work(size_t(0), n);
        return;
    }
    std::atomic<size_t> next{0};
    std::exception_ptr error;
    std::mutex error_mutex;
    auto loop = [&] {
        try {
            for (size_t begin; (begin = next.fetch_add(chunk)) < n;) work(begin, std::min(n, begin + chunk));
        } catch (...) {
            std::lock_guard<std::mutex> lock(error_mutex);
            if (!error) error = std::current_exception();
            next = n;
        }
    };
    std::vector<std::thread> pool;
    for (int k = 1; k < threads; ++k) pool.emplace_back(loop);
    loop();
    for (std::thread &t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

} // namespace bench
