// SPDX-License-Identifier: Apache-2.0
#include "scenefile/scene_file.h"

#include "core/error.h"
#include "io/text_file.h"
#include "scenefile/json_node.h"
#include "scenefile/load_error.h"
#include "scenefile/mitsuba_xml.h"
#include "scenefile/scene_builder.h"
#include "scenefile/transform.h"

#include <cctype>
#include <memory>

namespace ppm {

namespace {

// `integrator`: the renderer's settings, checked now by the same code that checks
// ppm_renderer_set_*, so that an error points into the file.
void read_integrator(const JsonNode &node, RenderSettings &settings, std::int64_t &passes, double &time) {
    node.allow_only({"type", "passes", "time", "photons_per_pass", "alpha", "initial_radius", "initial_radius_pixels",
                     "max_depth", "seed", "hit_point_search", "direct_lighting", "glossy_gather_alpha"});
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
            const std::string mode = value.one_of({"sppm", "ppm", "pppm", "vcm", "bpt", "vm"});
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

// `film.rfilter`: Mitsuba's reconstruction filters box, tent (radius) and gaussian (stddev).
void read_pixel_filter(const JsonNode &node, ppm_camera_v2 &camera) {
    const std::string type = node.at("type").one_of({"box", "tent", "gaussian"});
    if (type == "box") {
        node.allow_only({"type"});
        camera.pixel_filter = PPM_PIXEL_FILTER_BOX;
    } else if (type == "tent") {
        node.allow_only({"type", "radius"});
        camera.pixel_filter = PPM_PIXEL_FILTER_TENT;
        if (node.has("radius")) camera.pixel_filter_parameter = node.at("radius").number_in(0, 16, true, false);
    } else {
        node.allow_only({"type", "stddev"});
        camera.pixel_filter = PPM_PIXEL_FILTER_GAUSSIAN;
        if (node.has("stddev")) camera.pixel_filter_parameter = node.at("stddev").number_in(0, 4, true, false);
    }
}

// `sensor`: the camera from Mitsuba's perspective / thinlens parameters.
ppm_camera_v2 read_sensor(const JsonNode *node) {
    ppm_camera_v2 camera;
    ppm_camera_v2_init(&camera); // Mitsuba's fov (a 50 mm lens on 36 mm film, along x) and near clip
    camera.width = 768;
    camera.height = 576;
    Affine to_world;
    if (node) {
        const std::string type =
            node->has("type") ? node->at("type").one_of({"perspective", "thinlens"}) : std::string("perspective");
        if (type == "thinlens") {
            node->allow_only({"type", "fov", "to_world", "near_clip", "film", "aperture_radius", "focus_distance"});
            camera.aperture_radius = node->at("aperture_radius").positive();
            camera.focus_distance = node->at("focus_distance").positive();
        } else {
            // Mitsuba's perspective sensor takes a focus distance too (all its projective
            // cameras do); a pinhole has everything in focus, so it changes nothing.
            node->allow_only({"type", "fov", "to_world", "near_clip", "film", "focus_distance",
                              "principal_point_offset_x", "principal_point_offset_y"});
            if (node->has("focus_distance")) node->at("focus_distance").positive();
            if (node->has("principal_point_offset_x"))
                camera.principal_point_offset_x =
                    node->at("principal_point_offset_x").number_in(-1048576, 1048576, false, false);
            if (node->has("principal_point_offset_y"))
                camera.principal_point_offset_y =
                    node->at("principal_point_offset_y").number_in(-1048576, 1048576, false, false);
        }
        if (node->has("fov")) camera.fov = node->at("fov").number_in(0, 180, true, true);
        if (node->has("near_clip")) camera.near_clip = node->at("near_clip").non_negative();
        if (node->has("to_world")) to_world = parse_transform(node->at("to_world"));
        if (node->has("film")) {
            const JsonNode film = node->at("film");
            film.allow_only({"width", "height", "rfilter"});
            if (film.has("rfilter")) read_pixel_filter(film.at("rfilter"), camera);
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

bool has_xml_extension(const std::string &path) {
    if (path.size() < 4) return false;
    std::string extension = path.substr(path.size() - 4);
    for (char &c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return extension == ".xml";
}

// The document of either format, and the folder its file names are relative to: the JSON
// file's, while the XML reader has resolved every name against the file that holds it.
struct ReadDocument {
    std::unique_ptr<JsonDocument> document;
    std::string folder;
    std::vector<std::string> warnings;
    std::vector<std::string> failure_notes; // said only if loading fails
    bool lenient = false;                   // XML read with --lenient
    std::vector<std::string> substituted;   // where the XML reader's lenient reading substituted
};

ReadDocument read_document(const SceneFileSource &source) {
    using Format = SceneFileSource::Format;
    const std::string text = source.text ? *source.text : read_text_file(source.path);
    Format format = source.format;
    if (format == Format::Detect)
        format = has_xml_extension(source.path) || looks_like_xml(text) ? Format::Xml : Format::Json;
    ReadDocument read;
    if (format == Format::Xml) {
        XmlOptions options;
        options.defines = source.defines;
        options.lenient = source.lenient;
        XmlScene scene = source.text ? read_mitsuba_xml(source.path, options, &text, source.folder)
                                     : read_mitsuba_xml(source.path, options);
        read.document = std::make_unique<JsonDocument>(std::move(scene.root), std::move(scene.sources));
        read.warnings = std::move(scene.warnings);
        read.failure_notes = std::move(scene.failure_notes);
        read.lenient = source.lenient;
        read.substituted = std::move(scene.substituted_at);
        return read;
    }
    if (!source.defines.empty())
        invalid_argument(source.path + ": parameter '" + source.defines.begin()->first +
                         "' given, but parameters (-D) apply to Mitsuba XML scene files only");
    read.document = std::make_unique<JsonDocument>(source.path, text);
    read.folder = source.text ? source.folder : folder_of(source.path);
    return read;
}

} // namespace

SceneFile::SceneFile(ppm_context context, const SceneFileSource &source) {
    const ReadDocument read = read_document(source);
    warnings_ = read.warnings;
    LenientLog lenient;
    lenient.locations = read.substituted;
    try {
        build(context, source.path, *read.document, read.folder, read.lenient ? &lenient : nullptr);
    } catch (const Error &e) {
        std::vector<std::string> said = warnings_;
        said.insert(said.end(), lenient.warnings.begin(), lenient.warnings.end());
        said.insert(said.end(), read.failure_notes.begin(), read.failure_notes.end());
        throw LoadError(e, said);
    }
    warnings_.insert(warnings_.end(), lenient.warnings.begin(), lenient.warnings.end());
    // One line at the end lists every substitution again, so that none is missed among other
    // warnings.
    if (!lenient.locations.empty()) {
        std::string list;
        for (const std::string &at : lenient.locations) list += (list.empty() ? "" : ", ") + at;
        warnings_.push_back(source.path + ": --lenient replaced or left out " +
                            std::to_string(lenient.locations.size()) + " element" +
                            (lenient.locations.size() == 1 ? "" : "s") + ", at " + list);
    }
}

void SceneFile::build(ppm_context context, const std::string &path, const JsonDocument &document,
                      const std::string &folder, LenientLog *lenient) {
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
        SceneBuilder builder(scene_, folder, lenient);
        if (root.has("bsdfs")) builder.add_bsdfs(root.at("bsdfs"));
        if (root.has("emitters")) builder.add_emitters(root.at("emitters"));
        builder.add_shapes(root.at("shapes"));
        const ppm_status committed = ppm_scene_commit(scene_);
        if (committed != PPM_OK) fail(committed, path + ": " + ppm_last_error_message());
    } catch (...) {
        ppm_scene_release(scene_);
        scene_ = nullptr;
        throw;
    }
}

SceneFile::~SceneFile() { ppm_scene_release(scene_); }

} // namespace ppm
