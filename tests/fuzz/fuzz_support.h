// SPDX-License-Identifier: Apache-2.0
// Shared pieces of the fuzz targets: a private temporary folder for loaders that take a path,
// one context for the whole process, and a tiny render whose pixels must come out finite and
// non-negative. Every check that fails prints what and aborts, so libFuzzer (and the replay
// driver under ctest) reports it like a sanitizer error.
#pragma once

#include <ppm/ppm.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>

namespace fuzz {

// The film of every render: small enough that a pass takes well under a millisecond.
constexpr uint32_t kFilmSize = 8;
constexpr int64_t kPhotonsPerPass = 256;
constexpr int64_t kMaxDepth = 4;

// Prints "fuzz target: <what>" and the library's last error message, then aborts.
[[noreturn]] void die(const std::string &what);

// A context with one worker thread, created on first use and kept for the process.
ppm_context context();

// Writes `size` bytes to `name` inside the process's temporary folder (removed at exit) and
// returns the file's path. The folder also holds whatever files copy_into_temp put there.
std::string write_temp_file(const std::string &name, const uint8_t *data, size_t size);

// Limits a renderer's work to one tiny pass: kFilmSize film is the caller's job, this caps
// photons per pass and path depth (the file's values are kept when they are smaller).
void limit_renderer(ppm_renderer renderer);

// Runs one pass that must succeed, then checks that the pass count grew by one from a
// non-negative value and that every value of the radiance, radius and photons layers is
// finite and >= 0.
void render_one_pass(ppm_renderer renderer);

// For a committed scene of loaded geometry: fires a few rays at it (hits must be finite), then
// frames it with a kFilmSize camera and a point light and renders one pass. Scenes whose
// bounds overflow when the camera is placed around them are only intersected.
void check_geometry_scene(ppm_scene scene);

} // namespace fuzz

namespace fuzz {

// A failed load must report one of the statuses the header lists for it, with a message that
// names the file (its base name is enough). With PPM_FUZZ_VERBOSE set in the environment
// every refusal's message is printed, to see what a corpus file exercises.
void expect_located_error(ppm_status status, std::initializer_list<ppm_status> allowed, const std::string &file_name,
                          const char *call);

} // namespace fuzz
