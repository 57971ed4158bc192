#include "scenefile/scene_file.h"

#include "core/error.h"
#include "scenefile/json_node.h"
#include "scenefile/scene_builder.h"
#include "scenefile/transform.h"

namespace ppm {

namespace {

// `integrator`: the renderer's settings, checked now by the same code that checks
// ppm_renderer_set_*, so that an error points into the file.
void read_integrator(const JsonNode &node, RenderSettings &settings, std::int64_t &passes, double &time) {
    node.allow_only({"type", "passes", "time", "photons_per_pass", "alpha", "initial_radius", "initial_radius_pixels",
                     "max_depth", "seed", "hit_point_search", "direct_lighting"});
    const auto apply = [&](const JsonNode &value, auto &&set) {
        try {
            set();
        } catch (const Error &e) {
            value.fail(e.what());
        }
    };
    for (const std::string &key : node.keys()) {
        const JsonNode value = node.at(key.c_str());
        if (key == "type") {
            const std::string mode = value.one_of({"sppm", "ppm", "pppm"});
            apply(value, [&] { settings.set_string("mode", mode, false); });
        } else if (key == "passes") {
            passes = value.integer(0, std::int64_t(1) << 40);
        } else if (key == "time") {
            time = value.non_negative();
        } else if (key == "hit_point_search") {
            const std::string search = value.one_of({"kdtree", "grid"});
            apply(value, [&] { settings.set_string(key, search, false); });
        } else if (key == "direct_lighting") {
            const bool on = value.boolean();
            apply(value, [&] { settings.set_int(key, on ? 1 : 0, false); });
        } else if (key == "photons_per_pass" || key == "max_depth" || key == "seed") {
            const std::int64_t v = value.integer(key == "seed" ? 0 : 1, std::int64_t(1) << 53);
            apply(value, [&] { settings.set_int(key, v, false); });
        } else {
            const double v = value.number();
            apply(value, [&] { settings.set_double(key, v, false); });
        }
    }
}

// `sensor`: ppm_camera from Mitsuba's perspective / thinlens parameters.
ppm_camera read_sensor(const JsonNode *node) {
    ppm_camera camera{};
    camera.fov = 39.597752709049864; // Mitsuba: a 50 mm lens on 36 mm film, along x
    camera.width = 768;
    camera.height = 576;
    camera.near_clip = 0.01;
    Affine to_world;
    if (node) {
        const std::string type =
            node->has("type") ? node->at("type").one_of({"perspective", "thinlens"}) : std::string("perspective");
        if (type == "thinlens") {
            node->allow_only({"type", "fov", "to_world", "near_clip", "film", "aperture_radius", "focus_distance"});
            camera.aperture_radius = node->at("aperture_radius").positive();
            camera.focus_distance = node->at("focus_distance").positive();
        } else {
            node->allow_only({"type", "fov", "to_world", "near_clip", "film"});
        }
        if (node->has("fov")) camera.fov = node->at("fov").number_in(0, 180, true, true);
        if (node->has("near_clip")) camera.near_clip = node->at("near_clip").non_negative();
        if (node->has("to_world")) to_world = parse_transform(node->at("to_world"));
        if (node->has("film")) {
            const JsonNode film = node->at("film");
            film.allow_only({"width", "height"});
            constexpr std::int64_t max_side = std::int64_t(1) << 28;
            if (film.has("width")) camera.width = static_cast<std::uint32_t>(film.at("width").integer(1, max_side));
            if (film.has("height")) camera.height = static_cast<std::uint32_t>(film.at("height").integer(1, max_side));
            if (static_cast<std::uint64_t>(camera.width) * camera.height > (std::uint64_t(1) << 28))
                film.fail(
                    "width x height = " + std::to_string(static_cast<std::uint64_t>(camera.width) * camera.height) +
                    " pixels exceeds the limit of 2^28");
        }
    }
    const Vec3 origin = to_world.point({0, 0, 0});
    const Vec3 target = to_world.point({0, 0, 1});
    const Vec3 up = to_world.vector({0, 1, 0});
    for (int i = 0; i < 3; ++i) {
        camera.origin[i] = origin[i];
        camera.target[i] = target[i];
        camera.up[i] = up[i];
    }
    return camera;
}

std::string folder_of(const std::string &path) {
    const std::size_t slash = path.rfind('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

} // namespace

SceneFile::SceneFile(ppm_context context, const std::string &path) {
    const JsonDocument document(path);
    const JsonNode root(document, document.root(), "");
    root.allow_only({"version", "integrator", "sensor", "bsdfs", "emitters", "shapes"});
    if (root.has("version")) root.at("version").integer(1, 1);

    if (root.has("integrator")) read_integrator(root.at("integrator"), settings_, passes_, time_);
    if (root.has("sensor")) {
        const JsonNode sensor = root.at("sensor");
        camera_ = read_sensor(&sensor);
    } else {
        camera_ = read_sensor(nullptr);
    }

    const ppm_status created = ppm_scene_create(context, &scene_);
    if (created != PPM_OK) fail(created, ppm_last_error_message());
    try {
        SceneBuilder builder(scene_, folder_of(path));
        if (root.has("bsdfs")) builder.add_bsdfs(root.at("bsdfs"));
        if (root.has("emitters")) builder.add_emitters(root.at("emitters"));
        builder.add_shapes(root.at("shapes"));
        const ppm_status committed = ppm_scene_commit(scene_);
        if (committed != PPM_OK) fail(committed, path + ": " + ppm_last_error_message());
    } catch (...) {
        ppm_scene_release(scene_);
        throw;
    }
}

SceneFile::~SceneFile() { ppm_scene_release(scene_); }

} // namespace ppm
