// SPDX-License-Identifier: Apache-2.0
// The root object: the Embree device, the worker threads, the error callback.
#pragma once

#include <ppm/ppm.h>

#include "core/ref_counted.h"

#include <embree3/rtcore.h>
#include <tbb/task_arena.h>

#include <memory>
#include <string>

namespace ppm {

class Context : public RefCounted {
public:
    Context();
    ~Context() override;

    RTCDevice device() const { return device_; }

    // 0 means all hardware threads.
    int threads() const { return threads_; }
    void set_threads(int threads);

    // Runs `work` on this context's worker threads (TBB parallel loops inside it are limited
    // to the configured thread count).
    template <class F> void run(F &&work) { arena_->execute(std::forward<F>(work)); }

    // Throws ppm::Error if the last Embree call on this device failed; `what` names the call.
    void check_embree(const char *what) const;

    void set_error_callback(ppm_error_callback callback, void *user_data) {
        error_callback_ = callback;
        error_user_data_ = user_data;
    }
    void report_error(ppm_status status, const char *message) const {
        if (error_callback_) error_callback_(error_user_data_, status, message);
    }

    void set_warning_callback(ppm_warning_callback callback, void *user_data) {
        warning_callback_ = callback;
        warning_user_data_ = user_data;
    }
    // Through the callback, or to stderr when none is set.
    void warn(const std::string &message) const;

private:
    RTCDevice device_ = nullptr;
    int threads_ = 0;
    std::unique_ptr<tbb::task_arena> arena_;
    ppm_error_callback error_callback_ = nullptr;
    void *error_user_data_ = nullptr;
    ppm_warning_callback warning_callback_ = nullptr;
    void *warning_user_data_ = nullptr;
};

} // namespace ppm
