// SPDX-License-Identifier: Apache-2.0
#include "film/pass_set.h"

#include <algorithm>

namespace ppm {

std::uint64_t PassSet::count() const {
    std::uint64_t n = 0;
    for (const Range &r : ranges_) n += r.end - r.first;
    return n;
}

bool PassSet::contains(std::uint64_t pass) const {
    const auto it = std::upper_bound(ranges_.begin(), ranges_.end(), pass,
                                     [](std::uint64_t p, const Range &r) { return p < r.end; });
    return it != ranges_.end() && it->first <= pass;
}

void PassSet::insert(Range range) {
    if (range.first >= range.end) return;
    std::vector<Range> out;
    out.reserve(ranges_.size() + 1);
    bool placed = false;
    for (const Range &r : ranges_) {
        if (r.end < range.first) {
            out.push_back(r);
        } else if (range.end < r.first) {
            if (!placed) out.push_back(range), placed = true;
            out.push_back(r);
        } else { // touching or overlapping: joined into `range`
            range.first = std::min(range.first, r.first);
            range.end = std::max(range.end, r.end);
        }
    }
    if (!placed) out.push_back(range);
    ranges_ = std::move(out);
}

std::optional<PassSet::Range> PassSet::first_overlap(const PassSet &other) const {
    auto a = ranges_.begin(), b = other.ranges_.begin();
    while (a != ranges_.end() && b != other.ranges_.end()) {
        const std::uint64_t first = std::max(a->first, b->first), end = std::min(a->end, b->end);
        if (first < end) return Range{first, end};
        if (a->end < b->end)
            ++a;
        else
            ++b;
    }
    return std::nullopt;
}

void PassSet::merge(const PassSet &other) {
    for (const Range &r : other.ranges_) insert(r);
}

std::uint64_t PassSet::lowest_missing() const {
    return !ranges_.empty() && ranges_.front().first == 0 ? ranges_.front().end : 0;
}

PassSet PassSet::missing_below(std::uint64_t total) const {
    PassSet missing;
    std::uint64_t next = 0;
    for (const Range &r : ranges_) {
        if (next >= total) break;
        if (r.first > next) missing.ranges_.push_back(Range{next, std::min(r.first, total)});
        next = r.end;
    }
    if (next < total) missing.ranges_.push_back(Range{next, total});
    return missing;
}

std::string PassSet::describe(const Range &r) {
    return r.end - r.first == 1 ? std::to_string(r.first) : std::to_string(r.first) + "-" + std::to_string(r.end - 1);
}

std::string PassSet::describe() const {
    if (ranges_.empty()) return "none";
    std::string text;
    for (const Range &r : ranges_) text += (text.empty() ? "" : ", ") + describe(r);
    return text;
}

bool PassSet::assign_checked(std::vector<Range> ranges) {
    for (std::size_t i = 0; i < ranges.size(); ++i) {
        if (ranges[i].first >= ranges[i].end) return false;
        if (i > 0 && ranges[i].first <= ranges[i - 1].end) return false;
    }
    ranges_ = std::move(ranges);
    return true;
}

} // namespace ppm
