// SPDX-License-Identifier: Apache-2.0
// The film: the render's progressive state per slot (a pixel in SPPM, a split camera path in
// PPM), the pixel each slot belongs to, this pass's direct light, and the pass and photon
// counts; the image layers are read from it. It knows no camera paths or photons: a pass
// ends by folding the photons found at each slot into the statistics (commit_pass).
//
// A pass-independent film (set_pass_independent) keeps no statistics from pass to pass: each
// pass's estimate is added to per-pixel fixed-point sums (PassSums, commit_independent_pass)
// and the image is their mean, so passes can be rendered in any order and merged.
//
// Threads: the running pass writes slots and direct light without a lock (distinct slots from
// distinct threads); commit_pass() and restore() take the lock that the readers (read_layer,
// with_state) take, so a reader sees the state after the last completed pass.
#pragma once

#include "core/context.h"
#include "film/pass_estimate.h"
#include "film/pass_sums.h"
#include "film/slot_photons.h"
#include "photon/sppm_statistics.h"

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace ppm {

class Film {
public:
    Film(int width, int height) : width_(width), height_(height) {}

    int width() const { return width_; }
    int height() const { return height_; }
    std::uint32_t pixel_count() const { return static_cast<std::uint32_t>(width_) * height_; }
    std::string description() const; // "the film of W x H pixels", for messages

    // Bytes per slot, for the allocation messages of those who make the slots.
    static constexpr std::uint64_t kSlotBytes = sizeof(std::uint32_t) + sizeof(PixelStatistics) + sizeof(Rgb);

    // The slots, one per entry of slot_pixel (the pixel each belongs to), with zero statistics.
    // Not while a pass runs or after one has completed (the statistics would be lost).
    void set_slots(std::vector<std::uint32_t> slot_pixel);
    void clear_slots() { slot_pixel_.clear(); } // made again by the next pass
    bool has_slots() const { return !slot_pixel_.empty(); }
    std::size_t slot_count() const { return slot_pixel_.size(); }
    const std::vector<std::uint32_t> &slot_pixels() const { return slot_pixel_; }

    const PixelStatistics &statistics(std::size_t slot) const { return stats_[slot]; }
    // The slot's gather radius squared this pass: its statistics', or `initial` before its first.
    double radius2(std::size_t slot, double initial) const { return stats_[slot].r2 > 0 ? stats_[slot].r2 : initial; }
    void set_pass_direct(std::size_t slot, const Rgb &direct) { pass_direct_[slot] = direct; }

    // Ends a pass: every slot's photons taken from photons_found into its statistics (radius
    // reduced by alpha), its direct light added, and the counts advanced.
    void commit_pass(Context &context, SlotPhotons &photons_found, double alpha, std::uint64_t photons);

    // A pass-independent film: not after a pass has completed.
    void set_pass_independent(bool independent);
    bool pass_independent() const { return independent_; }
    // Ends pass `pass` of a pass-independent film: each slot's estimate of this pass, its
    // photons' flux over pi r^2 and `photons` emitted plus its direct light, added to its
    // pixel's sums. The pass must not be in the film yet.
    void commit_independent_pass(Context &context, SlotPhotons &photons_found, std::uint64_t pass,
                                 std::uint64_t photons);
    // Ends pass `pass` of a pass-independent film from an estimate made whole by the mode.
    void commit_estimated_pass(std::uint64_t pass, const PassEstimate &estimate);
    // f(sums) under the readers' lock (pass-independent films).
    template <class F> void with_sums(F &&f) const {
        std::lock_guard<std::mutex> lock(mutex_);
        f(sums_);
    }
    // Adds another render's sums of disjoint passes (checked by the caller).
    void merge_sums(const PassSums &other);
    // The lowest pass index this pass-independent film does not hold.
    std::uint64_t lowest_missing_pass() const;
    bool holds_pass(std::uint64_t pass) const;

    std::uint64_t passes() const { return passes_.load(); }
    std::uint64_t photons_emitted() const { return photons_emitted_.load(); }

    // Per-pixel layers, row-major from the top-left pixel:
    //   "radiance": 3 floats per pixel, linear RGB radiance (the image);
    //   "radius":   1 float, the gather radius (largest over a pixel's slots, 0 before any);
    //   "photons":  1 float, N, the (alpha-reduced) photon count of the pixel's statistics.
    static std::size_t layer_channels(const std::string &name); // throws for an unknown name
    void read_layer(const std::string &name, float *out) const;

    // f(slot_pixel, statistics, passes, photons_emitted) under the readers' lock: the state
    // after the last completed pass (no slots before the first).
    template <class F> void with_state(F &&f) const {
        std::lock_guard<std::mutex> lock(mutex_);
        const std::uint64_t passes = passes_.load();
        static const std::vector<std::uint32_t> no_slots;
        static const std::vector<PixelStatistics> no_stats;
        if (passes == 0) return f(no_slots, no_stats, passes, photons_emitted_.load());
        f(slot_pixel_, stats_, passes, photons_emitted_.load());
    }
    // A checkpoint's state, for slots already made as the checkpoint's render made them.
    void restore(std::vector<PixelStatistics> stats, std::uint64_t passes, std::uint64_t photons_emitted);

private:
    void ensure_sums(); // one entry per pixel, under the lock

    int width_, height_;
    std::vector<std::uint32_t> slot_pixel_;
    std::vector<PixelStatistics> stats_;
    std::vector<Rgb> pass_direct_;
    bool independent_ = false;
    PassSums sums_; // pass-independent films: one entry per pixel, made with the first pass
    std::atomic<std::uint64_t> passes_{0};
    std::atomic<std::uint64_t> photons_emitted_{0};
    mutable std::mutex mutex_;
};

} // namespace ppm
