// SPDX-License-Identifier: Apache-2.0
#include "io/ply_reader.h"

#include "core/error.h"
#include "io/text_file.h"
#include "math/limits.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <set>

namespace ppm {

namespace {

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct Property {
    std::string name;
    Scalar type = Scalar::Float32;
    bool is_list = false;
    Scalar count_type = Scalar::UInt8; // lists: the type of their length
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
    std::size_t header_line = 0;
};

std::size_t scalar_bytes(Scalar type) {
    switch (type) {
    case Scalar::Int8:
    case Scalar::UInt8: return 1;
    case Scalar::Int16:
    case Scalar::UInt16: return 2;
    case Scalar::Int32:
    case Scalar::UInt32:
    case Scalar::Float32: return 4;
    case Scalar::Float64: return 8;
    }
    return 8;
}

bool is_integer(Scalar type) { return type != Scalar::Float32 && type != Scalar::Float64; }

// The type names of PLY 1.0 and the sized aliases most writers use.
bool scalar_of(const std::string &word, Scalar *type) {
    static const struct {
        const char *name;
        Scalar type;
    } names[] = {{"char", Scalar::Int8},      {"int8", Scalar::Int8},       {"uchar", Scalar::UInt8},
                 {"uint8", Scalar::UInt8},    {"short", Scalar::Int16},     {"int16", Scalar::Int16},
                 {"ushort", Scalar::UInt16},  {"uint16", Scalar::UInt16},   {"int", Scalar::Int32},
                 {"int32", Scalar::Int32},    {"uint", Scalar::UInt32},     {"uint32", Scalar::UInt32},
                 {"float", Scalar::Float32},  {"float32", Scalar::Float32}, {"double", Scalar::Float64},
                 {"float64", Scalar::Float64}};
    for (const auto &entry : names)
        if (word == entry.name) {
            *type = entry.type;
            return true;
        }
    return false;
}

// The words of one header line, split on spaces and tabs.
std::vector<std::string> split_words(const std::string &line) {
    std::vector<std::string> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

// The roles the mesh gives an element's properties; the rest are skipped.
struct VertexLayout {
    int x = -1, y = -1, z = -1, nx = -1, ny = -1, nz = -1, u = -1, v = -1;
};

class PlyReader {
public:
    PlyReader(const std::string &bytes, const std::string &name) : bytes_(bytes), name_(name) {}

    PlyMesh read() {
        read_header();
        check_sizes();
        for (const Element &element : elements_) read_element(element);
        if (format_ == Format::Ascii) {
            skip_ascii_space();
            if (position_ < bytes_.size()) ascii_error("data after the last element");
        }
        if (faces_read_ == 0) fail(PPM_ERROR_PARSE, name_ + ": the file has no faces");
        PlyMesh result;
        result.mesh = std::move(mesh_);
        result.warnings = std::move(warnings_);
        return result;
    }

private:
    // ---- header ---------------------------------------------------------------------------

    [[noreturn]] void header_error(const std::string &what) const {
        fail(PPM_ERROR_PARSE, name_ + ": header line " + std::to_string(line_) + ": " + what);
    }

    bool next_header_line(std::string *line) {
        if (position_ >= bytes_.size()) return false;
        std::size_t end = bytes_.find('\n', position_);
        if (end == std::string::npos) end = bytes_.size();
        std::size_t stop = end;
        if (stop > position_ && bytes_[stop - 1] == '\r') --stop;
        *line = bytes_.substr(position_, stop - position_);
        position_ = end < bytes_.size() ? end + 1 : end;
        ++line_;
        for (char c : *line)
            if (static_cast<unsigned char>(c) < 0x20 && c != '\t') header_error("control character in the header");
        return true;
    }

    void read_header() {
        std::string line;
        if (!next_header_line(&line) || line != "ply")
            fail(PPM_ERROR_PARSE, name_ + ": not a PLY file (the first line is not 'ply')");
        bool have_format = false;
        while (true) {
            if (!next_header_line(&line)) header_error("the file ends before 'end_header'");
            const std::vector<std::string> words = split_words(line);
            if (words.empty()) continue;
            const std::string &keyword = words[0];
            if (keyword == "comment" || keyword == "obj_info") continue;
            if (keyword == "end_header") break;
            if (keyword == "format") {
                read_format(words);
                have_format = true;
            } else if (keyword == "element") {
                if (!have_format) header_error("'element' before 'format'");
                read_element_line(words);
            } else if (keyword == "property") {
                if (elements_.empty()) header_error("'property' before any 'element'");
                read_property_line(words);
            } else {
                header_error("unknown keyword '" + keyword + "'");
            }
        }
        if (!have_format) header_error("no 'format' line");
        body_line_ = line_ + 1;
    }

    void read_format(const std::vector<std::string> &words) {
        if (words.size() != 3) header_error("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
        if (words[1] == "ascii")
            format_ = Format::Ascii;
        else if (words[1] == "binary_little_endian")
            format_ = Format::BinaryLittleEndian;
        else if (words[1] == "binary_big_endian")
            format_ = Format::BinaryBigEndian;
        else
            header_error("unknown format '" + words[1] + "'");
        if (words[2] != "1.0") header_error("unsupported version '" + words[2] + "' (1.0 is read)");
    }

    void read_element_line(const std::vector<std::string> &words) {
        if (words.size() != 3) header_error("expected 'element <name> <count>'");
        Element element;
        element.name = words[1];
        element.header_line = line_;
        errno = 0;
        char *end = nullptr;
        const unsigned long long count = std::strtoull(words[2].c_str(), &end, 10);
        if (words[2][0] == '-' || end != words[2].c_str() + words[2].size() || errno == ERANGE)
            header_error("element count '" + words[2] + "' is not a whole number");
        element.count = count;
        for (const Element &other : elements_)
            if (other.name == element.name) header_error("element '" + element.name + "' is declared twice");
        elements_.push_back(element);
    }

    void read_property_line(const std::vector<std::string> &words) {
        Property property;
        if (words.size() >= 2 && words[1] == "list") {
            if (words.size() != 5) header_error("expected 'property list <count type> <item type> <name>'");
            if (!scalar_of(words[2], &property.count_type) || !is_integer(property.count_type))
                header_error("list count type '" + words[2] + "' is not an integer type");
            if (!scalar_of(words[3], &property.type)) header_error("unknown type '" + words[3] + "'");
            property.is_list = true;
            property.name = words[4];
        } else {
            if (words.size() != 3) header_error("expected 'property <type> <name>'");
            if (!scalar_of(words[1], &property.type)) header_error("unknown type '" + words[1] + "'");
            property.name = words[2];
        }
        Element &element = elements_.back();
        for (const Property &other : element.properties)
            if (other.name == property.name)
                header_error("property '" + property.name + "' of element '" + element.name + "' is declared twice");
        element.properties.push_back(property);
    }

    // Every element needs at least some bytes per instance: counts the rest of the file cannot
    // hold are refused before anything is allocated for them.
    void check_sizes() const {
        // An ASCII value takes a character and a separator, but the last needs no separator.
        const std::uint64_t remaining = bytes_.size() - position_ + (format_ == Format::Ascii ? 1 : 0);
        std::uint64_t needed = 0;
        for (const Element &element : elements_) {
            std::uint64_t per_instance = 0;
            for (const Property &p : element.properties)
                per_instance += format_ == Format::Ascii ? 2 : scalar_bytes(p.is_list ? p.count_type : p.type);
            if (per_instance == 0) continue;
            if (element.count > remaining / per_instance || needed + element.count * per_instance > remaining)
                fail(PPM_ERROR_PARSE, name_ + ": header line " + std::to_string(element.header_line) + ": element '" +
                                          element.name + "' claims " + std::to_string(element.count) +
                                          " entries, more than the file's remaining " + std::to_string(remaining) +
                                          " bytes can hold");
            needed += element.count * per_instance;
        }
    }

    // ---- body -----------------------------------------------------------------------------

    [[noreturn]] void ascii_error(const std::string &what) const {
        fail(PPM_ERROR_PARSE, name_ + ":" + std::to_string(body_line_) + ": " + what);
    }
    [[noreturn]] void binary_error(const std::string &what, std::size_t at) const {
        fail(PPM_ERROR_PARSE, name_ + ": byte " + std::to_string(at) + ": " + what);
    }
    // "vertex 12", for messages.
    static std::string instance(const Element &element, std::uint64_t index) {
        return element.name + " " + std::to_string(index);
    }
    [[noreturn]] void error_at(const std::string &what, std::size_t byte) const {
        if (format_ == Format::Ascii) ascii_error(what);
        binary_error(what, byte);
    }

    void skip_ascii_space() {
        while (position_ < bytes_.size()) {
            const char c = bytes_[position_];
            if (c == '\n')
                ++body_line_;
            else if (c != ' ' && c != '\t' && c != '\r')
                break;
            ++position_;
        }
    }

    // One value of `type`, as a double (every PLY scalar fits one exactly).
    double read_value(Scalar type, const Element &element, std::uint64_t index, const char *what) {
        if (format_ == Format::Ascii) return read_ascii_value(type, element, index, what);
        const std::size_t size = scalar_bytes(type);
        if (bytes_.size() - position_ < size)
            binary_error("the file ends inside " + instance(element, index) + " (of " + std::to_string(element.count) +
                             ")",
                         position_);
        unsigned char raw[8];
        std::memcpy(raw, bytes_.data() + position_, size);
        position_ += size;
        const bool swap = (format_ == Format::BinaryBigEndian) != (__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__);
        if (swap)
            for (std::size_t i = 0; i < size / 2; ++i) std::swap(raw[i], raw[size - 1 - i]);
        switch (type) {
        case Scalar::Int8: return static_cast<std::int8_t>(raw[0]);
        case Scalar::UInt8: return raw[0];
        case Scalar::Int16: return load<std::int16_t>(raw);
        case Scalar::UInt16: return load<std::uint16_t>(raw);
        case Scalar::Int32: return load<std::int32_t>(raw);
        case Scalar::UInt32: return load<std::uint32_t>(raw);
        case Scalar::Float32: return load<float>(raw);
        case Scalar::Float64: return load<double>(raw);
        }
        return 0;
    }

    template <class T> static double load(const unsigned char *raw) {
        T value;
        std::memcpy(&value, raw, sizeof value);
        return static_cast<double>(value);
    }

    double read_ascii_value(Scalar type, const Element &element, std::uint64_t index, const char *what) {
        skip_ascii_space();
        const std::size_t start = position_;
        while (position_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[position_]))) {
            if (static_cast<unsigned char>(bytes_[position_]) < 0x20) ascii_error("control character in the data");
            ++position_;
        }
        if (position_ == start)
            ascii_error("the file ends inside " + instance(element, index) + " (of " + std::to_string(element.count) +
                        ")");
        const std::string word = bytes_.substr(start, position_ - start);
        char *end = nullptr;
        const double value = std::strtod(word.c_str(), &end);
        if (end != word.c_str() + word.size())
            ascii_error(instance(element, index) + ": " + what + " '" + word + "' is not a number");
        if (is_integer(type) && value != std::floor(value))
            ascii_error(instance(element, index) + ": " + what + " '" + word + "' is not an integer");
        return value;
    }

    void read_element(const Element &element) {
        if (element.name == "vertex")
            read_vertices(element);
        else if (element.name == "face")
            read_faces(element);
        else
            skip_element(element, "element '" + element.name + "' skipped");
    }

    void warn_once(const std::string &message) {
        if (warned_.insert(message).second) warnings_.push_back(name_ + ": " + message);
    }

    // Reads (and drops) property p of an instance; lists are read whole.
    void skip_property(const Property &p, const Element &element, std::uint64_t index) {
        if (!p.is_list) {
            read_value(p.type, element, index, p.name.c_str());
            return;
        }
        const std::size_t at = position_;
        const double count = read_value(p.count_type, element, index, "list length");
        if (count < 0) error_at(instance(element, index) + ": negative list length", at);
        for (std::uint64_t k = 0; k < static_cast<std::uint64_t>(count); ++k)
            read_value(p.type, element, index, p.name.c_str());
    }

    void skip_element(const Element &element, const std::string &warning) {
        if (element.count > 0) warn_once(warning);
        for (std::uint64_t i = 0; i < element.count; ++i)
            for (const Property &p : element.properties) skip_property(p, element, i);
    }

    int find(const Element &element, const char *name) const {
        for (std::size_t i = 0; i < element.properties.size(); ++i)
            if (!element.properties[i].is_list && element.properties[i].name == name) return static_cast<int>(i);
        return -1;
    }

    VertexLayout vertex_layout(const Element &element) {
        VertexLayout layout;
        layout.x = find(element, "x"), layout.y = find(element, "y"), layout.z = find(element, "z");
        if (layout.x < 0 || layout.y < 0 || layout.z < 0)
            fail(PPM_ERROR_PARSE, name_ + ": header line " + std::to_string(element.header_line) +
                                      ": element 'vertex' needs the properties x, y and z");
        const int nx = find(element, "nx"), ny = find(element, "ny"), nz = find(element, "nz");
        if (nx >= 0 && ny >= 0 && nz >= 0) layout.nx = nx, layout.ny = ny, layout.nz = nz;
        static const char *const uv_names[][2] = {{"u", "v"}, {"texture_u", "texture_v"}, {"s", "t"}};
        for (const auto &names : uv_names) {
            const int u = find(element, names[0]), v = find(element, names[1]);
            if (u >= 0 && v >= 0) {
                layout.u = u, layout.v = v;
                break;
            }
        }
        std::string skipped;
        bool colours = false;
        for (std::size_t i = 0; i < element.properties.size(); ++i) {
            const int k = static_cast<int>(i);
            if (k == layout.x || k == layout.y || k == layout.z || k == layout.nx || k == layout.ny || k == layout.nz ||
                k == layout.u || k == layout.v)
                continue;
            const std::string &n = element.properties[i].name;
            if (n == "red" || n == "green" || n == "blue" || n == "alpha" || n == "r" || n == "g" || n == "b" ||
                n == "a")
                colours = true;
            else
                skipped += (skipped.empty() ? "" : ", ") + n;
        }
        if (colours && element.count > 0) warn_once("vertex colours are ignored");
        if (!skipped.empty() && element.count > 0) warn_once("vertex properties ignored: " + skipped);
        return layout;
    }

    void read_vertices(const Element &element) {
        if (vertices_read_) fail(PPM_ERROR_PARSE, name_ + ": more than one 'vertex' element");
        vertices_read_ = true;
        const VertexLayout layout = vertex_layout(element);
        const std::size_t count = static_cast<std::size_t>(element.count);
        mesh_.positions.resize(count);
        if (layout.nx >= 0) mesh_.normals.resize(count);
        if (layout.u >= 0) mesh_.uvs.resize(2 * count);
        std::vector<double> values(element.properties.size());
        for (std::size_t i = 0; i < count; ++i) {
            const std::size_t at = position_;
            for (std::size_t k = 0; k < element.properties.size(); ++k) {
                const Property &p = element.properties[k];
                if (p.is_list) {
                    skip_property(p, element, i);
                    continue;
                }
                values[k] = read_value(p.type, element, i, p.name.c_str());
            }
            const Vec3 position{values[layout.x], values[layout.y], values[layout.z]};
            if (!within_coordinate_limit(position))
                error_at(instance(element, i) + ": position (" + format_number(position.x) + ", " +
                             format_number(position.y) + ", " + format_number(position.z) +
                             ") is not finite or lies beyond +-" + format_number(kCoordinateLimit),
                         at);
            mesh_.positions[i] = position;
            if (layout.nx >= 0) {
                const Vec3 normal{values[layout.nx], values[layout.ny], values[layout.nz]};
                if (!std::isfinite(normal.x) || !std::isfinite(normal.y) || !std::isfinite(normal.z))
                    error_at(instance(element, i) + ": the normal is not finite", at);
                mesh_.normals[i] = normal;
            }
            if (layout.u >= 0) {
                const double u = values[layout.u], v = values[layout.v];
                if (!std::isfinite(u) || !std::isfinite(v))
                    error_at(instance(element, i) + ": the texture coordinates are not finite", at);
                mesh_.uvs[2 * i] = u;
                mesh_.uvs[2 * i + 1] = v;
            }
        }
    }

    void read_faces(const Element &element) {
        if (!vertices_read_)
            fail(PPM_ERROR_PARSE, name_ + ": header line " + std::to_string(element.header_line) +
                                      ": element 'face' comes before element 'vertex'");
        int indices = -1;
        std::string skipped;
        for (std::size_t k = 0; k < element.properties.size(); ++k) {
            const Property &p = element.properties[k];
            if (indices < 0 && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
                if (!is_integer(p.type))
                    fail(PPM_ERROR_PARSE, name_ + ": header line " + std::to_string(element.header_line) +
                                              ": face property '" + p.name + "' must hold integers");
                indices = static_cast<int>(k);
            } else {
                skipped += (skipped.empty() ? "" : ", ") + p.name;
            }
        }
        if (indices < 0)
            fail(PPM_ERROR_PARSE, name_ + ": header line " + std::to_string(element.header_line) +
                                      ": element 'face' has no list property vertex_indices or vertex_index");
        if (!skipped.empty() && element.count > 0) warn_once("face properties ignored: " + skipped);
        const double vertex_count = static_cast<double>(mesh_.positions.size());
        std::vector<std::uint32_t> corners;
        mesh_.indices.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(element.count, 1u << 26)) * 3);
        for (std::uint64_t i = 0; i < element.count; ++i) {
            const std::size_t at = position_;
            for (std::size_t k = 0; k < element.properties.size(); ++k) {
                const Property &p = element.properties[k];
                if (static_cast<int>(k) != indices) {
                    skip_property(p, element, i);
                    continue;
                }
                const double count = read_value(p.count_type, element, i, "corner count");
                if (count < 3)
                    error_at(instance(element, i) + ": a face needs at least 3 corners, found " + format_number(count),
                             at);
                corners.clear();
                for (std::uint64_t c = 0; c < static_cast<std::uint64_t>(count); ++c) {
                    const double index = read_value(p.type, element, i, "vertex index");
                    if (!(index >= 0 && index < vertex_count))
                        error_at(instance(element, i) + ": vertex index " + format_number(index) +
                                     " is out of range (the file has " + std::to_string(mesh_.positions.size()) +
                                     " vertices)",
                                 at);
                    corners.push_back(static_cast<std::uint32_t>(index));
                }
            }
            add_polygon(corners, element, i, at);
            ++faces_read_;
        }
    }

    // Fans the polygon from its first corner, as the OBJ reader does: triangles repeating a
    // vertex have no area and are left out, and a face left with none is an error.
    void add_polygon(const std::vector<std::uint32_t> &c, const Element &element, std::uint64_t index, std::size_t at) {
        std::size_t triangles = 0;
        for (std::size_t k = 2; k < c.size(); ++k) {
            if (c[0] == c[k - 1] || c[0] == c[k] || c[k - 1] == c[k]) continue;
            mesh_.indices.insert(mesh_.indices.end(), {c[0], c[k - 1], c[k]});
            ++triangles;
        }
        if (triangles == 0) error_at(instance(element, index) + ": the face repeats its corners and has no area", at);
    }

    const std::string &bytes_;
    const std::string &name_;
    std::size_t position_ = 0;
    std::size_t line_ = 0;      // header lines read
    std::size_t body_line_ = 0; // the ASCII body's current line
    Format format_ = Format::Ascii;
    std::vector<Element> elements_;
    bool vertices_read_ = false;
    std::uint64_t faces_read_ = 0;
    MeshData mesh_;
    std::vector<std::string> warnings_;
    std::set<std::string> warned_;
};

} // namespace

PlyMesh parse_ply(const std::string &bytes, const std::string &name) { return PlyReader(bytes, name).read(); }

PlyMesh read_ply_file(const std::string &path) { return parse_ply(read_text_file(path), path); }

} // namespace ppm
