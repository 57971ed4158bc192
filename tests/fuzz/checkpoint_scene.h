// SPDX-License-Identifier: Apache-2.0
// The fixed render that the checkpoint target loads checkpoints into, shared with the tool
// that writes its seed checkpoints: a diffuse floor, a mirror sphere and a point light seen
// by a 4 x 4 camera.
#pragma once

#include <ppm/ppm.h>

namespace fuzz {

// A renderer of the fixed scene in `mode` ("sppm" or "ppm"), seed 1, 64 photons per pass.
// Returns NULL after printing the error if something fails.
ppm_renderer create_checkpoint_renderer(ppm_context context, const char *mode);

} // namespace fuzz
