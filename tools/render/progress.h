// SPDX-License-Identifier: Apache-2.0
// The progress bar on stderr: pass, photons per second, elapsed time and ETA, redrawn in
// place. Silent when stderr is not a terminal (logs get the summary line only) or --quiet.
#pragma once

#include <cstdint>

namespace ppm_render {

class ProgressBar {
public:
    explicit ProgressBar(bool enabled);
    // `target_passes` 0: unknown (time budget only); `eta_seconds` < 0: unknown.
    void update(std::uint64_t passes, std::uint64_t target_passes, double photons_per_second, double elapsed,
                double eta_seconds);
    // Ends the line the bar is drawn on, so that later output starts on a fresh line.
    void finish();

private:
    bool enabled_;
    bool drawn_ = false;
};

// "1:05", "1:02:03".
void format_duration(double seconds, char *out, unsigned size);

} // namespace ppm_render
