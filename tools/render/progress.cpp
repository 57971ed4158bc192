// SPDX-License-Identifier: Apache-2.0
#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ppm_render {

void format_duration(double seconds, char *out, unsigned size) {
    const long total = std::lround(std::max(seconds, 0.0));
    if (total >= 3600)
        std::snprintf(out, size, "%ld:%02ld:%02ld", total / 3600, total / 60 % 60, total % 60);
    else
        std::snprintf(out, size, "%ld:%02ld", total / 60, total % 60);
}

ProgressBar::ProgressBar(bool enabled) : enabled_(enabled && isatty(STDERR_FILENO)) {}

void ProgressBar::update(std::uint64_t passes, std::uint64_t target_passes, double photons_per_second, double elapsed,
                         double eta_seconds) {
    if (!enabled_) return;
    constexpr int width = 24;
    char bar[width + 1];
    const double fraction =
        target_passes > 0 ? std::min(1.0, static_cast<double>(passes) / static_cast<double>(target_passes))
                          : (eta_seconds >= 0 && elapsed + eta_seconds > 0 ? elapsed / (elapsed + eta_seconds) : 0);
    const int filled = static_cast<int>(fraction * width);
    for (int i = 0; i < width; ++i) bar[i] = i < filled ? '#' : '.';
    bar[width] = '\0';
    char elapsed_text[32], eta_text[32] = "?";
    format_duration(elapsed, elapsed_text, sizeof elapsed_text);
    if (eta_seconds >= 0) format_duration(eta_seconds, eta_text, sizeof eta_text);
    char target[32] = "";
    if (target_passes > 0)
        std::snprintf(target, sizeof target, "/%llu", static_cast<unsigned long long>(target_passes));
    std::fprintf(stderr, "\r[%s] pass %llu%s  %.2f M photons/s  %s elapsed  ETA %s \033[K", bar,
                 static_cast<unsigned long long>(passes), target, photons_per_second / 1e6, elapsed_text, eta_text);
    std::fflush(stderr);
    drawn_ = true;
}

void ProgressBar::finish() {
    if (drawn_) std::fputc('\n', stderr);
    drawn_ = false;
}

} // namespace ppm_render
