// SPDX-License-Identifier: Apache-2.0
// Ownership of one libppm handle by one Python object.
//
// close() drops the Python object's reference at once; the C library keeps whatever a child
// still needs alive (a scene holds its context, a renderer its scene), so closing a parent
// before its children is safe. Calls that release the GIL take a reference of their own for
// their duration (Borrowed), so that close() from another thread cannot free the object
// under a running pass or ray batch.
#pragma once

#include "status.h"

#include <string>
#include <utility>

namespace ppm_py {

template <typename T, ppm_status (*Retain)(T), void (*Release)(T)> class Handle {
public:
    // A reference held for the duration of one call made without the GIL.
    class Borrowed {
    public:
        explicit Borrowed(T handle) : handle_(handle) { check(Retain(handle_)); }
        ~Borrowed() { Release(handle_); }
        Borrowed(const Borrowed &) = delete;
        Borrowed &operator=(const Borrowed &) = delete;
        T get() const { return handle_; }

    private:
        T handle_;
    };

    // Adopts the one reference `handle` holds.
    Handle(T handle, const char *kind) : handle_(handle), kind_(kind) {}
    ~Handle() { Release(handle_); }
    Handle(const Handle &) = delete;
    Handle &operator=(const Handle &) = delete;

    T get() const {
        if (!handle_) throw ClosedError(std::string(kind_) + " is closed");
        return handle_;
    }
    Borrowed borrow() const { return Borrowed(get()); }
    void close() { Release(std::exchange(handle_, nullptr)); }
    bool closed() const { return handle_ == nullptr; }

private:
    T handle_;
    const char *kind_;
};

} // namespace ppm_py
