// SPDX-License-Identifier: Apache-2.0
// Intrusive reference count behind the C handles' retain/release.
#pragma once

#include <atomic>
#include <cstdint>

namespace ppm {

class RefCounted {
public:
    RefCounted() = default;
    RefCounted(const RefCounted &) = delete;
    RefCounted &operator=(const RefCounted &) = delete;
    virtual ~RefCounted() = default;

    void retain() { references_.fetch_add(1, std::memory_order_relaxed); }
    void release() {
        if (references_.fetch_sub(1, std::memory_order_acq_rel) == 1) delete this;
    }

private:
    std::atomic<int64_t> references_{1};
};

// Holds the one reference a factory returned and releases it at the end of the scope.
template <class T> class Owned {
public:
    explicit Owned(T *object) : object_(object) {}
    Owned(const Owned &) = delete;
    Owned &operator=(const Owned &) = delete;
    ~Owned() {
        if (object_) object_->release();
    }
    T *operator->() const { return object_; }
    T &operator*() const { return *object_; }

private:
    T *object_;
};

} // namespace ppm
