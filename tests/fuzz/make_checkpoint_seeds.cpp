// SPDX-License-Identifier: Apache-2.0
// Writes the checkpoint target's seeds into a folder: for each mode, the checkpoint of a
// renderer that has not run a pass and the one after two passes.
//
//   make_checkpoint_seeds DIR
#include "checkpoint_scene.h"

#include <cstdio>
#include <string>

int main(int argc, char **argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 1;
    }
    ppm_context context = nullptr;
    if (ppm_context_create(&context) != PPM_OK || ppm_context_set_int(context, "threads", 1) != PPM_OK) return 2;
    for (const char *mode : {"sppm", "ppm"}) {
        ppm_renderer renderer = fuzz::create_checkpoint_renderer(context, mode);
        if (!renderer) return 2;
        const std::string base = std::string(argv[1]) + "/" + mode;
        bool ok = ppm_renderer_save_checkpoint(renderer, (base + "-0-passes.ckpt").c_str()) == PPM_OK &&
                  ppm_render_pass(renderer) == PPM_OK && ppm_render_pass(renderer) == PPM_OK &&
                  ppm_renderer_save_checkpoint(renderer, (base + "-2-passes.ckpt").c_str()) == PPM_OK;
        ppm_renderer_release(renderer);
        if (!ok) {
            std::fprintf(stderr, "%s: %s\n", mode, ppm_last_error_message());
            return 2;
        }
    }
    ppm_context_release(context);
    return 0;
}
