// SPDX-License-Identifier: Apache-2.0
// A set of pass indices as sorted, disjoint, non-adjacent half-open ranges [first, end): the
// passes a pass-independent render holds, compact for any split of a render into chunks.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ppm {

// Pass indices are below this (the random streams take 32-bit pass numbers).
constexpr std::uint64_t kPassIndexLimit = std::uint64_t(1) << 32;

class PassSet {
public:
    struct Range {
        std::uint64_t first, end; // [first, end), first < end
        bool operator==(const Range &o) const { return first == o.first && end == o.end; }
    };

    bool empty() const { return ranges_.empty(); }
    std::uint64_t count() const; // the number of passes
    bool contains(std::uint64_t pass) const;
    const std::vector<Range> &ranges() const { return ranges_; }

    void insert(std::uint64_t pass) { insert(Range{pass, pass + 1}); }
    void insert(Range range); // joins neighbours; overlapping is allowed here
    // The first range both sets hold some of, as the intersection's first range.
    std::optional<Range> first_overlap(const PassSet &other) const;
    void merge(const PassSet &other); // union
    // The lowest index not in the set.
    std::uint64_t lowest_missing() const;
    // The ranges of [0, total) not in the set.
    PassSet missing_below(std::uint64_t total) const;

    // "0-9, 20, 30-39" (inclusive ends), for messages.
    std::string describe() const;
    static std::string describe(const Range &range);

    bool operator==(const PassSet &o) const { return ranges_ == o.ranges_; }

    // A set read from a file: throws nothing, returns false unless `ranges` are sorted,
    // disjoint, non-adjacent and non-empty, as the set keeps them.
    bool assign_checked(std::vector<Range> ranges);

private:
    std::vector<Range> ranges_;
};

} // namespace ppm
