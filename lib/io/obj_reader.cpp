#include "io/obj_reader.h"

#include "core/error.h"
#include "io/text_file.h"

#include <tiny_obj_loader.h>

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <map>
#include <sstream>
#include <tuple>

namespace ppm {

namespace {

// tinyobjloader is lenient: it reads "nan" or garbage as some number and does not say on
// which line a bad face index stands. This pass checks the lines we use and names the line.
void check_obj_lines(const std::string &text, const std::string &name) {
    std::istringstream in(text);
    std::string line;
    size_t line_number = 0, positions = 0, normals = 0, texcoords = 0;
    auto error = [&](const std::string &what) {
        fail(PPM_ERROR_PARSE, name + ":" + std::to_string(line_number) + ": " + what);
    };
    auto check_index = [&](const std::string &text_index, size_t count, const char *what) {
        if (text_index.empty()) return;
        char *end = nullptr;
        errno = 0;
        const long long index = std::strtoll(text_index.c_str(), &end, 10);
        if (end != text_index.c_str() + text_index.size() || errno == ERANGE)
            error(std::string("face ") + what + " index '" + text_index + "' is not an integer");
        const long long n = static_cast<long long>(count);
        if (index == 0 || index > n || index < -n)
            error(std::string("face ") + what + " index " + text_index + " is out of range (" +
                  std::to_string(count) + " defined so far)");
    };
    while (std::getline(in, line)) {
        ++line_number;
        std::istringstream words(line);
        std::string keyword;
        if (!(words >> keyword)) continue;
        if (keyword == "v" || keyword == "vn" || keyword == "vt") {
            const int needed = keyword == "vt" ? 1 : 3;
            int read = 0;
            std::string token;
            while (words >> token) {
                if (token[0] == '#') break;
                char *end = nullptr;
                const double value = std::strtod(token.c_str(), &end);
                if (end != token.c_str() + token.size()) error("'" + token + "' is not a number");
                if (!std::isfinite(value)) error("coordinate '" + token + "' is not finite");
                ++read;
            }
            if (read < needed)
                error("'" + keyword + "' needs " + std::to_string(needed) + " numbers, found " +
                      std::to_string(read));
            (keyword == "v" ? positions : keyword == "vn" ? normals : texcoords) += 1;
        } else if (keyword == "f") {
            std::string corner;
            int corners = 0;
            while (words >> corner) {
                if (corner[0] == '#') break;
                const size_t slash1 = corner.find('/');
                const size_t slash2 = slash1 == std::string::npos ? std::string::npos : corner.find('/', slash1 + 1);
                const std::string v = corner.substr(0, slash1);
                if (v.empty()) error("face corner '" + corner + "' has no vertex index");
                check_index(v, positions, "vertex");
                if (slash1 != std::string::npos)
                    check_index(corner.substr(slash1 + 1, slash2 == std::string::npos ? std::string::npos : slash2 - slash1 - 1),
                                texcoords, "texture coordinate");
                if (slash2 != std::string::npos) check_index(corner.substr(slash2 + 1), normals, "normal");
                ++corners;
            }
            if (corners < 3) error("a face needs at least 3 corners, found " + std::to_string(corners));
        }
    }
}

// tinyobjloader takes a comment after a face ("f 1 2 3 # top") for more corners and fails;
// check_obj_lines accepts it. Blank out every '#' that starts a word, to the end of its line,
// keeping the newlines so that line numbers stay right.
std::string without_comments(const std::string &text) {
    std::string out = text;
    bool in_comment = false;
    for (size_t k = 0; k < out.size(); ++k) {
        if (out[k] == '\n') {
            in_comment = false;
        } else if (out[k] == '#' && (k == 0 || std::isspace(static_cast<unsigned char>(out[k - 1])))) {
            in_comment = true;
        }
        if (in_comment) out[k] = ' ';
    }
    return out;
}

} // namespace

MeshData parse_obj(const std::string &text, const std::string &name) {
    check_obj_lines(text, name);
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromString(without_comments(text), "", config))
        fail(PPM_ERROR_PARSE, name + ": " + (reader.Error().empty() ? "not a valid OBJ file" : reader.Error()));

    const tinyobj::attrib_t &attrib = reader.GetAttrib();
    bool all_normals = true, all_texcoords = true;
    size_t corners = 0;
    for (const tinyobj::shape_t &shape : reader.GetShapes())
        for (const tinyobj::index_t &index : shape.mesh.indices) {
            all_normals = all_normals && index.normal_index >= 0;
            all_texcoords = all_texcoords && index.texcoord_index >= 0;
            ++corners;
        }
    if (corners == 0) fail(PPM_ERROR_PARSE, name + ": the file has no faces");

    // OBJ indexes positions, normals and texture coordinates separately; Embree wants one
    // index per corner, so each distinct combination becomes a vertex.
    MeshData mesh;
    std::map<std::tuple<int, int, int>, uint32_t> vertex_of;
    for (const tinyobj::shape_t &shape : reader.GetShapes())
        for (const tinyobj::index_t &index : shape.mesh.indices) {
            const auto key = std::make_tuple(index.vertex_index, all_normals ? index.normal_index : -1,
                                             all_texcoords ? index.texcoord_index : -1);
            auto found = vertex_of.find(key);
            if (found == vertex_of.end()) {
                const uint32_t id = static_cast<uint32_t>(mesh.positions.size());
                const size_t v = static_cast<size_t>(index.vertex_index);
                mesh.positions.push_back({attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]});
                if (all_normals) {
                    const size_t n = static_cast<size_t>(index.normal_index);
                    mesh.normals.push_back({attrib.normals[3 * n], attrib.normals[3 * n + 1], attrib.normals[3 * n + 2]});
                }
                if (all_texcoords) {
                    const size_t t = static_cast<size_t>(index.texcoord_index);
                    // OBJ's vt has v = 0 at the image's bottom row; libppm (like Mitsuba 3,
                    // whose OBJ loader does the same) has v = 0 at the top.
                    mesh.uvs.push_back(attrib.texcoords[2 * t]);
                    mesh.uvs.push_back(1.0 - attrib.texcoords[2 * t + 1]);
                }
                found = vertex_of.emplace(key, id).first;
            }
            mesh.indices.push_back(found->second);
        }
    return mesh;
}

MeshData read_obj_file(const std::string &path) { return parse_obj(read_text_file(path), path); }

} // namespace ppm
