// SPDX-License-Identifier: Apache-2.0
#include "api/api_camera.h"

#include "api/api_support.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>

namespace ppm::api {

namespace {

// The size of the first ppm_camera_v2, which ends with `reserved`: fields are appended after
// it, so this stays the size callers compiled against the first header pass, and they are
// served.
constexpr size_t kFirstCameraV2Size = offsetof(ppm_camera_v2, reserved) + sizeof(ppm_camera_v2{}.reserved);
// A size no version will reach. Larger is taken for an uninitialised struct, whose bytes the
// library must not read past what the caller allocated.
constexpr size_t kMaxCameraV2Size = 4096;

void check_size(size_t size, const char *name) {
    if (size < kFirstCameraV2Size || size > kMaxCameraV2Size)
        invalid_argument(std::string(name) + "->size is " + std::to_string(size) +
                         ", expected sizeof(ppm_camera_v2) (" + std::to_string(sizeof(ppm_camera_v2)) +
                         " in this libppm): initialise the struct with " + "ppm_camera_v2_init");
}

// The fields ppm_camera and ppm_camera_v2 share.
template <class Camera> ppm::CameraSettings from_fields(const Camera &camera) {
    ppm::CameraSettings c;
    c.origin = finite_point(camera.origin, "camera origin");
    c.target = finite_point(camera.target, "camera target");
    c.up = finite_point(camera.up, "camera up");
    c.fov = camera.fov;
    if (camera.width > (1u << 28) || camera.height > (1u << 28))
        invalid_argument("camera width and height must be at most 2^28, not " + std::to_string(camera.width) + " x " +
                         std::to_string(camera.height));
    c.width = static_cast<int>(camera.width);
    c.height = static_cast<int>(camera.height);
    c.aperture_radius = camera.aperture_radius;
    c.focus_distance = camera.focus_distance;
    c.near_clip = camera.near_clip;
    return c;
}

int crop_coordinate(uint32_t value, const char *name) {
    if (value > (1u << 28))
        invalid_argument(std::string("camera ") + name + " must be at most 2^28, not " + std::to_string(value));
    return static_cast<int>(value);
}

} // namespace

ppm::CameraSettings camera_settings(const ppm_camera *camera) {
    require(camera, "camera");
    return from_fields(*camera);
}

ppm::CameraSettings camera_settings(const ppm_camera_v2 *camera) {
    require(camera, "camera");
    const size_t size = camera->size;
    check_size(size, "camera");
    // Bytes of a newer struct that this library does not know: 0 means "as before".
    const auto *bytes = reinterpret_cast<const unsigned char *>(camera);
    for (size_t i = sizeof(ppm_camera_v2); i < size; ++i)
        if (bytes[i] != 0)
            fail(PPM_ERROR_UNSUPPORTED, "camera byte " + std::to_string(i) + " of " + std::to_string(size) +
                                            " is not 0: a field that libppm " PPM_VERSION_STRING
                                            " does not know (it knows the first " +
                                            std::to_string(sizeof(ppm_camera_v2)) + " bytes)");
    ppm_camera_v2 known;
    std::memset(&known, 0, sizeof known);
    std::memcpy(&known, camera, std::min(size, sizeof known));
    for (size_t i = 0; i < sizeof known.reserved / sizeof known.reserved[0]; ++i)
        if (known.reserved[i] != 0) invalid_argument("camera reserved[" + std::to_string(i) + "] is not 0");
    ppm::CameraSettings settings = from_fields(known);
    settings.crop_x0 = crop_coordinate(known.crop_x0, "crop_x0");
    settings.crop_y0 = crop_coordinate(known.crop_y0, "crop_y0");
    settings.crop_x1 = crop_coordinate(known.crop_x1, "crop_x1");
    settings.crop_y1 = crop_coordinate(known.crop_y1, "crop_y1");
    settings.principal_point_offset_x = known.principal_point_offset_x;
    settings.principal_point_offset_y = known.principal_point_offset_y;
    if (known.reserved_pad != 0) invalid_argument("camera reserved_pad is not 0");
    if (known.pixel_filter > PPM_PIXEL_FILTER_GAUSSIAN)
        invalid_argument("camera pixel_filter " + std::to_string(known.pixel_filter) +
                         " is not PPM_PIXEL_FILTER_BOX (0), _TENT (1) or _GAUSSIAN (2)");
    settings.filter.type = static_cast<ppm::PixelFilterType>(known.pixel_filter);
    settings.filter.parameter = known.pixel_filter_parameter;
    if (settings.filter.type == ppm::PixelFilterType::Box && known.pixel_filter_parameter != 0)
        invalid_argument("camera pixel_filter_parameter must be 0 for the box filter");
    return settings;
}

void write_camera(const ppm::CameraSettings &settings, ppm_camera_v2 *out) {
    require(out, "out_camera");
    const size_t size = out->size;
    check_size(size, "out_camera");
    ppm_camera_v2 camera;
    std::memset(&camera, 0, sizeof camera);
    camera.size = size;
    settings.origin.store(camera.origin);
    settings.target.store(camera.target);
    settings.up.store(camera.up);
    camera.fov = settings.fov;
    camera.width = static_cast<uint32_t>(settings.width);
    camera.height = static_cast<uint32_t>(settings.height);
    camera.aperture_radius = settings.aperture_radius;
    camera.focus_distance = settings.focus_distance;
    camera.near_clip = settings.near_clip;
    camera.crop_x0 = static_cast<uint32_t>(settings.crop_x0);
    camera.crop_y0 = static_cast<uint32_t>(settings.crop_y0);
    camera.crop_x1 = static_cast<uint32_t>(settings.crop_x1);
    camera.crop_y1 = static_cast<uint32_t>(settings.crop_y1);
    camera.principal_point_offset_x = settings.principal_point_offset_x;
    camera.principal_point_offset_y = settings.principal_point_offset_y;
    camera.pixel_filter = static_cast<uint32_t>(settings.filter.type);
    camera.pixel_filter_parameter = settings.filter.parameter;
    std::memcpy(out, &camera, std::min(size, sizeof camera));
    if (size > sizeof camera)
        std::memset(reinterpret_cast<unsigned char *>(out) + sizeof camera, 0, size - sizeof camera);
}

} // namespace ppm::api
