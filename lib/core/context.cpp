// SPDX-License-Identifier: Apache-2.0
#include "core/context.h"

#include "core/error.h"

#include <cstdio>

namespace ppm {

namespace {

// Embree reports details through a callback; keep the last one per thread so check_embree
// can put it in the exception.
thread_local std::string last_embree_message;

void on_embree_error(void *, RTCError, const char *message) { last_embree_message = message ? message : ""; }

const char *embree_error_name(RTCError error) {
    switch (error) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "unknown error";
    }
}

} // namespace

Context::Context() {
    device_ = rtcNewDevice("verbose=0");
    if (!device_) {
        const RTCError error = rtcGetDeviceError(nullptr);
        fail(error == RTC_ERROR_OUT_OF_MEMORY ? PPM_ERROR_OUT_OF_MEMORY : PPM_ERROR_UNSUPPORTED,
             std::string("Embree device creation failed: ") + embree_error_name(error));
    }
    rtcSetDeviceErrorFunction(device_, on_embree_error, nullptr);
    arena_ = std::make_unique<tbb::task_arena>();
}

Context::~Context() { rtcReleaseDevice(device_); }

void Context::set_threads(int threads) {
    threads_ = threads;
    arena_ = threads > 0 ? std::make_unique<tbb::task_arena>(threads) : std::make_unique<tbb::task_arena>();
}

void Context::check_embree(const char *what) const {
    const RTCError error = rtcGetDeviceError(device_);
    if (error == RTC_ERROR_NONE) return;
    const ppm_status status = error == RTC_ERROR_OUT_OF_MEMORY ? PPM_ERROR_OUT_OF_MEMORY : PPM_ERROR_INTERNAL;
    fail(status, std::string(what) + ": Embree " + embree_error_name(error) +
                     (last_embree_message.empty() ? "" : ": " + last_embree_message));
}

void Context::warn(const std::string &message) const {
    if (warning_callback_)
        warning_callback_(warning_user_data_, message.c_str());
    else
        std::fprintf(stderr, "libppm: warning: %s\n", message.c_str());
}

} // namespace ppm
