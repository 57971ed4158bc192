// SPDX-License-Identifier: Apache-2.0
// The public camera structs (ppm_camera, ppm_camera_v2) to and from the renderer's
// CameraSettings. Values are checked by ppm::Camera when the renderer is built; here only what
// the structs themselves can get wrong: NULL, a coordinate beyond the limit, an image side
// beyond 2^28, and for ppm_camera_v2 its size and reserved words.
#pragma once

#include <ppm/ppm.h>

#include "camera/camera.h"

namespace ppm::api {

ppm::CameraSettings camera_settings(const ppm_camera *camera);
ppm::CameraSettings camera_settings(const ppm_camera_v2 *camera);

// Writes `settings` into the first out->size bytes of *out (0 beyond the fields this library
// knows), leaving out->size as it is. Throws INVALID_ARGUMENT for NULL or a size out of range.
void write_camera(const ppm::CameraSettings &settings, ppm_camera_v2 *out);

} // namespace ppm::api
