// SPDX-License-Identifier: Apache-2.0
// The C ABI of materials, textures, lights and the renderer.
#include <ppm/ppm.h>

#include "api/api_camera.h"
#include "api/api_renderer.h"
#include "api/api_support.h"
#include "scene/patch_geometry.h"
#include "scene/quad_geometry.h"
#include "scene/sphere_geometry.h"

#include <cmath>
#include <cstring>

namespace {

using namespace ppm::api;
using ppm::invalid_argument;

ppm::Rgb read_color(const double *c, const char *name) {
    require(c, name);
    const ppm::Rgb rgb{c[0], c[1], c[2]};
    if (!rgb.is_finite() || rgb.min() < 0)
        invalid_argument(std::string(name) + " must be finite and >= 0 in every channel");
    return rgb;
}

// An intensity or radiance: a colour no larger than the emission limit (math/limits.h).
ppm::Rgb read_emission(const double *c, const char *name) {
    const ppm::Rgb rgb = read_color(c, name);
    if (rgb.max() > ppm::kEmissionLimit)
        invalid_argument(std::string(name) + " " + ppm::format_number(rgb.max()) + " exceeds the limit " +
                         ppm::format_number(ppm::kEmissionLimit) + " of light values");
    return rgb;
}

ppm::Rgb read_reflectance(const double *c, const char *name) {
    const ppm::Rgb rgb = read_color(c, name);
    if (rgb.max() > 1)
        invalid_argument(std::string(name) + " must be at most 1 in every channel (energy conservation)");
    return rgb;
}

template <class Make> ppm_status add_material(ppm_scene scene, uint32_t *out_id, Make &&make) {
    return scene_call(scene, [&](ppm_scene_t &s) {
        ppm::Material material{make(), {}};
        write_id(out_id, s.shading.add_material(std::move(material)));
    });
}

// The renderer's read-only values (its settings are RenderSettings' keys): true and the value
// in *out when `key` is one of the type asked for.
bool read_only_int(const ppm::Renderer &r, const std::string &key, int64_t *out) {
    if (key == "passes")
        *out = static_cast<int64_t>(r.passes());
    else if (key == "photons_emitted")
        *out = static_cast<int64_t>(r.photons_emitted());
    else if (key == "paths_per_pass")
        *out = static_cast<int64_t>(r.paths_per_pass());
    else if (key == "width")
        *out = r.width();
    else if (key == "height")
        *out = r.height();
    else if (key == "lights")
        *out = static_cast<int64_t>(r.light_count());
    else
        return false;
    return true;
}

bool read_only_double(const ppm::Renderer &r, const std::string &key, double *out) {
    if (key == "last_eye_pass_seconds")
        *out = r.last_eye_seconds();
    else if (key == "last_photon_pass_seconds")
        *out = r.last_photon_seconds();
    else if (key == "last_search_build_seconds")
        *out = r.last_search_build_seconds();
    else
        return false;
    return true;
}

void refuse_read_only(const ppm::Renderer &r, const char *key) {
    require_key(key);
    int64_t i = 0;
    double d = 0;
    if (read_only_int(r, key, &i) || read_only_double(r, key, &d))
        invalid_argument(std::string("render value '") + key + "' is read-only");
}

} // namespace

extern "C" {

ppm_status ppm_scene_add_diffuse_material(ppm_scene scene, const double reflectance[3], uint32_t *out_id) {
    return add_material(scene, out_id,
                        [&] { return ppm::Bsdf::diffuse(read_reflectance(reflectance, "reflectance")); });
}

ppm_status ppm_scene_add_mirror_material(ppm_scene scene, const double specular_reflectance[3], uint32_t *out_id) {
    return add_material(scene, out_id, [&] {
        return ppm::Bsdf::mirror(read_reflectance(specular_reflectance, "specular_reflectance"));
    });
}

ppm_status ppm_scene_add_dielectric_material(ppm_scene scene, double int_ior, double ext_ior, uint32_t *out_id) {
    return add_material(scene, out_id, [&] { return ppm::Bsdf::dielectric(int_ior, ext_ior); });
}

ppm_status ppm_scene_add_coated_material(ppm_scene scene, const double diffuse_reflectance[3], double int_ior,
                                         double ext_ior, uint32_t *out_id) {
    return add_material(scene, out_id, [&] {
        return ppm::Bsdf::coated(read_reflectance(diffuse_reflectance, "diffuse_reflectance"), int_ior, ext_ior);
    });
}

ppm_status ppm_scene_set_material_texture(ppm_scene scene, uint32_t material_id, const char *path,
                                          const double scale[2], const double offset[2]) {
    return scene_call(scene, [&](ppm_scene_t &s) {
        require(path, "path");
        ppm::Material &material = s.shading.material(material_id);
        if (material.kind != ppm::Material::Kind::Single)
            invalid_argument("material " + std::to_string(material_id) +
                             " is a blend or mask of others: texture those instead");
        const ppm::Bsdf::Type type = material.bsdf.type();
        if (type == ppm::Bsdf::Type::Dielectric || type == ppm::Bsdf::Type::ThinDielectric ||
            type == ppm::Bsdf::Type::RoughDielectric)
            invalid_argument("material " + std::to_string(material_id) + " is glass, which has no colour to texture");
        double scale_uv[2] = {1, 1}, offset_uv[2] = {0, 0};
        if (scale) {
            if (!std::isfinite(scale[0]) || !std::isfinite(scale[1]) || scale[0] == 0 || scale[1] == 0)
                invalid_argument("texture scale must be finite and non-zero");
            scale_uv[0] = scale[0];
            scale_uv[1] = scale[1];
        }
        if (offset) {
            if (!std::isfinite(offset[0]) || !std::isfinite(offset[1]))
                invalid_argument("texture offset must be finite");
            offset_uv[0] = offset[0];
            offset_uv[1] = offset[1];
        }
        material.texture = ppm::TextureRef::bitmap(
            ppm::Texture::load(path),
            ppm::TextureMapping::scale_offset(scale_uv[0], scale_uv[1], offset_uv[0], offset_uv[1]));
    });
}

ppm_status ppm_scene_set_patch_uv_rects(ppm_scene scene, uint32_t geom_id, const double *rects) {
    return scene_call(scene, [&](ppm::Scene &s) {
        require(rects, "rects");
        auto *patches = dynamic_cast<ppm::PatchGeometry *>(&s.geometry(geom_id));
        if (!patches) invalid_argument("geometry " + std::to_string(geom_id) + " is not a patch set");
        std::vector<double> values(rects, rects + 4 * patches->primitive_count());
        for (size_t i = 0; i < values.size(); ++i)
            if (!std::isfinite(values[i]))
                invalid_argument("uv rect of patch " + std::to_string(i / 4) + " has a NaN or infinite value");
        patches->set_uv_rects(std::move(values));
    });
}

ppm_status ppm_scene_add_point_light(ppm_scene scene, const double position[3], const double intensity[3],
                                     uint32_t *out_light_id) {
    return scene_call(scene, [&](ppm_scene_t &s) {
        const ppm::Vec3 p = finite_point(position, "position");
        write_id(out_light_id, s.shading.add_light(ppm::Light::point(p, read_emission(intensity, "intensity"))));
    });
}

ppm_status ppm_scene_add_spot_light(ppm_scene scene, const double position[3], const double target[3],
                                    const double intensity[3], double cutoff_angle, double beam_width,
                                    uint32_t *out_light_id) {
    return scene_call(scene, [&](ppm_scene_t &s) {
        const ppm::Vec3 p = finite_point(position, "position"), t = finite_point(target, "target");
        write_id(out_light_id, s.shading.add_light(ppm::Light::spot(p, t, read_emission(intensity, "intensity"),
                                                                    cutoff_angle, beam_width)));
    });
}

ppm_status ppm_scene_set_geometry_emission(ppm_scene scene, uint32_t geom_id, const double radiance[3]) {
    return scene_call(scene, [&](ppm_scene_t &s) {
        ppm::Geometry &g = s.geometry(geom_id);
        const ppm::Rgb rgb = read_emission(radiance, "radiance");
        if (dynamic_cast<ppm::PatchGeometry *>(&g))
            invalid_argument("geometry " + std::to_string(geom_id) + " is a " + g.kind() +
                             "; Bezier patches cannot be area lights (quads, spheres, disks, cylinders and "
                             "triangle meshes can: tessellate the patches into a mesh to make them emit)");
        s.shading.set_emission(geom_id, rgb);
        // Every shadow ray towards the light names it (RayHints::skip_geometry).
        if (!rgb.is_black()) s.prefer_mask_bit(geom_id);
    });
}

/* Renderer ---------------------------------------------------------------------------- */

ppm_status ppm_renderer_create(ppm_scene scene, const ppm_camera *camera, ppm_renderer *out_renderer) {
    return scene_call(scene, [&](ppm_scene_t &s) {
        require(out_renderer, "out_renderer");
        *out_renderer = new ppm_renderer_t(s, camera_settings(camera));
    });
}

ppm_status ppm_renderer_create_v2(ppm_scene scene, const ppm_camera_v2 *camera, ppm_renderer *out_renderer) {
    return scene_call(scene, [&](ppm_scene_t &s) {
        require(out_renderer, "out_renderer");
        *out_renderer = new ppm_renderer_t(s, camera_settings(camera));
    });
}

ppm_status ppm_renderer_get_camera_v2(ppm_renderer renderer, ppm_camera_v2 *out_camera) {
    return renderer_call(renderer, [&](ppm::Renderer &) { write_camera(renderer->camera, out_camera); });
}

ppm_status ppm_renderer_retain(ppm_renderer renderer) {
    return renderer_call(renderer, [](ppm::Renderer &r) { r.retain(); });
}

void ppm_renderer_release(ppm_renderer renderer) {
    if (renderer) renderer->release();
}

ppm_status ppm_renderer_set_int(ppm_renderer renderer, const char *key, int64_t value) {
    return renderer_call(renderer, [&](ppm::Renderer &r) {
        refuse_read_only(r, key);
        r.settings().set_int(key, value, r.started());
    });
}

ppm_status ppm_renderer_set_double(ppm_renderer renderer, const char *key, double value) {
    return renderer_call(renderer, [&](ppm::Renderer &r) {
        refuse_read_only(r, key);
        r.settings().set_double(key, value, r.started());
    });
}

ppm_status ppm_renderer_set_string(ppm_renderer renderer, const char *key, const char *value) {
    return renderer_call(renderer, [&](ppm::Renderer &r) {
        refuse_read_only(r, key);
        require(value, "value");
        r.settings().set_string(key, value, r.started());
    });
}

ppm_status ppm_renderer_get_int(ppm_renderer renderer, const char *key, int64_t *out_value) {
    return renderer_call(renderer, [&](ppm::Renderer &r) {
        require_key(key);
        require(out_value, "out_value");
        double seconds = 0;
        if (read_only_double(r, key, &seconds))
            invalid_argument(std::string("render value '") + key +
                             "' is a double, not an integer: read it as a double");
        if (!read_only_int(r, key, out_value)) *out_value = r.settings().get_int(key);
    });
}

ppm_status ppm_renderer_get_double(ppm_renderer renderer, const char *key, double *out_value) {
    return renderer_call(renderer, [&](ppm::Renderer &r) {
        require_key(key);
        require(out_value, "out_value");
        int64_t count = 0;
        if (read_only_int(r, key, &count))
            *out_value = static_cast<double>(count);
        else if (!read_only_double(r, key, out_value))
            *out_value = r.settings().get_double(key);
    });
}

ppm_status ppm_renderer_get_string(ppm_renderer renderer, const char *key, char *out, size_t capacity,
                                   size_t *out_length) {
    return renderer_call(renderer, [&](ppm::Renderer &r) {
        require_key(key);
        if (capacity > 0) require(out, "out");
        const std::string value = r.settings().get_string(key);
        if (capacity > 0) {
            const size_t n = std::min(capacity - 1, value.size());
            std::memcpy(out, value.data(), n);
            out[n] = '\0';
        }
        if (out_length) *out_length = value.size();
    });
}

ppm_status ppm_renderer_render_pass(ppm_renderer renderer) {
    return renderer_call(renderer, [](ppm::Renderer &r) { r.render_pass(); });
}

// libppm 0.1's name of ppm_renderer_render_pass, exported for the programs built against it.
ppm_status ppm_render_pass(ppm_renderer renderer) { return ppm_renderer_render_pass(renderer); }

ppm_status ppm_renderer_cancel(ppm_renderer renderer) {
    return renderer_call(renderer, [](ppm::Renderer &r) { r.cancel(); });
}

ppm_status ppm_renderer_get_layer(ppm_renderer renderer, const char *layer, float *out, size_t count) {
    return renderer_call(renderer, [&](ppm::Renderer &r) {
        require(layer, "layer");
        const size_t needed = static_cast<size_t>(r.width()) * r.height() * ppm::Renderer::layer_channels(layer);
        require(out, "out");
        if (count < needed)
            invalid_argument("layer '" + std::string(layer) + "' needs " + std::to_string(needed) +
                             " floats, out holds " + std::to_string(count));
        r.read_layer(layer, out);
    });
}

ppm_status ppm_renderer_save_checkpoint(ppm_renderer renderer, const char *path) {
    return renderer_call(renderer, [&](ppm::Renderer &r) {
        require(path, "path");
        r.save_checkpoint(path);
    });
}

ppm_status ppm_renderer_load_checkpoint(ppm_renderer renderer, const char *path) {
    return renderer_call(renderer, [&](ppm::Renderer &r) {
        require(path, "path");
        r.load_checkpoint(path);
    });
}

} // extern "C"
