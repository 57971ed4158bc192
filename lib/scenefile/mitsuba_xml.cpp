// SPDX-License-Identifier: Apache-2.0
#include "scenefile/mitsuba_xml.h"

#include <ppm/ppm.h>

#include "core/error.h"
#include "core/suggest.h"
#include "io/text_file.h"
#include "math/spectrum.h"
#include "scenefile/load_error.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <set>

namespace ppm {

bool looks_like_xml(const std::string &text) {
    std::size_t i = 0;
    if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) i = 3; // UTF-8 byte order mark
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    return i < text.size() && text[i] == '<';
}

namespace {

constexpr int kMaxIncludeDepth = 32;

// Mitsuba's table of named indices of refraction (src/render/ior.h), for dielectrics and plastics.
const std::map<std::string, double> &named_iors() {
    static const std::map<std::string, double> table = {
        {"vacuum", 1.0},      {"helium", 1.00004},         {"hydrogen", 1.00013},
        {"air", 1.000277},    {"carbon dioxide", 1.00045}, {"water", 1.3330},
        {"acetone", 1.36},    {"ethanol", 1.361},          {"carbon tetrachloride", 1.461},
        {"glycerol", 1.4729}, {"benzene", 1.501},          {"silicone oil", 1.52045},
        {"bromine", 1.661},   {"water ice", 1.31},         {"fused quartz", 1.458},
        {"pyrex", 1.470},     {"acrylic glass", 1.49},     {"polypropylene", 1.49},
        {"bk7", 1.5046},      {"sodium chloride", 1.544},  {"amber", 1.55},
        {"pet", 1.5750},      {"diamond", 2.419}};
    return table;
}

// Object tags: each becomes a member of its parent (or of the scene) under this role.
const std::set<std::string> &object_tags() {
    static const std::set<std::string> tags = {"bsdf",    "emitter", "shape",  "texture", "sensor",     "film",
                                               "sampler", "rfilter", "medium", "phase",   "integrator", "volume"};
    return tags;
}

// The types libppm renders, by XML tag: the API's type tables (ppm_type_name), which the
// builder (scene_builder.cpp) reads the objects with; lenient mode substitutes the others.
const std::set<std::string> &renderable(const std::string &tag) {
    static const std::map<std::string, std::set<std::string>> types = [] {
        std::map<std::string, std::set<std::string>> by_tag;
        const std::pair<const char *, const char *> kinds[] = {
            {"bsdf", "material"}, {"emitter", "light"}, {"shape", "shape"}, {"texture", "texture"}};
        for (const auto &[tag, kind] : kinds) {
            std::size_t count = 0;
            ppm_type_count(kind, &count);
            for (std::size_t i = 0; i < count; ++i) {
                const char *name = nullptr;
                if (ppm_type_name(kind, i, &name) == PPM_OK) by_tag[tag].insert(name);
            }
        }
        // An area emitter is not a light of its own but the emission of the shape that holds
        // it (ppm_scene_set_geometry_emission).
        by_tag["emitter"].insert("area");
        return by_tag;
    }();
    static const std::set<std::string> none;
    const auto found = types.find(tag);
    return found == types.end() ? none : found->second;
}

class XmlReader {
public:
    XmlReader(const XmlOptions &options, XmlScene &out) : options_(options), out_(out) {
        for (const auto &define : options.defines) parameters_[define.first] = define.second;
    }

    void read(const std::string &path, const std::string *text, const std::string *folder) {
        out_.root = Json::Value(Json::objectValue);
        out_.root["shapes"] = Json::Value(Json::arrayValue);
        read_file(path, nullptr, text, folder);
        // Objects at the top with an id are converted where they are referred to; the BSDFs
        // also become the scene's named materials.
        for (const Pending &pending : top_level_) convert_top_level(pending);
        for (const Pending &pending : referable_only_)
            if (!referred_to_.count(pending.node.attribute("id").value()))
                warn(pending.node, *pending.source, "no object refers to this id: it is not used");
        for (const Pending &pending : unattached_area_emitters_)
            if (!referred_to_.count(pending.node.attribute("id").value()))
                warn(pending.node, *pending.source,
                     "this area emitter is never used: no <shape> refers to its id, and it emits only from one");
        if (out_.root["shapes"].empty()) out_.root.removeMember("shapes");
        // A parameter given from outside that no $name takes is likely a typo: said, not fatal
        // (Mitsuba accepts it too).
        const std::vector<std::string> referenced(referenced_.begin(), referenced_.end());
        for (const auto &define : options_.defines)
            if (!referenced_.count(define.first))
                out_.warnings.push_back(path + ": parameter '" + define.first + "' (-D " + define.first + "=" +
                                        define.second + ") is not used by the scene" +
                                        did_you_mean(define.first, referenced));
    }

private:
    struct Source {
        std::unique_ptr<pugi::xml_document> document;
        std::size_t base;
        std::string folder;    // of the file, for relative file names
        bool before_2 = false; // a Mitsuba 0.x file, upgraded as Mitsuba 3 upgrades it
    };
    struct Pending {
        pugi::xml_node node;
        const Source *source;
    };
    std::string main_folder_; // of the scene file itself

    // ---- locations ----------------------------------------------------------------------

    // Where the element starts: pugixml gives the offset of its name, just after the '<'.
    std::size_t position(const pugi::xml_node &node, const Source &source) const {
        const std::ptrdiff_t offset = node.offset_debug();
        return offset <= 0 ? source.base : source.base + static_cast<std::size_t>(offset) - 1;
    }
    std::string where(const pugi::xml_node &node, const Source &source) const {
        return out_.sources.location(position(node, source)) + ": <" + node.name() + ">";
    }
    [[noreturn]] void error(const pugi::xml_node &node, const Source &source, const std::string &what) const {
        fail(PPM_ERROR_PARSE, where(node, source) + ": " + what);
    }
    void warn(const pugi::xml_node &node, const Source &source, const std::string &what) {
        out_.warnings.push_back(where(node, source) + ": " + what);
    }
    // The same at the element a converted object came from.
    std::string where(const Json::Value &value, const char *tag) const {
        return out_.sources.location(static_cast<std::size_t>(value.getOffsetStart())) + ": <" + tag + ">";
    }
    void warn(const Json::Value &value, const char *tag, const std::string &what) {
        out_.warnings.push_back(where(value, tag) + ": " + what);
    }
    [[noreturn]] void error(const Json::Value &value, const char *tag, const std::string &what) const {
        fail(PPM_ERROR_PARSE, where(value, tag) + ": " + what);
    }
    Json::Value located(Json::Value value, const pugi::xml_node &node, const Source &source) const {
        const std::size_t at = position(node, source);
        value.setOffsetStart(static_cast<std::ptrdiff_t>(at));
        value.setOffsetLimit(static_cast<std::ptrdiff_t>(at + 1));
        return value;
    }

    // ---- files and includes -------------------------------------------------------------

    // `given_text`: the file's text when the caller has it already (NULL: read `path`), and
    // `given_folder` what its names are relative to (NULL: the folder of `path`).
    void read_file(const std::string &path, const std::pair<pugi::xml_node, const Source *> *included_from,
                   const std::string *given_text = nullptr, const std::string *given_folder = nullptr) {
        if (std::find(include_stack_.begin(), include_stack_.end(), path) != include_stack_.end()) {
            std::string cycle;
            for (const std::string &file : include_stack_) cycle += file + " -> ";
            error(included_from->first, *included_from->second, "cyclic include: " + cycle + path);
        }
        if (include_stack_.size() >= kMaxIncludeDepth)
            error(included_from->first, *included_from->second,
                  "includes nested deeper than " + std::to_string(kMaxIncludeDepth) + " files");
        std::string text;
        try {
            text = given_text ? *given_text : read_text_file(path);
        } catch (const Error &e) {
            if (!included_from) throw;
            fail(e.status(), where(included_from->first, *included_from->second) + ": " + e.what());
        }
        auto source = std::make_unique<Source>();
        source->document = std::make_unique<pugi::xml_document>();
        source->base = out_.sources.add(path, text);
        const std::size_t slash = path.rfind('/');
        source->folder = given_folder                 ? *given_folder
                         : slash == std::string::npos ? std::string()
                                                      : path.substr(0, slash + 1);
        if (!included_from) main_folder_ = source->folder;
        const pugi::xml_parse_result parsed =
            source->document->load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
        if (!parsed)
            fail(PPM_ERROR_PARSE, out_.sources.location(source->base + static_cast<std::size_t>(parsed.offset)) +
                                      ": malformed XML: " + parsed.description());
        const pugi::xml_node scene = source->document->document_element();
        sources_.push_back(std::move(source));
        const Source &current = *sources_.back();
        if (std::string(scene.name()) != "scene")
            error(scene, current, "the root element must be <scene>, not <" + std::string(scene.name()) + ">");
        check_version(scene, current);
        sources_.back()->before_2 = std::atoi(scene.attribute("version").value()) < 2;
        include_stack_.push_back(path);
        // An included file's <path> folders serve its own includes only: Mitsuba resolves the
        // files that properties name after parsing, with the main file's folders.
        const std::vector<std::string> outer_folders = search_folders_;
        for (const pugi::xml_node &child : scene.children()) {
            if (child.type() != pugi::node_element) continue;
            read_top_level(child, current);
        }
        if (included_from) search_folders_ = outer_folders;
        include_stack_.pop_back();
    }

    void check_version(const pugi::xml_node &scene, const Source &source) const {
        const std::string version = scene.attribute("version").value();
        if (version.empty()) error(scene, source, "the 'version' attribute is missing (e.g. version=\"3.0.0\")");
        const int major = std::atoi(version.c_str());
        if (major < 0 || major > 3 || !std::isdigit(static_cast<unsigned char>(version[0])))
            error(scene, source, "version \"" + version + "\" is not supported (0.x to 3.x files are read)");
    }

    void read_top_level(const pugi::xml_node &node, const Source &source) {
        const std::string tag = node.name();
        if (tag == "default") {
            check_attributes(node, source, {"name", "value"});
            const std::string name = required(node, source, "name");
            // A value given by the caller (-D) wins over the file's default.
            if (!parameters_.count(name)) parameters_[name] = substitute(node, source, "value");
        } else if (tag == "include") {
            check_attributes(node, source, {"filename"});
            const std::pair<pugi::xml_node, const Source *> from(node, &source);
            read_file(resolve_include(source, substitute(node, source, "filename")), &from);
        } else if (tag == "path") {
            check_attributes(node, source, {"value"});
            add_search_folder(node, source, substitute(node, source, "value"));
        } else if (object_tags().count(tag)) {
            const std::string id = node.attribute("id").value();
            if (!id.empty()) {
                if (by_id_.count(id)) error(node, source, "id \"" + id + "\" is defined twice");
                by_id_[id] = Pending{node, &source};
            }
            top_level_.push_back(Pending{node, &source});
        } else {
            error(node, source, "unknown element (expected an object such as <shape>, or <default>, <include>)");
        }
    }

    // ---- file names, searched as Mitsuba's file resolver searches them ------------------

    static bool exists(const std::string &path) {
        std::error_code ignored;
        return std::filesystem::exists(path, ignored);
    }
    static bool is_folder(const std::string &path) {
        std::error_code ignored;
        return std::filesystem::is_directory(path, ignored);
    }

    // The folders a relative name is looked up in, in order: the <path> folders (the latest
    // first), the main scene file's folder, then `first_beside`'s folder if it is another one
    // (Mitsuba does not look beside an included file, but scenes split into fragments rely
    // on it), then the working directory ("").
    std::vector<std::string> search_folders(const Source &first_beside) const {
        std::vector<std::string> folders = search_folders_;
        for (const std::string &folder : {main_folder_, first_beside.folder, std::string()})
            if (std::find(folders.begin(), folders.end(), folder) == folders.end()) folders.push_back(folder);
        return folders;
    }

    static std::string shown(const std::string &folder) { return folder.empty() ? "./" : folder; }

    // <path value="...">: a folder searched for the files the scene names. Relative to the
    // file holding the element, else found through the folders searched so far.
    void add_search_folder(const pugi::xml_node &node, const Source &source, const std::string &value) {
        if (value.empty()) error(node, source, "the 'value' attribute is empty");
        std::string folder = value[0] == '/' ? value : source.folder + value;
        if (!is_folder(folder) && value[0] != '/')
            for (const std::string &base : search_folders(source))
                if (is_folder(base + value)) {
                    folder = base + value;
                    break;
                }
        if (!is_folder(folder)) error(node, source, "the folder \"" + value + "\" does not exist (" + folder + ")");
        if (folder.back() != '/') folder += '/';
        search_folders_.erase(std::remove(search_folders_.begin(), search_folders_.end(), folder),
                              search_folders_.end());
        search_folders_.insert(search_folders_.begin(), folder);
    }

    // An <include>: beside the including file, else through the search folders.
    std::string resolve_include(const Source &source, const std::string &name) const {
        if (name.empty() || name[0] == '/') return name;
        if (exists(source.folder + name)) return source.folder + name;
        for (const std::string &folder : search_folders(source))
            if (exists(folder + name)) return folder + name;
        return source.folder + name; // reported as missing by read_file
    }

    // A file a property names (a mesh, a texture). One found nowhere keeps the name beside
    // the main file, which the builder reports as missing, and the folders searched are a
    // failure note.
    std::string resolve_data_file(const pugi::xml_node &node, const Source &source, const std::string &name) {
        if (name.empty() || name[0] == '/') return name;
        const std::vector<std::string> folders = search_folders(source);
        for (const std::string &folder : folders)
            if (exists(folder + name)) return folder + name;
        std::string list;
        for (const std::string &folder : folders) list += (list.empty() ? "" : ", ") + shown(folder);
        out_.failure_notes.push_back(where(node, source) + ": \"" + name +
                                     "\" is in none of the folders searched: " + list);
        return main_folder_ + name;
    }

    // ---- attributes and parameters ------------------------------------------------------

    void check_attributes(const pugi::xml_node &node, const Source &source,
                          std::initializer_list<const char *> allowed) const {
        for (const pugi::xml_attribute &attribute : node.attributes()) {
            bool known = false;
            for (const char *name : allowed) known = known || std::string(attribute.name()) == name;
            if (!known) {
                std::string list;
                for (const char *name : allowed) list += std::string(list.empty() ? "" : ", ") + name;
                error(node, source,
                      "unknown attribute '" + std::string(attribute.name()) + "' (allowed: " + list + ")");
            }
        }
    }

    std::string required(const pugi::xml_node &node, const Source &source, const char *attribute) const {
        const pugi::xml_attribute found = node.attribute(attribute);
        if (!found) error(node, source, std::string("the attribute '") + attribute + "' is missing");
        return found.value();
    }

    // An attribute's value with $name parameters replaced.
    std::string substitute(const pugi::xml_node &node, const Source &source, const char *attribute) const {
        const std::string raw = required(node, source, attribute);
        std::string result;
        for (std::size_t i = 0; i < raw.size(); ++i) {
            if (raw[i] != '$') {
                result += raw[i];
                continue;
            }
            std::size_t end = i + 1;
            while (end < raw.size() && (std::isalnum(static_cast<unsigned char>(raw[end])) || raw[end] == '_')) ++end;
            const std::string name = raw.substr(i + 1, end - i - 1);
            if (name.empty()) error(node, source, "a '$' in '" + raw + "' is not followed by a parameter name");
            referenced_.insert(name);
            const auto found = parameters_.find(name);
            if (found == parameters_.end())
                error(node, source,
                      "the parameter $" + name + " has no value: give it a <default> or define it (ppm-render -D " +
                          name + "=...)");
            result += found->second;
            i = end - 1;
        }
        return result;
    }

    double parse_number(const std::string &text, const pugi::xml_node &node, const Source &source) const {
        char *end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value))
            error(node, source, "'" + text + "' is not a finite number");
        return value;
    }

    // "1, 2, 3" or "1 2 3": numbers separated by commas and/or white space.
    std::vector<double> parse_numbers(const std::string &text, const pugi::xml_node &node, const Source &source) const {
        std::vector<double> values;
        std::string word;
        for (std::size_t i = 0; i <= text.size(); ++i) {
            const char c = i < text.size() ? text[i] : ' ';
            if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
                if (!word.empty()) values.push_back(parse_number(word, node, source));
                word.clear();
            } else {
                word += c;
            }
        }
        return values;
    }

    // <point>/<vector>: value="x, y, z" or x= y= z= (missing components 0).
    Json::Value vector3(const pugi::xml_node &node, const Source &source) const {
        Json::Value out(Json::arrayValue);
        if (node.attribute("value")) {
            const std::vector<double> v = parse_numbers(substitute(node, source, "value"), node, source);
            if (v.size() != 3 && v.size() != 1) error(node, source, "expected 3 numbers (or 1 for all three)");
            for (int i = 0; i < 3; ++i) out.append(v.size() == 1 ? v[0] : v[i]);
        } else {
            for (const char *axis : {"x", "y", "z"})
                out.append(node.attribute(axis) ? parse_number(substitute(node, source, axis), node, source) : 0.0);
        }
        return located(out, node, source);
    }

    // What a colour parameter is, for its spectrum's conversion (Mitsuba's Properties::
    // get_texture and get_unbounded_texture): a reflectance (D65-weighted, clamped to [0, 1]),
    // an unbounded quantity such as a conductor's eta and k (D65-weighted, clamped to >= 0)
    // or an emission (unweighted, clamped to >= 0).
    enum class ColourRange { Reflectance, Unbounded, Emission };

    static ColourRange colour_range(const std::string &tag, const std::string &name) {
        if (tag == "emitter") return ColourRange::Emission;
        static const std::set<std::string> unbounded = {"eta", "k", "alpha", "alpha_u", "alpha_v"};
        return tag == "bsdf" && unbounded.count(name) ? ColourRange::Unbounded : ColourRange::Reflectance;
    }

    // <rgb> as it is; <spectrum> as Mitsuba 3's RGB variants read it (math/spectrum.cpp). In an
    // emitter a spectrum is an emission: a single value is then the equal-energy white of that
    // power, not grey. Clamped by its range (above), with a warning.
    Json::Value colour(const pugi::xml_node &node, const Source &source, ColourRange range) {
        const bool emission = range == ColourRange::Emission;
        const std::string tag = node.name();
        const std::string text = substitute(node, source, "value");
        Json::Value out(Json::arrayValue);
        if (tag == "rgb") {
            const std::vector<double> v = parse_numbers(text, node, source);
            if (v.size() != 3 && v.size() != 1) error(node, source, "expected 3 numbers (r, g, b) or 1 (grey)");
            for (int i = 0; i < 3; ++i) out.append(v.size() == 1 ? v[0] : v[i]);
            return located(out, node, source);
        }
        std::vector<double> wavelengths, values;
        if (text.find(':') == std::string::npos) {
            const std::vector<double> v = parse_numbers(text, node, source);
            if (v.size() != 1) error(node, source, "expected one value or wavelength:value pairs");
            // A constant spectrum: grey as a reflectance; as an emission, XYZ = (v, v, v) in sRGB.
            const Rgb white = emission ? xyz_to_srgb(1, 1, 1) : Rgb(1.0);
            for (double c : {white.r, white.g, white.b}) out.append(v[0] * c);
            return located(out, node, source);
        } else {
            std::string pair;
            for (std::size_t i = 0; i <= text.size(); ++i) {
                if (i < text.size() && text[i] != ',') {
                    pair += text[i];
                    continue;
                }
                const std::size_t colon = pair.find(':');
                if (colon == std::string::npos) error(node, source, "'" + pair + "' is not a wavelength:value pair");
                const double w = parse_number(trimmed(pair.substr(0, colon)), node, source);
                if (!wavelengths.empty() && !(w > wavelengths.back()))
                    error(node, source, "wavelengths must increase (" + pair + ")");
                wavelengths.push_back(w);
                values.push_back(parse_number(trimmed(pair.substr(colon + 1)), node, source));
                pair.clear();
            }
        }
        Rgb rgb = spectrum_to_rgb(wavelengths, values, !emission);
        const Rgb clamped(std::max(rgb.r, 0.0), std::max(rgb.g, 0.0), std::max(rgb.b, 0.0));
        const bool to_one = range == ColourRange::Reflectance;
        const Rgb bounded =
            to_one ? Rgb(std::min(clamped.r, 1.0), std::min(clamped.g, 1.0), std::min(clamped.b, 1.0)) : clamped;
        if (!(bounded.r == rgb.r && bounded.g == rgb.g && bounded.b == rgb.b))
            out_.warnings.push_back(where(node, source) + ": the spectrum's colour (" + format_number(rgb.r) + ", " +
                                    format_number(rgb.g) + ", " + format_number(rgb.b) +
                                    ") lies outside the sRGB gamut" + (to_one ? " or above 1" : "") + ": clamped");
        for (double c : {bounded.r, bounded.g, bounded.b}) out.append(c);
        return located(out, node, source);
    }

    static std::string trimmed(const std::string &text) {
        const std::size_t first = text.find_first_not_of(" \t\n\r");
        if (first == std::string::npos) return "";
        return text.substr(first, text.find_last_not_of(" \t\n\r") - first + 1);
    }

    // ---- transforms ---------------------------------------------------------------------

    Json::Value transform(const pugi::xml_node &node, const Source &source) const {
        Json::Value ops(Json::arrayValue);
        for (const pugi::xml_node &op : node.children()) {
            if (op.type() != pugi::node_element) continue;
            const std::string tag = op.name();
            Json::Value entry(Json::objectValue);
            if (tag == "translate") {
                check_attributes(op, source, {"x", "y", "z", "value"});
                entry["translate"] = vector3(op, source);
            } else if (tag == "scale") {
                check_attributes(op, source, {"x", "y", "z", "value"});
                if (op.attribute("value") && !op.attribute("x") && !op.attribute("y") && !op.attribute("z")) {
                    const std::vector<double> v = parse_numbers(substitute(op, source, "value"), op, source);
                    if (v.size() == 1)
                        entry["scale"] = located(Json::Value(v[0]), op, source);
                    else
                        entry["scale"] = vector3(op, source);
                } else {
                    // Mitsuba's per-axis scale: a missing axis keeps its size.
                    Json::Value s(Json::arrayValue);
                    for (const char *axis : {"x", "y", "z"})
                        s.append(op.attribute(axis) ? parse_number(substitute(op, source, axis), op, source) : 1.0);
                    entry["scale"] = located(s, op, source);
                }
            } else if (tag == "rotate") {
                check_attributes(op, source, {"x", "y", "z", "value", "angle"});
                Json::Value rotate(Json::objectValue);
                rotate["axis"] = vector3(op, source);
                rotate["angle"] =
                    located(Json::Value(parse_number(substitute(op, source, "angle"), op, source)), op, source);
                entry["rotate"] = located(rotate, op, source);
            } else if (tag == "matrix") {
                check_attributes(op, source, {"value"});
                const std::vector<double> v = parse_numbers(substitute(op, source, "value"), op, source);
                if (v.size() != 16 && v.size() != 9)
                    error(op, source, "expected 16 numbers (a 4x4 matrix, row by row) or 9 (3x3)");
                Json::Value m(Json::arrayValue);
                if (v.size() == 16) {
                    for (double x : v) m.append(x);
                } else {
                    for (int r = 0; r < 4; ++r)
                        for (int c = 0; c < 4; ++c) m.append(r < 3 && c < 3 ? v[3 * r + c] : (r == c ? 1.0 : 0.0));
                }
                entry["matrix"] = located(m, op, source);
            } else if (tag == "lookat" || tag == "look_at") {
                check_attributes(op, source, {"origin", "target", "up"});
                Json::Value look(Json::objectValue);
                for (const char *key : {"origin", "target", "up"}) {
                    if (!op.attribute(key)) {
                        if (std::string(key) == "up") continue;
                        error(op, source, std::string("the attribute '") + key + "' is missing");
                    }
                    const std::vector<double> v = parse_numbers(substitute(op, source, key), op, source);
                    if (v.size() != 3) error(op, source, std::string("'") + key + "' needs 3 numbers");
                    Json::Value p(Json::arrayValue);
                    for (double x : v) p.append(x);
                    look[key] = located(p, op, source);
                }
                if (!look.isMember("up") ||
                    (look["up"][0].asDouble() == 0 && look["up"][1].asDouble() == 0 && look["up"][2].asDouble() == 0))
                    look["up"] = located(generated_up(look["origin"], look["target"]), op, source);
                entry["look_at"] = located(look, op, source);
            } else {
                error(op, source, "unknown transform operation (translate, rotate, scale, matrix, lookat)");
            }
            ops.append(located(entry, op, source));
        }
        return located(ops, node, source);
    }

    // Mitsuba's up vector for a lookat without one (or with a zero one): the first vector of
    // coordinate_system(view direction), the orthonormal basis of Duff et al. 2017 ("Building
    // an Orthonormal Basis, Revisited"), so that a camera looking along y still has a frame.
    static Json::Value generated_up(const Json::Value &origin, const Json::Value &target) {
        double d[3], length2 = 0;
        for (int i = 0; i < 3; ++i) {
            d[i] = target[i].asDouble() - origin[i].asDouble();
            length2 += d[i] * d[i];
        }
        Json::Value up(Json::arrayValue);
        if (!(length2 > 0)) { // the builder reports origin == target
            for (int i = 0; i < 3; ++i) up.append(i == 1 ? 1.0 : 0.0);
            return up;
        }
        for (double &c : d) c /= std::sqrt(length2);
        const double sign = std::copysign(1.0, d[2]);
        const double a = -1.0 / (sign + d[2]);
        const double b = d[0] * d[1] * a;
        for (double c : {1.0 + sign * d[0] * d[0] * a, sign * b, -sign * d[0]}) up.append(c);
        return up;
    }

    // ---- Mitsuba 0.x files -----------------------------------------------------------------

    // Mitsuba 3's upgrade of a property name from a file of version < 2.0 (its parser's
    // camel_to_underscore_case): "intIOR" is "int_ior", "sampleCount" "sample_count".
    static std::string upgraded_name(const std::string &name) {
        std::string out;
        for (std::size_t i = 0; i < name.size(); ++i) {
            const unsigned char c = static_cast<unsigned char>(name[i]);
            if (i > 0 && std::islower(static_cast<unsigned char>(name[i - 1])) && std::isupper(c)) {
                out += '_';
                out += static_cast<char>(std::tolower(c));
                while (i + 1 < name.size() && std::isupper(static_cast<unsigned char>(name[i + 1])))
                    out += static_cast<char>(std::tolower(static_cast<unsigned char>(name[++i])));
            } else {
                out += name[i];
            }
        }
        return out;
    }

    // The rest of Mitsuba 3's upgrade (its parser's upgrade_from_v1), on an object read from
    // such a file: diffuse's diffuse_reflectance is its reflectance, and uoffset, voffset,
    // uscale, vscale become the texture transform to_uv (the offset first, then the scale).
    static void upgrade_object(Json::Value &out) {
        if (out["type"].asString() == "diffuse" && out.isMember("diffuse_reflectance") &&
            !out.isMember("reflectance")) {
            out["reflectance"] = out["diffuse_reflectance"];
            out.removeMember("diffuse_reflectance");
        }
        double offset[2] = {0, 0}, scale[2] = {1, 1};
        bool any = false;
        const char *names[4] = {"uoffset", "voffset", "uscale", "vscale"};
        for (int k = 0; k < 4; ++k) {
            if (!out.isMember(names[k])) continue;
            (k < 2 ? offset : scale)[k % 2] = out[names[k]].asDouble();
            out.removeMember(names[k]);
            any = true;
        }
        if (!any || out.isMember("to_uv")) return;
        Json::Value ops(Json::arrayValue), translate(Json::objectValue), scaling(Json::objectValue);
        for (double v : {offset[0], offset[1], 0.0}) translate["translate"].append(v);
        for (double v : {scale[0], scale[1], 1.0}) scaling["scale"].append(v);
        ops.append(translate);
        ops.append(scaling);
        out["to_uv"] = ops;
    }

    // ---- objects ------------------------------------------------------------------------

    // An object element as {"type": ..., parameters under their Mitsuba names, nested objects
    // under their role}. BSDF references become the referenced id (a named material); other
    // references are replaced by the referenced object.
    Json::Value object(const pugi::xml_node &node, const Source &source, int depth = 0) {
        if (depth > 32) error(node, source, "objects nested deeper than 32 levels (a cycle of references?)");
        const std::string tag = node.name();
        check_attributes(node, source, {"type", "id", "name"});
        Json::Value out(Json::objectValue);
        out["type"] = located(Json::Value(substitute(node, source, "type")), node, source);
        for (const pugi::xml_node &child : node.children()) {
            if (child.type() != pugi::node_element) continue;
            const std::string kind = child.name();
            if (kind == "float" || kind == "integer" || kind == "boolean" || kind == "string" || kind == "rgb" ||
                kind == "spectrum" || kind == "point" || kind == "vector") {
                check_attributes(child, source, {"name", "value", "x", "y", "z"});
                const std::string name =
                    source.before_2 ? upgraded_name(required(child, source, "name")) : required(child, source, "name");
                if (out.isMember(name)) error(child, source, "the parameter '" + name + "' is given twice");
                out[name] = property(child, source, colour_range(tag, name));
            } else if (kind == "transform") {
                check_attributes(child, source, {"name"});
                const std::string name = required(child, source, "name");
                out[source.before_2 ? upgraded_name(name) : name] = transform(child, source);
            } else if (kind == "ref") {
                check_attributes(child, source, {"id", "name"});
                const std::string id = substitute(child, source, "id");
                const auto found = by_id_.find(id);
                if (found == by_id_.end()) error(child, source, "no object has the id \"" + id + "\"");
                referred_to_.insert(id);
                std::string role = child.attribute("name") ? std::string(child.attribute("name").value())
                                                           : std::string(found->second.node.name());
                if (source.before_2) role = upgraded_name(role);
                if (role == "bsdf" && !child.attribute("name") && out["type"].asString() == "blendbsdf")
                    role = out.isMember("bsdf_0") ? "bsdf_1" : "bsdf_0";
                if (!supported_nested(found->second.node, *found->second.source, child, source)) continue;
                // A BSDF referred to in any role (bsdf, blendbsdf's bsdf_0 and bsdf_1) is the
                // named material, shared.
                if (std::string(found->second.node.name()) == "bsdf") {
                    if (out.isMember(role)) error(child, source, "a second '" + role + "' in the same object");
                    out[role] = located(Json::Value(id), child, source);
                } else
                    out[role] = object(found->second.node, *found->second.source, depth + 1);
            } else if (object_tags().count(kind)) {
                std::string role =
                    kind == "texture" || child.attribute("name") ? required(child, source, "name") : kind;
                if (source.before_2) role = upgraded_name(role);
                // Mitsuba's blendbsdf takes its two nested BSDFs in order when they have no names.
                if (kind == "bsdf" && !child.attribute("name") && out["type"].asString() == "blendbsdf")
                    role = out.isMember("bsdf_0") ? "bsdf_1" : "bsdf_0";
                if (out.isMember(role)) error(child, source, "a second '" + role + "' in the same object");
                if (!supported_nested(child, source, child, source)) continue;
                out[role] = object(child, source, depth + 1);
            } else {
                error(child, source, "unknown element inside <" + tag + ">");
            }
        }
        if (source.before_2) upgrade_object(out);
        return located(out, node, source);
    }

    // Whether the nested object `node` (written at `at`) is one libppm renders: textures of
    // the texture table; no media. Otherwise an error, or with --lenient a warning, and the
    // parameter it fills keeps its default.
    bool supported_nested(const pugi::xml_node &node, const Source &source, const pugi::xml_node &at,
                          const Source &at_source) {
        const std::string tag = node.name();
        std::string what, left_out = ": left out";
        if (tag == "texture" && !renderable("texture").count(node.attribute("type").value())) {
            what = "texture type '" + std::string(node.attribute("type").value()) + "' is not supported by libppm" +
                   supported_list("texture");
            left_out = ": left out, the parameter keeps its default";
        } else if (tag == "medium" || tag == "phase" || tag == "volume") {
            what = "<" + tag + "> is not supported by libppm (participating media are not rendered)";
        }
        if (what.empty()) return true;
        if (!options_.lenient) error(at, at_source, what + " (with --lenient it is left out with a warning)");
        substituted(at, at_source, what + left_out);
        return false;
    }

    // " (supported: a, b, ...)" for the types of `tag` libppm renders.
    static std::string supported_list(const char *tag) {
        std::string list;
        for (const std::string &type : renderable(tag)) list += (list.empty() ? "" : ", ") + type;
        return " (supported: " + list + ")";
    }

    // A warning for what --lenient replaced or left out, counted for the summary.
    void substituted(const pugi::xml_node &node, const Source &source, const std::string &what) {
        warn(node, source, what);
        out_.substituted_at.push_back(where(node, source));
    }
    void substituted(const Json::Value &value, const char *tag, const std::string &what) {
        warn(value, tag, what);
        out_.substituted_at.push_back(where(value, tag));
    }

    Json::Value property(const pugi::xml_node &node, const Source &source, ColourRange range) {
        const std::string kind = node.name();
        if (kind == "point" || kind == "vector") return vector3(node, source);
        if (kind == "rgb" || kind == "spectrum") return colour(node, source, range);
        const std::string text = substitute(node, source, "value");
        if (kind == "string") {
            if (std::string(node.attribute("name").value()) == "filename")
                return located(Json::Value(resolve_data_file(node, source, text)), node, source);
            return located(Json::Value(text), node, source);
        }
        if (kind == "boolean") {
            if (text != "true" && text != "false") error(node, source, "'" + text + "' is not true or false");
            return located(Json::Value(text == "true"), node, source);
        }
        const double value = parse_number(text, node, source);
        if (kind == "integer") {
            if (value != std::floor(value) || std::fabs(value) > 9.007199254740992e15)
                error(node, source, "'" + text + "' is not an integer");
            return located(Json::Value(static_cast<Json::Int64>(value)), node, source);
        }
        return located(Json::Value(value), node, source);
    }

    // ---- the scene's parts --------------------------------------------------------------

    void convert_top_level(const Pending &pending) {
        const pugi::xml_node &node = pending.node;
        const Source &source = *pending.source;
        const std::string tag = node.name();
        const std::string id = node.attribute("id").value();
        Json::Value &root = out_.root;
        if (tag == "bsdf") {
            if (id.empty()) {
                warn(node, source, "a BSDF without id at the top is never used");
                return;
            }
            root["bsdfs"][id] = bsdf(object(node, source));
        } else if (tag == "texture") {
            if (id.empty()) warn(node, source, "a texture without id at the top is never used");
            // Textures with an id are inlined where they are referred to.
        } else if (tag == "shape") {
            Json::Value shape = this->shape(object(node, source));
            if (!shape.isNull()) root["shapes"].append(shape);
        } else if (tag == "emitter" && substitute(node, source, "type") == "area") {
            // An area emitter is the emission of the shape that holds it: at the top, it is
            // defined for the shapes that refer to its id (before or after this point).
            if (id.empty())
                skip(node, source, "an area emitter at the top has no shape to emit from (put it inside a <shape>)");
            else
                unattached_area_emitters_.push_back(pending);
        } else if (tag == "emitter") {
            Json::Value emitter = this->emitter(object(node, source));
            if (!emitter.isNull()) root["emitters"].append(emitter);
        } else if (tag == "sensor") {
            if (root.isMember("sensor")) error(node, source, "a second <sensor>: libppm renders one camera");
            sensor(object(node, source), node, source);
        } else if (tag == "integrator") {
            if (root.isMember("integrator") && root["integrator"].isMember("type"))
                error(node, source, "a second <integrator>");
            integrator(object(node, source), node, source);
        } else if (!id.empty()) {
            // Another object with an id (a sampler, film, medium...) is read where a <ref>
            // names it; one that nothing names is said once the whole file is read.
            referable_only_.push_back(pending);
        } else {
            skip(node, source, "<" + tag + "> is not supported by libppm");
        }
    }

    void skip(const pugi::xml_node &node, const Source &source, const std::string &what) {
        if (!options_.lenient) error(node, source, what + " (with --lenient it is skipped with a warning)");
        substituted(node, source, what + ": skipped");
    }

    // Unwraps twosided (libppm's opaque materials are two-sided) and resolves named indices of
    // refraction; lenient mode replaces what the builder cannot render by diffuse grey 0.5.
    Json::Value bsdf(Json::Value value) {
        if (value.isString()) return value; // a named material
        const std::string type = value["type"].asString();
        if (type == "twosided") {
            for (const char *role : {"bsdf", "brdf_0"})
                if (value.isMember(role)) return bsdf(value[role]);
            error(value, "bsdf", "a twosided BSDF needs a nested <bsdf>");
        }
        if (type == "blendbsdf" || type == "mask") {
            // Nested BSDFs (elements or references, in their roles) get the same treatment.
            for (const char *role : {"bsdf", "bsdf_0", "bsdf_1"})
                if (value.isMember(role)) value[role] = bsdf(value[role]);
            return value;
        }
        if (!renderable("bsdf").count(type)) {
            const std::string what = "BSDF type '" + type + "' is not supported by libppm";
            if (!options_.lenient)
                error(value, "bsdf", what + supported_list("bsdf") + " (with --lenient it is replaced with a warning)");
            // A wrapper that only bends the shading frame: what it wraps, as it is.
            if ((type == "bumpmap" || type == "normalmap") && value.isMember("bsdf")) {
                substituted(value, "bsdf", what + ": the BSDF it wraps is rendered without it");
                return bsdf(value["bsdf"]);
            }
            substituted(value, "bsdf", what + ": diffuse grey 0.5 instead");
            Json::Value grey(Json::objectValue);
            grey["type"] = "diffuse";
            grey.setOffsetStart(value.getOffsetStart());
            grey.setOffsetLimit(value.getOffsetLimit());
            return grey;
        }
        for (const char *key : {"int_ior", "ext_ior"}) {
            if (!value.isMember(key) || !value[key].isString()) continue;
            const auto found = named_iors().find(value[key].asString());
            if (found == named_iors().end())
                error(value[key], "bsdf",
                      std::string(key) + " \"" + value[key].asString() + "\" is not a known material");
            const Json::Value where = value[key];
            value[key] = Json::Value(found->second);
            value[key].setOffsetStart(where.getOffsetStart());
            value[key].setOffsetLimit(where.getOffsetLimit());
        }
        return value;
    }

    // Whether the emitter or shape `value` (of element `tag`) has a type libppm renders;
    // otherwise an error, or with --lenient a warning, and it is skipped.
    bool renders_type(const Json::Value &value, const char *tag) {
        const std::string type = value["type"].asString();
        if (renderable(tag).count(type)) return true;
        const std::string what = std::string(tag) + " type '" + type + "' is not supported by libppm";
        if (!options_.lenient)
            error(value, tag, what + supported_list(tag) + " (with --lenient it is skipped with a warning)");
        substituted(value, tag, what + ": skipped");
        return false;
    }

    Json::Value emitter(Json::Value value) { return renders_type(value, "emitter") ? value : Json::Value(); }

    Json::Value shape(Json::Value value) {
        if (!renders_type(value, "shape")) return Json::Value();
        if (value.isMember("bsdf")) value["bsdf"] = bsdf(value["bsdf"]);
        if (value.isMember("emitter")) {
            Json::Value emitter = this->emitter(value["emitter"]);
            if (emitter.isNull())
                value.removeMember("emitter");
            else
                value["emitter"] = emitter;
        }
        return value;
    }

    // The film's size and the field of view along libppm's x axis.
    void sensor(Json::Value value, const pugi::xml_node &node, const Source &source) {
        Json::Value out(Json::objectValue);
        out["type"] = value["type"];
        double width = 768, height = 576;
        if (value.isMember("film")) {
            Json::Value film = value["film"];
            Json::Value size(Json::objectValue);
            for (const char *key : {"width", "height"})
                if (film.isMember(key)) size[key] = film[key];
            if (size.isMember("width")) width = size["width"].asDouble();
            if (size.isMember("height")) height = size["height"].asDouble();
            size["rfilter"] = pixel_filter(film.isMember("rfilter") ? film["rfilter"] : Json::Value(), node, source);
            out["film"] = located(size, node, source);
        }
        if (!value.isMember("film")) {
            // Mitsuba's default film: hdrfilm with its default, gaussian filter.
            Json::Value film(Json::objectValue);
            film["rfilter"] = pixel_filter(Json::Value(), node, source);
            out["film"] = located(film, node, source);
        }
        if (value.isMember("sampler")) {
            // One pass per sample: both are the unit of progress, and a pass is as cheap as a
            // few samples per pixel of a path tracer. An integrator's own count wins.
            const Json::Value &sampler = value["sampler"];
            Json::Value &integrator = integrator_settings();
            if (sampler.isMember("sample_count") && !integrator.isMember("passes"))
                integrator["passes"] = sampler["sample_count"];
            if (sampler.isMember("seed")) integrator["seed"] = sampler["seed"];
        }
        if (value.isMember("fov")) {
            const std::string axis = value.isMember("fov_axis") ? value["fov_axis"].asString() : "x";
            const double fov = value["fov"].asDouble();
            const double tan_half = std::tan(fov * M_PI / 360.0);
            double x_over_axis = 1; // tan(half fov along x) / tan(half fov along the axis)
            if (axis == "y")
                x_over_axis = width / height;
            else if (axis == "diagonal")
                x_over_axis = width / std::hypot(width, height);
            else if (axis == "smaller")
                x_over_axis = width <= height ? 1 : width / height;
            else if (axis == "larger")
                x_over_axis = width >= height ? 1 : width / height;
            else if (axis != "x")
                error(node, source, "fov_axis \"" + axis + "\" is not x, y, diagonal, smaller or larger");
            Json::Value fov_x(2 * std::atan(tan_half * x_over_axis) * 180.0 / M_PI);
            fov_x.setOffsetStart(value["fov"].getOffsetStart());
            fov_x.setOffsetLimit(value["fov"].getOffsetLimit());
            out["fov"] = fov_x;
        }
        for (const char *key : {"to_world", "near_clip", "aperture_radius", "focus_distance"})
            if (value.isMember(key)) out[key] = value[key];
        for (const char *ignored : {"far_clip", "shutter_open", "shutter_close", "srf"})
            if (value.isMember(ignored)) warn(node, source, std::string("'") + ignored + "' is ignored");
        for (const std::string &key : value.getMemberNames())
            if (key != "type" && key != "film" && key != "sampler" && key != "fov" && key != "fov_axis" &&
                !out.isMember(key) && key != "far_clip" && key != "shutter_open" && key != "shutter_close" &&
                key != "srf")
                out[key] = value[key]; // the builder names what it does not know
        out_.root["sensor"] = located(out, node, source);
    }

    // The film's reconstruction filter as libppm reads it: Mitsuba's default (none given) is
    // the gaussian; the filters with negative lobes, which libppm does not render, are read as
    // that with a warning.
    Json::Value pixel_filter(const Json::Value &rfilter, const pugi::xml_node &node, const Source &source) {
        Json::Value out(Json::objectValue);
        const std::string type = rfilter.isNull() ? "gaussian" : rfilter["type"].asString();
        if (type == "box" || type == "tent" || type == "gaussian") {
            out = rfilter.isNull() ? Json::Value(Json::objectValue) : rfilter;
            out["type"] = type;
        } else {
            warn(rfilter, "rfilter",
                 "pixel filter '" + type +
                     "' is not supported by libppm (its negative lobes): read as Mitsuba's default, the gaussian");
            out["type"] = "gaussian";
        }
        return located(out, node, source);
    }

    Json::Value &integrator_settings() {
        Json::Value &settings = out_.root["integrator"];
        if (settings.isNull()) settings = Json::Value(Json::objectValue);
        return settings;
    }

    void integrator(Json::Value value, const pugi::xml_node &node, const Source &source) {
        Json::Value &out = integrator_settings();
        const std::string type = value["type"].asString();
        if (type == "sppm" || type == "ppm") {
            out["type"] = value["type"];
        } else {
            warn(node, source,
                 "integrator '" + type + "' read as \"render this scene\": libppm renders it in its default mode, vcm");
        }
        // Mitsuba's max_depth counts the emitted vertex too; -1 is unlimited.
        if (value.isMember("max_depth")) {
            const Json::Int64 depth = value["max_depth"].asInt64();
            Json::Value converted(depth < 0 ? Json::Int64(1000) : std::max<Json::Int64>(1, depth - 1));
            converted.setOffsetStart(value["max_depth"].getOffsetStart());
            out["max_depth"] = converted;
        }
        static const std::map<std::string, std::string> renamed = {{"photon_count", "photons_per_pass"},
                                                                   {"initial_radius", "initial_radius"},
                                                                   {"alpha", "alpha"},
                                                                   {"max_passes", "passes"},
                                                                   {"seed", "seed"}};
        for (const std::string &key : value.getMemberNames()) {
            if (key == "type" || key == "max_depth") continue;
            const auto found = renamed.find(key);
            if (found != renamed.end() && (type == "sppm" || type == "ppm"))
                out[found->second] = value[key];
            else
                warn(node, source, "integrator parameter '" + key + "' is ignored");
        }
        out = located(out, node, source);
    }

    const XmlOptions &options_;
    XmlScene &out_;
    std::map<std::string, std::string> parameters_;
    mutable std::set<std::string> referenced_; // every $name met, known or not
    std::vector<std::unique_ptr<Source>> sources_;
    std::vector<std::string> include_stack_;
    std::map<std::string, Pending> by_id_;
    std::vector<Pending> top_level_;
    std::vector<std::string> search_folders_;       // of <path>, the latest first, each ending in '/'
    std::set<std::string> referred_to_;             // ids named by a <ref>
    std::vector<Pending> unattached_area_emitters_; // at the top, with an id
    std::vector<Pending> referable_only_;           // other objects at the top with an id
};

} // namespace

namespace {

XmlScene read(const std::string &path, const XmlOptions &options, const std::string *text, const std::string *folder) {
    XmlScene scene;
    try {
        XmlReader(options, scene).read(path, text, folder);
    } catch (const Error &e) {
        std::vector<std::string> said = scene.warnings;
        said.insert(said.end(), scene.failure_notes.begin(), scene.failure_notes.end());
        throw LoadError(e, said);
    }
    return scene;
}

} // namespace

XmlScene read_mitsuba_xml(const std::string &path, const XmlOptions &options) {
    return read(path, options, nullptr, nullptr);
}

XmlScene read_mitsuba_xml(const std::string &path, const XmlOptions &options, const std::string *text,
                          const std::string &folder) {
    return read(path, options, text, &folder);
}

} // namespace ppm
