// SPDX-License-Identifier: Apache-2.0
#include "io/obj_reader.h"

#include "core/error.h"
#include "io/text_file.h"
#include "math/limits.h"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <tuple>

namespace ppm {

namespace {

// One pass over the text that both checks and reads, so that what is validated is exactly
// what is used: no second tokenizer can disagree about what separates words and let a face
// index point past the arrays.
//
// Words are separated by spaces and tabs only; a line ends at "\n" (a "\r" just before it is
// dropped). Any other control character is an error, so that no byte is silently read as a
// separator by one part of the code and as part of a word by another.
class ObjReader {
public:
    ObjReader(const std::string &text, const std::string &name) : text_(text), name_(name) {}

    MeshData read() {
        std::size_t start = 0;
        while (start < text_.size()) {
            std::size_t end = text_.find('\n', start);
            if (end == std::string::npos) end = text_.size();
            ++line_number_;
            std::size_t stop = end;
            if (stop > start && text_[stop - 1] == '\r') --stop;
            read_line(start, stop);
            start = end + 1;
        }
        if (faces_.empty()) fail(PPM_ERROR_PARSE, name_ + ": the file has no faces");
        return build_mesh();
    }

private:
    struct Corner {
        long position, texcoord, normal; // 0-based, -1 when absent
    };
    struct Face {
        std::size_t first, count; // its corners in corners_
        std::size_t line;
    };

    [[noreturn]] void error(const std::string &what) const {
        fail(PPM_ERROR_PARSE, name_ + ":" + std::to_string(line_number_) + ": " + what);
    }

    // Splits [start, stop) into words; a word starting with '#' ends the line.
    void read_line(std::size_t start, std::size_t stop) {
        words_.clear();
        std::size_t k = start;
        while (k < stop) {
            const unsigned char c = static_cast<unsigned char>(text_[k]);
            if (c == ' ' || c == '\t') {
                ++k;
                continue;
            }
            if (c == '#') break;
            std::size_t word_end = k;
            while (word_end < stop && text_[word_end] != ' ' && text_[word_end] != '\t') {
                const unsigned char w = static_cast<unsigned char>(text_[word_end]);
                if (w < 0x20 || w == 0x7f) {
                    char code[8];
                    std::snprintf(code, sizeof code, "0x%02x", w);
                    error(std::string("control character ") + code +
                          " in the line (words are separated by "
                          "spaces and tabs, lines end with a line feed)");
                }
                ++word_end;
            }
            words_.emplace_back(text_, k, word_end - k);
            k = word_end;
        }
        if (words_.empty()) return;
        const std::string &keyword = words_[0];
        if (keyword == "v")
            read_vector(positions_, 3);
        else if (keyword == "vn")
            read_vector(normals_, 3);
        else if (keyword == "vt")
            read_texcoord();
        else if (keyword == "f")
            read_face();
        // Everything else (o, g, s, usemtl, mtllib, l, p, ...) does not change the surface.
    }

    double number(const std::string &word) const {
        char *end = nullptr;
        const double value = std::strtod(word.c_str(), &end);
        if (word.empty() || end != word.c_str() + word.size()) error("'" + word + "' is not a number");
        if (!std::isfinite(value)) error("coordinate '" + word + "' is not finite");
        if (!within(value, kCoordinateLimit))
            error("coordinate '" + word + "' lies beyond +-" + format_number(kCoordinateLimit) +
                  " (the limit of scene coordinates)");
        return value;
    }

    // "v x y z [w or r g b]" and "vn x y z": the first three numbers; the rest must be numbers.
    void read_vector(std::vector<Vec3> &into, std::size_t needed) {
        if (words_.size() - 1 < needed)
            error("'" + words_[0] + "' needs " + std::to_string(needed) + " numbers, found " +
                  std::to_string(words_.size() - 1));
        for (std::size_t i = needed + 1; i < words_.size(); ++i) number(words_[i]);
        into.push_back({number(words_[1]), number(words_[2]), number(words_[3])});
    }

    // "vt u [v [w]]": v defaults to 0.
    void read_texcoord() {
        if (words_.size() < 2) error("'vt' needs at least 1 number, found 0");
        for (std::size_t i = 3; i < words_.size(); ++i) number(words_[i]);
        texcoords_.push_back({number(words_[1]), words_.size() > 2 ? number(words_[2]) : 0.0});
    }

    // A 1-based index, or a negative one relative to the end of what is defined so far.
    long index(const std::string &word, std::size_t defined, const char *what) const {
        char *end = nullptr;
        errno = 0;
        const long long value = std::strtoll(word.c_str(), &end, 10);
        if (word.empty() || end != word.c_str() + word.size() || errno == ERANGE)
            error(std::string("face ") + what + " index '" + word + "' is not an integer");
        const long long n = static_cast<long long>(defined);
        if (value == 0 || value > n || value < -n)
            error(std::string("face ") + what + " index " + word + " is out of range (" + std::to_string(defined) +
                  " defined so far)");
        return static_cast<long>(value > 0 ? value - 1 : n + value);
    }

    // "f v1 v2 v3 ...", each corner "v", "v/t", "v//n" or "v/t/n".
    void read_face() {
        Face face{corners_.size(), 0, line_number_};
        for (std::size_t i = 1; i < words_.size(); ++i) {
            const std::string &word = words_[i];
            const std::size_t slash1 = word.find('/');
            const std::size_t slash2 = slash1 == std::string::npos ? std::string::npos : word.find('/', slash1 + 1);
            if (slash2 != std::string::npos && word.find('/', slash2 + 1) != std::string::npos)
                error("face corner '" + word + "' has more than three parts");
            const std::string position = word.substr(0, slash1);
            if (position.empty()) error("face corner '" + word + "' has no vertex index");
            Corner corner{index(position, positions_.size(), "vertex"), -1, -1};
            if (slash1 != std::string::npos) {
                const std::string texcoord =
                    word.substr(slash1 + 1, slash2 == std::string::npos ? std::string::npos : slash2 - slash1 - 1);
                if (!texcoord.empty()) corner.texcoord = index(texcoord, texcoords_.size(), "texture coordinate");
            }
            if (slash2 != std::string::npos) {
                const std::string normal = word.substr(slash2 + 1);
                if (normal.empty()) error("face corner '" + word + "' ends with '/' but has no normal index");
                corner.normal = index(normal, normals_.size(), "normal");
            }
            corners_.push_back(corner);
        }
        face.count = corners_.size() - face.first;
        if (face.count < 3) error("a face needs at least 3 corners, found " + std::to_string(face.count));
        faces_.push_back(face);
    }

    // Fans each polygon from its first corner (as Mitsuba 3's OBJ loader does). A fan triangle
    // that repeats a vertex index has no area and is left out; a face left with no triangle at
    // all is an error, so that no face disappears without a word.
    MeshData build_mesh() const {
        bool all_normals = true, all_texcoords = true;
        for (const Corner &corner : corners_) {
            all_normals = all_normals && corner.normal >= 0;
            all_texcoords = all_texcoords && corner.texcoord >= 0;
        }

        // OBJ indexes positions, normals and texture coordinates separately; Embree wants one
        // index per corner, so each distinct combination becomes a vertex.
        MeshData mesh;
        std::map<std::tuple<long, long, long>, uint32_t> vertex_of;
        auto vertex = [&](const Corner &corner) {
            const auto key = std::make_tuple(corner.position, all_normals ? corner.normal : -1,
                                             all_texcoords ? corner.texcoord : -1);
            const auto found = vertex_of.find(key);
            if (found != vertex_of.end()) return found->second;
            const uint32_t id = static_cast<uint32_t>(mesh.positions.size());
            mesh.positions.push_back(positions_[static_cast<std::size_t>(corner.position)]);
            if (all_normals) mesh.normals.push_back(normals_[static_cast<std::size_t>(corner.normal)]);
            if (all_texcoords) {
                const auto &uv = texcoords_[static_cast<std::size_t>(corner.texcoord)];
                // OBJ's vt has v = 0 at the image's bottom row; libppm (like Mitsuba 3,
                // whose OBJ loader does the same) has v = 0 at the top.
                mesh.uvs.push_back(uv[0]);
                mesh.uvs.push_back(1.0 - uv[1]);
            }
            vertex_of.emplace(key, id);
            return id;
        };
        for (const Face &face : faces_) {
            const Corner *c = corners_.data() + face.first;
            std::size_t triangles = 0;
            for (std::size_t i = 2; i < face.count; ++i) {
                if (c[0].position == c[i - 1].position || c[0].position == c[i].position ||
                    c[i - 1].position == c[i].position)
                    continue;
                mesh.indices.push_back(vertex(c[0]));
                mesh.indices.push_back(vertex(c[i - 1]));
                mesh.indices.push_back(vertex(c[i]));
                ++triangles;
            }
            if (triangles == 0)
                fail(PPM_ERROR_PARSE,
                     name_ + ":" + std::to_string(face.line) + ": the face repeats its corners and has no area");
        }
        return mesh;
    }

    const std::string &text_;
    const std::string &name_;
    std::size_t line_number_ = 0;
    std::vector<std::string> words_;
    std::vector<Vec3> positions_, normals_;
    std::vector<std::array<double, 2>> texcoords_;
    std::vector<Corner> corners_;
    std::vector<Face> faces_;
};

} // namespace

MeshData parse_obj(const std::string &text, const std::string &name) { return ObjReader(text, name).read(); }

MeshData read_obj_file(const std::string &path) { return parse_obj(read_text_file(path), path); }

} // namespace ppm
