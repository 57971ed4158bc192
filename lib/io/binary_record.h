// SPDX-License-Identifier: Apache-2.0
// Building blocks of libppm's versioned binary files (checkpoints, partial renders): a byte
// buffer written field by field, a reader that names the field a truncated file ends in, and
// the FNV-1a hash their checksums use. Native byte order; the files record a byte-order mark.
#pragma once

#include "core/error.h"
#include "math/rgb.h"
#include "math/vec3.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace ppm {

class Fnv1a {
public:
    void add(const void *data, std::size_t size) {
        const auto *bytes = static_cast<const unsigned char *>(data);
        for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ bytes[i]) * 1099511628211ull;
    }
    template <class T> void add(const T &value) {
        static_assert(std::is_arithmetic_v<T>);
        add(&value, sizeof value);
    }
    void add(const Vec3 &v) { add(v.x), add(v.y), add(v.z); }
    void add(const Rgb &c) { add(c.r), add(c.g), add(c.b); }
    std::uint64_t value() const { return hash_; }

private:
    std::uint64_t hash_ = 14695981039346656037ull;
};

class ByteWriter {
public:
    template <class T> void put(const T &value) {
        static_assert(std::is_trivially_copyable_v<T>);
        put_bytes(&value, sizeof value);
    }
    void put_bytes(const void *data, std::size_t size) {
        const auto *bytes = static_cast<const char *>(data);
        buffer_.insert(buffer_.end(), bytes, bytes + size);
    }
    std::vector<char> &buffer() { return buffer_; }

private:
    std::vector<char> buffer_;
};

// Reads `bytes` (not copied: it must outlive the reader). A read past the end throws
// ppm::Error(PARSE) "<origin>: truncated <kind> (ends in the <field>)".
class ByteReader {
public:
    ByteReader(const std::string &origin, const char *kind, const char *bytes, std::size_t size)
        : origin_(origin), kind_(kind), bytes_(bytes), size_(size) {}
    template <class T> T get(const char *what) {
        static_assert(std::is_trivially_copyable_v<T>);
        T value;
        get_bytes(&value, sizeof value, what);
        return value;
    }
    void get_bytes(void *out, std::size_t size, const char *what) {
        if (size_ - position_ < size)
            fail(PPM_ERROR_PARSE, origin_ + ": truncated " + kind_ + " (ends in the " + what + ")");
        std::memcpy(out, bytes_ + position_, size);
        position_ += size;
    }
    std::size_t position() const { return position_; }
    std::size_t remaining() const { return size_ - position_; }

private:
    const std::string &origin_;
    const char *kind_;
    const char *bytes_;
    std::size_t size_;
    std::size_t position_ = 0;
};

} // namespace ppm
