// SPDX-License-Identifier: Apache-2.0
// Renderer checkpoints through ppm_renderer_load_checkpoint, into a fixed 4 x 4 render (see
// checkpoint_scene.h) in the mode the input's header names. Each input is loaded twice: as
// given, which mostly exercises the header and checksum checks, and with its trailing FNV-1a
// checksum recomputed, so that mutated statistics and counts reach the checks behind the
// checksum. A checkpoint that loads must render one more finite pass.
#include "checkpoint_scene.h"
#include "fuzz_support.h"

#include <cstring>
#include <vector>

namespace {

// Header offset of the u32 mode (0 sppm, 1 ppm): magic, version, byte-order mark, width, height.
constexpr size_t kModeOffset = 8 + 4 + 4 + 4 + 4;

uint64_t fnv1a(const uint8_t *data, size_t size) {
    uint64_t hash = 14695981039346656037ull;
    for (size_t i = 0; i < size; ++i) hash = (hash ^ data[i]) * 1099511628211ull;
    return hash;
}

void load_and_render(const char *mode, const uint8_t *data, size_t size) {
    const std::string path = fuzz::write_temp_file("input.ckpt", data, size);
    ppm_renderer renderer = fuzz::create_checkpoint_renderer(fuzz::context(), mode);
    if (!renderer) fuzz::die("creating the checkpoint target's renderer");
    const ppm_status status = ppm_renderer_load_checkpoint(renderer, path.c_str());
    if (status == PPM_OK) {
        fuzz::render_one_pass(renderer);
    } else {
        fuzz::expect_located_error(status, {PPM_ERROR_IO, PPM_ERROR_PARSE, PPM_ERROR_INVALID_ARGUMENT}, "input.ckpt",
                                   "ppm_renderer_load_checkpoint");
    }
    ppm_renderer_release(renderer);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    uint32_t mode_value = 0;
    if (size >= kModeOffset + sizeof mode_value) std::memcpy(&mode_value, data + kModeOffset, sizeof mode_value);
    const char *mode = mode_value == 1 ? "ppm" : "sppm";
    load_and_render(mode, data, size);
    if (size >= sizeof(uint64_t)) {
        std::vector<uint8_t> fixed(data, data + size);
        const uint64_t hash = fnv1a(fixed.data(), size - sizeof hash);
        if (std::memcmp(fixed.data() + size - sizeof hash, &hash, sizeof hash) != 0) {
            std::memcpy(fixed.data() + size - sizeof hash, &hash, sizeof hash);
            load_and_render(mode, fixed.data(), size);
        }
    }
    return 0;
}
