// SPDX-License-Identifier: Apache-2.0
#include "scenefile/scene_builder.h"

#include "core/error.h"
#include "geometry/cube_mesh.h"
#include "math/frame.h"
#include "scenefile/scene_params.h"
#include "scenefile/transform.h"

#include <sys/stat.h>

#include <array>
#include <cmath>
#include <vector>

namespace ppm {

namespace {

std::array<double, 3> to_array(const Vec3 &v) { return {v.x, v.y, v.z}; }

// A colour given as {"type": "bitmap", ...} rather than a number, [r, g, b] or {"type": "rgb"}.
bool is_bitmap(const JsonNode &color) {
    return color.is_object() && color.has("type") && color.at("type").is_string() &&
           color.at("type").string() == "bitmap";
}

// A texture the generic path reads (ppm_scene_add_texture): any texture object but a bitmap
// with only the keys of libppm's older form (filename, scale, offset).
bool is_generic_texture(const JsonNode &color) {
    if (!color.is_object() || !color.has("type") || !color.at("type").is_string()) return false;
    const std::string type = color.at("type").string();
    if (type == "rgb" || type == "spectrum") return false;
    if (type != "bitmap") return true;
    for (const std::string &key : color.keys())
        if (key != "type" && key != "filename" && key != "scale" && key != "offset") return true;
    return false;
}

} // namespace

void SceneBuilder::check(const JsonNode &node, ppm_status status) const {
    if (status != PPM_OK) fail(status, node.where() + ": " + ppm_last_error_message());
}

std::string SceneBuilder::existing_file(const JsonNode &filename) const {
    const std::string name = filename.string();
    if (name.empty()) filename.fail("expected a file name");
    const std::string path = name[0] == '/' ? name : folder_ + name;
    struct stat info {};
    if (stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode))
        fail(PPM_ERROR_IO, filename.where() + ": file not found: " + path);
    return path;
}

// ---------------------------------------------------------------------------------------------
// bsdfs

void SceneBuilder::add_bsdfs(const JsonNode &bsdfs) {
    bsdfs.require_object();
    for (const std::string &name : bsdfs.keys()) named_bsdfs_[name] = add_bsdf(bsdfs.at(name.c_str()));
}

std::uint32_t SceneBuilder::add_bsdf(const JsonNode &bsdf) {
    bsdf.require_object();
    const std::string type = bsdf.at("type").string();
    std::uint32_t id = 0;
    const char *const color_keys[] = {"reflectance", "specular_reflectance", "diffuse_reflectance"};
    // Every type but these three goes to the API's material table (conductor and
    // roughconductor among them: their eta, k and named materials), as does any material whose
    // colour is a texture other than the plain bitmap form.
    bool generic = type != "diffuse" && type != "dielectric" && type != "plastic";
    for (const char *key : color_keys) generic = generic || (bsdf.has(key) && is_generic_texture(bsdf.at(key)));
    if (generic) {
        const SceneParams params = params_of(bsdf);
        params.check(ppm_scene_add_material(scene_, type.c_str(), params.data(), params.size(), &id));
        return id;
    }
    // The colour key, which may instead hold a bitmap texture.
    const char *color_key = nullptr;
    const double default_color = 0.5;
    if (type == "diffuse") {
        bsdf.allow_only({"type", "reflectance"});
        color_key = "reflectance";
    } else if (type == "plastic") {
        bsdf.allow_only({"type", "diffuse_reflectance", "int_ior", "ext_ior", "nonlinear"});
        if (bsdf.has("nonlinear") && bsdf.at("nonlinear").boolean())
            bsdf.at("nonlinear").fail("nonlinear plastic is not supported (only false)");
        color_key = "diffuse_reflectance";
    } else {
        bsdf.allow_only({"type", "int_ior", "ext_ior"});
    }

    std::array<double, 3> color{default_color, default_color, default_color};
    const bool textured = color_key && bsdf.has(color_key) && is_bitmap(bsdf.at(color_key));
    if (color_key && bsdf.has(color_key) && !textured) color = bsdf.at(color_key).color(true);
    const auto ior = [&](const char *key, double fallback) {
        return bsdf.has(key) ? bsdf.at(key).positive() : fallback;
    };

    if (type == "diffuse") {
        check(bsdf, ppm_scene_add_diffuse_material(scene_, color.data(), &id));
    } else if (type == "plastic") {
        check(bsdf,
              ppm_scene_add_coated_material(scene_, color.data(), ior("int_ior", 1.49), ior("ext_ior", 1.000277), &id));
    } else {
        check(bsdf, ppm_scene_add_dielectric_material(scene_, ior("int_ior", 1.5046), ior("ext_ior", 1.000277), &id));
    }

    if (textured) {
        const JsonNode texture = bsdf.at(color_key);
        texture.allow_only({"type", "filename", "scale", "offset"});
        const std::string path = existing_file(texture.at("filename"));
        std::array<double, 2> scale{1, 1}, offset{0, 0};
        if (texture.has("scale")) {
            const JsonNode s = texture.at("scale");
            if (s.is_number()) {
                scale = {s.number(), s.number()};
            } else {
                if (!s.is_array() || s.size() != 2) s.fail("expected a number or [su, sv]");
                scale = {s[0].number(), s[1].number()};
            }
            if (scale[0] == 0 || scale[1] == 0) s.fail("a texture scale must not be zero");
        }
        if (texture.has("offset")) {
            const JsonNode o = texture.at("offset");
            if (!o.is_array() || o.size() != 2) o.fail("expected [ou, ov]");
            offset = {o[0].number(), o[1].number()};
        }
        check(texture, ppm_scene_set_material_texture(scene_, id, path.c_str(), scale.data(), offset.data()));
    }
    return id;
}

SceneParams SceneBuilder::params_of(const JsonNode &object) {
    return SceneParams(
        object, folder_, [this](const JsonNode &nested) { return nested_material(nested); },
        [this](const JsonNode &nested) { return add_texture(nested); });
}

std::uint32_t SceneBuilder::nested_material(const JsonNode &bsdf) {
    if (bsdf.is_object()) return add_bsdf(bsdf);
    const std::string name = bsdf.string();
    const auto found = named_bsdfs_.find(name);
    if (found == named_bsdfs_.end()) bsdf.fail("no bsdf named '" + name + "' in bsdfs");
    return found->second;
}

std::uint32_t SceneBuilder::add_texture(const JsonNode &texture) {
    texture.require_object();
    const std::string type = texture.at("type").string();
    const SceneParams params = params_of(texture);
    std::uint32_t id = 0;
    params.check(ppm_scene_add_texture(scene_, type.c_str(), params.data(), params.size(), &id));
    return id;
}

// ---------------------------------------------------------------------------------------------
// emitters

void SceneBuilder::add_emitters(const JsonNode &emitters) {
    emitters.require_array();
    for (std::size_t i = 0; i < emitters.size(); ++i) add_emitter(emitters[i]);
}

void SceneBuilder::add_emitter(const JsonNode &emitter) {
    emitter.require_object();
    const std::string type = emitter.at("type").string();
    if (type != "point" && type != "spot") {
        // Every other type as the API's light table reads it (it names unknown types).
        const SceneParams params = params_of(emitter);
        params.check(ppm_scene_add_light(scene_, type.c_str(), params.data(), params.size(), nullptr));
        return;
    }
    const std::array<double, 3> intensity =
        emitter.has("intensity") ? emitter.at("intensity").color(false) : std::array<double, 3>{1, 1, 1};
    if (type == "point") {
        // Placed by `position` or, as Mitsuba also allows, by where `to_world` takes the origin.
        emitter.allow_only({"type", "position", "to_world", "intensity"});
        if (emitter.has("position") && emitter.has("to_world"))
            emitter.fail("a point light takes 'position' or 'to_world', not both");
        const std::array<double, 3> position = emitter.has("to_world")
                                                   ? to_array(parse_transform(emitter.at("to_world")).point({0, 0, 0}))
                                                   : emitter.vec3_or("position", {0, 0, 0});
        check(emitter, ppm_scene_add_point_light(scene_, position.data(), intensity.data(), nullptr));
        return;
    }
    emitter.allow_only({"type", "to_world", "intensity", "cutoff_angle", "beam_width"});
    const Affine to_world = parse_transform(emitter.at("to_world"));
    const double cutoff = emitter.has("cutoff_angle") ? emitter.at("cutoff_angle").number_in(0, 90, true, false) : 20.0;
    const double beam =
        emitter.has("beam_width") ? emitter.at("beam_width").number_in(0, cutoff, true, false) : cutoff * 0.75;
    const std::array<double, 3> position = to_array(to_world.point({0, 0, 0}));
    const std::array<double, 3> target = to_array(to_world.point({0, 0, 1}));
    check(emitter,
          ppm_scene_add_spot_light(scene_, position.data(), target.data(), intensity.data(), cutoff, beam, nullptr));
}

// ---------------------------------------------------------------------------------------------
// shapes

void SceneBuilder::add_shapes(const JsonNode &shapes) {
    shapes.require_array();
    if (shapes.size() == 0) shapes.fail("a scene needs at least one shape");
    for (std::size_t i = 0; i < shapes.size(); ++i) add_shape(shapes[i]);
}

std::uint32_t SceneBuilder::shape_material(const JsonNode &shape) {
    if (shape.has("bsdf")) return nested_material(shape.at("bsdf"));
    if (!has_default_material_) {
        const double grey[3] = {0.5, 0.5, 0.5};
        check(shape, ppm_scene_add_diffuse_material(scene_, grey, &default_material_));
        has_default_material_ = true;
    }
    return default_material_;
}

void SceneBuilder::add_shape(const JsonNode &shape) {
    shape.require_object();
    const std::string type = shape.at("type").one_of(
        {"sphere", "rectangle", "quad", "disk", "cylinder", "cube", "obj", "ply", "serialized", "bezier"});
    const Affine to_world = shape.has("to_world") ? parse_transform(shape.at("to_world")) : Affine{};
    // Transforms that the shape cannot take in its own parameters go to the geometry.
    bool transform_geometry = !is_identity(to_world);
    bool mirrored_normal = false; // the shape's normal must be flipped to be Mitsuba's
    std::uint32_t geom = 0;

    if (type == "sphere") {
        shape.allow_only({"type", "bsdf", "emitter", "to_world", "center", "radius"});
        const std::array<double, 3> center = shape.vec3_or("center", {0, 0, 0});
        const double radius = shape.has("radius") ? shape.at("radius").positive() : 1.0;
        check(shape, ppm_scene_add_sphere(scene_, center.data(), radius, &geom));
    } else if (type == "rectangle" || type == "quad") {
        if (type == "rectangle") {
            shape.allow_only({"type", "bsdf", "emitter", "to_world", "flip_normals"});
        } else {
            shape.allow_only({"type", "bsdf", "emitter", "to_world", "flip_normals", "origin", "edge_u", "edge_v"});
        }
        // Mitsuba's rectangle is [-1, 1]^2 at z = 0 with normal +z.
        const Vec3 origin = type == "rectangle" ? Vec3{-1, -1, 0} : Vec3::from(shape.at("origin").vec3().data());
        const Vec3 edge_u = type == "rectangle" ? Vec3{2, 0, 0} : Vec3::from(shape.at("edge_u").vec3().data());
        const Vec3 edge_v = type == "rectangle" ? Vec3{0, 2, 0} : Vec3::from(shape.at("edge_v").vec3().data());
        const std::array<double, 3> o = to_array(to_world.point(origin)), u = to_array(to_world.vector(edge_u)),
                                    v = to_array(to_world.vector(edge_v));
        check(shape, ppm_scene_add_quad(scene_, o.data(), u.data(), v.data(), &geom));
        transform_geometry = false;
        // As for the disk below: Mitsuba's rectangle normal is to_world's inverse transpose
        // applied to +z, reversed from edge_u x edge_v by a mirroring to_world.
        mirrored_normal = type == "rectangle" && to_world.determinant() < 0;
    } else if (type == "disk") {
        // Mitsuba's disk: the unit disk at z = 0 with normal +z, placed by to_world.
        shape.allow_only({"type", "bsdf", "emitter", "to_world", "flip_normals"});
        const std::array<double, 3> c = to_array(to_world.point({0, 0, 0})), u = to_array(to_world.vector({1, 0, 0})),
                                    v = to_array(to_world.vector({0, 1, 0}));
        check(shape, ppm_scene_add_disk(scene_, c.data(), u.data(), v.data(), &geom));
        transform_geometry = false;
        // Mitsuba's normal is to_world's inverse transpose applied to +z, which is
        // (x axis) x (y axis) / det: reversed by a mirroring to_world.
        mirrored_normal = to_world.determinant() < 0;
    } else if (type == "cylinder") {
        // Mitsuba's cylinder: p0 (0, 0, 0), p1 (0, 0, 1), radius 1, then to_world; the tube
        // must stay circular in the world (to_world may stretch along the axis only).
        shape.allow_only({"type", "bsdf", "emitter", "to_world", "flip_normals", "p0", "p1", "radius"});
        const Vec3 p0 = Vec3::from(shape.vec3_or("p0", {0, 0, 0}).data());
        const Vec3 p1 = Vec3::from(shape.vec3_or("p1", {0, 0, 1}).data());
        const double radius = shape.has("radius") ? shape.at("radius").positive() : 1.0;
        if (!(length(p1 - p0) > 0)) shape.fail("cylinder p0 and p1 are equal: the cylinder has no length");
        Vec3 e1, e2;
        orthonormal_basis(normalize(p1 - p0), e1, e2);
        const Vec3 w0 = to_world.point(p0), w1 = to_world.point(p1);
        const Vec3 x = to_world.vector(e1 * radius), y = to_world.vector(e2 * radius), axis = w1 - w0;
        const double lx = length(x), ly = length(y), la = length(axis);
        const double eps = 1e-6;
        if (std::fabs(lx - ly) > eps * lx || std::fabs(dot(x, y)) > eps * lx * ly ||
            std::fabs(dot(x, axis)) > eps * lx * la || std::fabs(dot(y, axis)) > eps * ly * la)
            shape.at("to_world")
                .fail("a cylinder's to_world must keep it circular: no shear or non-uniform "
                      "scaling across its axis");
        const std::array<double, 3> a = to_array(w0), b = to_array(w1);
        check(shape, ppm_scene_add_cylinder(scene_, a.data(), b.data(), lx, &geom));
        transform_geometry = false;
    } else if (type == "cube") {
        shape.allow_only({"type", "bsdf", "emitter", "to_world", "flip_normals"});
        const MeshData cube = cube_mesh();
        std::vector<double> positions, normals;
        for (std::size_t i = 0; i < cube.positions.size(); ++i)
            for (int axis = 0; axis < 3; ++axis) {
                positions.push_back(cube.positions[i][axis]);
                normals.push_back(cube.normals[i][axis]);
            }
        check(shape, ppm_scene_add_triangle_mesh(scene_, positions.data(), cube.positions.size(), cube.indices.data(),
                                                 cube.indices.size() / 3, normals.data(), cube.uvs.data(), &geom));
    } else if (type == "obj" || type == "ply") {
        shape.allow_only({"type", "bsdf", "emitter", "to_world", "flip_normals", "face_normals", "filename"});
        const JsonNode filename = shape.at("filename");
        const std::string path = existing_file(filename);
        check(filename, type == "obj" ? ppm_scene_load_obj(scene_, path.c_str(), &geom)
                                      : ppm_scene_load_ply(scene_, path.c_str(), &geom));
        if (shape.has("face_normals") && shape.at("face_normals").boolean())
            check(shape.at("face_normals"), ppm_scene_set_mesh_face_normals(scene_, geom, 1));
    } else if (type == "serialized") {
        shape.allow_only(
            {"type", "bsdf", "emitter", "to_world", "flip_normals", "face_normals", "filename", "shape_index"});
        const JsonNode filename = shape.at("filename");
        const std::int64_t index = shape.has("shape_index") ? shape.at("shape_index").integer(0, 0xFFFFFFFF) : 0;
        check(filename, ppm_scene_load_serialized(scene_, existing_file(filename).c_str(),
                                                  static_cast<std::uint32_t>(index), &geom));
        if (shape.has("face_normals") && shape.at("face_normals").boolean())
            check(shape.at("face_normals"), ppm_scene_set_mesh_face_normals(scene_, geom, 1));
    } else {
        shape.allow_only({"type", "bsdf", "emitter", "to_world", "filename", "patches", "uv_rects"});
        if (shape.has("filename") == shape.has("patches"))
            shape.fail("a bezier shape needs either 'filename' or 'patches'");
        if (shape.has("filename")) {
            const JsonNode filename = shape.at("filename");
            check(filename, ppm_scene_load_bpt(scene_, existing_file(filename).c_str(), &geom));
        } else {
            const JsonNode patches = shape.at("patches");
            patches.require_array();
            if (patches.size() == 0) patches.fail("expected at least one patch");
            std::vector<double> points;
            for (std::size_t p = 0; p < patches.size(); ++p) {
                const JsonNode patch = patches[p];
                if (!patch.is_array() || patch.size() != 16) patch.fail("expected 16 control points [x, y, z]");
                for (std::size_t k = 0; k < 16; ++k)
                    for (double c : patch[k].vec3()) points.push_back(c);
            }
            check(patches, ppm_scene_add_bezier_patches(scene_, points.data(), patches.size(), &geom));
        }
        if (shape.has("uv_rects")) {
            const JsonNode rects = shape.at("uv_rects");
            std::size_t patch_count = 0;
            check(shape, ppm_scene_get_primitive_count(scene_, geom, &patch_count));
            rects.require_array();
            if (rects.size() != patch_count)
                rects.fail("expected one [u0, v0, u1, v1] per patch (" + std::to_string(patch_count) + ")");
            std::vector<double> values;
            for (std::size_t p = 0; p < rects.size(); ++p) {
                const JsonNode rect = rects[p];
                if (!rect.is_array() || rect.size() != 4) rect.fail("expected [u0, v0, u1, v1]");
                for (std::size_t k = 0; k < 4; ++k) values.push_back(rect[k].number());
            }
            check(rects, ppm_scene_set_patch_uv_rects(scene_, geom, values.data()));
        }
    }

    if (transform_geometry) {
        const std::array<double, 16> matrix = matrix16(to_world);
        check(shape.at("to_world"), ppm_scene_set_geometry_transform(scene_, geom, matrix.data()));
    }
    const bool flip = shape.has("flip_normals") && shape.at("flip_normals").boolean();
    if (flip != mirrored_normal) check(shape, ppm_scene_set_geometry_flip_normals(scene_, geom, 1));
    check(shape, ppm_scene_set_geometry_material(scene_, geom, shape_material(shape)));
    if (shape.has("emitter")) {
        const JsonNode emitter = shape.at("emitter");
        emitter.allow_only({"type", "radiance"});
        emitter.at("type").one_of({"area"});
        const std::array<double, 3> radiance =
            emitter.has("radiance") ? emitter.at("radiance").color(false) : std::array<double, 3>{1, 1, 1};
        check(emitter, ppm_scene_set_geometry_emission(scene_, geom, radiance.data()));
    }
}

} // namespace ppm
