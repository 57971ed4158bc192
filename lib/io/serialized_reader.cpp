// SPDX-License-Identifier: Apache-2.0
// Layout (little endian), per mesh:
//   u16 0x041C, u16 version (3 or 4), then a zlib stream holding
//   u32 flags (0x0001 normals, 0x0002 texture coordinates, 0x0008 colours, 0x0010 face
//   normals, 0x1000 single precision, 0x2000 double precision; as in Mitsuba's loader, the
//   data are doubles exactly when 0x2000 is set, and other bits are ignored), a NUL-terminated name
//   (version 4 only), u64 vertex count, u64 triangle count, positions (3 per vertex), normals,
//   texture coordinates, colours (each when flagged), then 3 indices per triangle (u32, or u64
//   when there are more than 2^32 vertices).
// Meshes follow each other; the file ends with the offset of each mesh (u64 in version 4, u32
// in version 3) and a u32 mesh count.
#include "io/serialized_reader.h"

#include "core/error.h"
#include "io/text_file.h"
#include "math/limits.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

namespace ppm {

namespace {

constexpr std::uint16_t kMagic = 0x041C;
constexpr std::uint32_t kHasNormals = 0x0001, kHasTexcoords = 0x0002, kHasColours = 0x0008, kFaceNormals = 0x0010,
                        kDoublePrecision = 0x2000;

template <class T> T little_endian(const unsigned char *bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof value);
    static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the reader assumes a little-endian host");
    return value;
}

// Inflates a zlib stream on demand, so that a mesh is read without inflating the ones after it.
class Inflater {
public:
    Inflater(const std::string &bytes, std::size_t offset, std::string where)
        : bytes_(bytes), offset_(offset), where_(std::move(where)) {
        if (inflateInit(&stream_) != Z_OK) fail(PPM_ERROR_OUT_OF_MEMORY, where_ + ": cannot start zlib");
    }
    ~Inflater() { inflateEnd(&stream_); }
    Inflater(const Inflater &) = delete;
    Inflater &operator=(const Inflater &) = delete;

    // Exactly `size` bytes into out, or a PARSE error naming `what`.
    void read(void *out, std::size_t size, const std::string &what) {
        auto *target = static_cast<Bytef *>(out);
        while (size > 0) {
            // zlib counts in 32 bits: input and output go to it in chunks of at most 1 GiB.
            if (stream_.avail_in == 0 && consumed_ < bytes_.size() - offset_) {
                const std::size_t chunk = std::min<std::size_t>(bytes_.size() - offset_ - consumed_, 1u << 30);
                stream_.next_in = reinterpret_cast<Bytef *>(const_cast<char *>(bytes_.data() + offset_ + consumed_));
                stream_.avail_in = static_cast<uInt>(chunk);
                consumed_ += chunk;
            }
            const uInt chunk = static_cast<uInt>(std::min<std::size_t>(size, 1u << 30));
            stream_.next_out = target;
            stream_.avail_out = chunk;
            const int status = inflate(&stream_, Z_SYNC_FLUSH);
            const std::size_t produced = chunk - stream_.avail_out;
            target += produced;
            size -= produced;
            if (size == 0) break;
            // Z_BUF_ERROR: no progress is possible, all the input is used.
            if (status == Z_STREAM_END || status == Z_BUF_ERROR)
                fail(PPM_ERROR_PARSE, where_ + ": the compressed data ends inside the " + what);
            if (status != Z_OK)
                fail(PPM_ERROR_PARSE, where_ + ": corrupt compressed data in the " + what +
                                          " (zlib: " + (stream_.msg ? stream_.msg : "error " + std::to_string(status)) +
                                          ", input byte " + std::to_string(offset_ + stream_.total_in) + ")");
        }
    }

    template <class T> T read(const std::string &what) {
        T value;
        read(&value, sizeof value, what);
        return value;
    }

private:
    const std::string &bytes_;
    std::size_t offset_;
    std::size_t consumed_ = 0; // input bytes handed to zlib
    std::string where_;
    z_stream stream_{};
};

class SerializedReader {
public:
    SerializedReader(const std::string &bytes, const std::string &name, std::uint32_t shape_index)
        : bytes_(bytes), name_(name), shape_index_(shape_index) {}

    SerializedMesh read() {
        if (bytes_.size() < 4 || little_endian<std::uint16_t>(data(0)) != kMagic)
            error("not a Mitsuba serialized mesh file (no 0x041C header)");
        version_ = little_endian<std::uint16_t>(data(2));
        if (version_ != 3 && version_ != 4)
            error("format version " + std::to_string(version_) + " is not supported (3 and 4 are read)");
        const std::size_t offset = mesh_offset();
        where_ = name_ + ": mesh " + std::to_string(shape_index_) + " (at byte " + std::to_string(offset) + ")";
        if (offset + 4 > bytes_.size() || little_endian<std::uint16_t>(data(offset)) != kMagic ||
            little_endian<std::uint16_t>(data(offset + 2)) != version_)
            fail(PPM_ERROR_PARSE, where_ + ": no mesh header at this offset");
        return read_mesh(offset + 4);
    }

private:
    const unsigned char *data(std::size_t offset) const {
        return reinterpret_cast<const unsigned char *>(bytes_.data()) + offset;
    }
    [[noreturn]] void error(const std::string &what) const { fail(PPM_ERROR_PARSE, name_ + ": " + what); }

    // Mesh 0 starts the file; the others are found through the index at its end.
    std::size_t mesh_offset() const {
        if (shape_index_ == 0) return 0;
        if (bytes_.size() < 8) error("the file is too short to hold an index of meshes");
        const std::uint32_t count = little_endian<std::uint32_t>(data(bytes_.size() - 4));
        const std::size_t entry = version_ == 4 ? 8 : 4;
        if (count > (bytes_.size() - 4) / entry)
            error("the index at the end of the file claims " + std::to_string(count) +
                  " meshes, more than the file can hold (is it a single-mesh file?)");
        if (shape_index_ >= count)
            error("shape_index " + std::to_string(shape_index_) + " is out of range: the file holds " +
                  std::to_string(count) + (count == 1 ? " mesh" : " meshes") + " (0 to " + std::to_string(count - 1) +
                  ")");
        const std::size_t at = bytes_.size() - 4 - entry * (count - shape_index_);
        const std::uint64_t offset =
            version_ == 4 ? little_endian<std::uint64_t>(data(at)) : little_endian<std::uint32_t>(data(at));
        if (offset >= bytes_.size())
            error("the index gives mesh " + std::to_string(shape_index_) + " the offset " + std::to_string(offset) +
                  ", beyond the file's " + std::to_string(bytes_.size()) + " bytes");
        return static_cast<std::size_t>(offset);
    }

    SerializedMesh read_mesh(std::size_t offset) {
        Inflater in(bytes_, offset, where_);
        SerializedMesh result;
        const std::uint32_t flags = in.read<std::uint32_t>("flags");
        // Files written by other tools set bits that Mitsuba's loader does not read (0x0100 has
        // been seen) or leave the precision unflagged: read as Mitsuba reads them.
        const bool doubles = (flags & kDoublePrecision) != 0;
        if (version_ == 4) {
            for (char c; (c = in.read<char>("name")) != '\0';) {
                if (result.name.size() > 4096) fail(PPM_ERROR_PARSE, where_ + ": the mesh name is not terminated");
                result.name += c;
            }
        }
        const std::uint64_t vertices = in.read<std::uint64_t>("vertex count");
        const std::uint64_t triangles = in.read<std::uint64_t>("triangle count");
        check_counts(vertices, triangles, flags, doubles, offset);

        MeshData &mesh = result.mesh;
        mesh.positions = read_vectors(in, vertices, doubles, "positions");
        for (std::size_t i = 0; i < mesh.positions.size(); ++i)
            if (!within_coordinate_limit(mesh.positions[i]))
                fail(PPM_ERROR_PARSE, where_ + ": vertex " + std::to_string(i) + " is not finite or lies beyond +-" +
                                          format_number(kCoordinateLimit));
        if (flags & kHasNormals) {
            mesh.normals = read_vectors(in, vertices, doubles, "normals");
            for (std::size_t i = 0; i < mesh.normals.size(); ++i)
                if (!std::isfinite(mesh.normals[i].x) || !std::isfinite(mesh.normals[i].y) ||
                    !std::isfinite(mesh.normals[i].z))
                    fail(PPM_ERROR_PARSE, where_ + ": the normal of vertex " + std::to_string(i) + " is not finite");
        }
        if (flags & kHasTexcoords) {
            mesh.uvs = read_reals(in, 2 * vertices, doubles, "texture coordinates");
            for (double value : mesh.uvs)
                if (!std::isfinite(value)) fail(PPM_ERROR_PARSE, where_ + ": a texture coordinate is not finite");
        }
        if (flags & kHasColours) {
            read_reals(in, 3 * vertices, doubles, "vertex colours");
            result.had_colours = true;
        }
        result.face_normals = (flags & kFaceNormals) != 0;
        if (result.face_normals) mesh.normals.clear();
        read_indices(in, vertices, triangles, mesh.indices);
        return result;
    }

    // Counts the compressed rest of the file cannot hold are refused before any allocation:
    // zlib compresses at most about 1032:1, so the inflated data is bounded by the file size.
    void check_counts(std::uint64_t vertices, std::uint64_t triangles, std::uint32_t flags, bool doubles,
                      std::size_t offset) const {
        const std::uint64_t real = doubles ? 8 : 4;
        const std::uint64_t per_vertex = real * (3 + (flags & kHasNormals ? 3 : 0) + (flags & kHasTexcoords ? 2 : 0) +
                                                 (flags & kHasColours ? 3 : 0));
        const std::uint64_t index = vertices > 0xFFFFFFFFull ? 8 : 4;
        const long double inflated =
            static_cast<long double>(vertices) * per_vertex + static_cast<long double>(triangles) * 3 * index;
        const long double most = (static_cast<long double>(bytes_.size() - offset) + 64) * 1100;
        if (inflated > most)
            fail(PPM_ERROR_PARSE, where_ + ": " + std::to_string(vertices) + " vertices and " +
                                      std::to_string(triangles) + " triangles cannot fit in the file's " +
                                      std::to_string(bytes_.size() - offset) + " bytes");
        if (vertices == 0 || triangles == 0) fail(PPM_ERROR_PARSE, where_ + ": the mesh has no triangles");
    }

    std::vector<double> read_reals(Inflater &in, std::uint64_t count, bool doubles, const char *what) {
        std::vector<double> values(static_cast<std::size_t>(count));
        if (doubles) {
            in.read(values.data(), values.size() * sizeof(double), what);
        } else {
            std::vector<float> floats(values.size());
            in.read(floats.data(), floats.size() * sizeof(float), what);
            for (std::size_t i = 0; i < floats.size(); ++i) values[i] = floats[i];
        }
        return values;
    }

    std::vector<Vec3> read_vectors(Inflater &in, std::uint64_t count, bool doubles, const char *what) {
        const std::vector<double> values = read_reals(in, 3 * count, doubles, what);
        std::vector<Vec3> vectors(static_cast<std::size_t>(count));
        for (std::size_t i = 0; i < vectors.size(); ++i)
            vectors[i] = {values[3 * i], values[3 * i + 1], values[3 * i + 2]};
        return vectors;
    }

    // Triangles repeating a vertex have no area and are left out (as in the OBJ and PLY
    // readers); indices beyond the vertices are an error naming the triangle.
    void read_indices(Inflater &in, std::uint64_t vertices, std::uint64_t triangles,
                      std::vector<std::uint32_t> &indices) {
        if (vertices > 0xFFFFFFFFull) fail(PPM_ERROR_PARSE, where_ + ": more than 2^32 vertices are not supported");
        std::vector<std::uint32_t> raw(static_cast<std::size_t>(3 * triangles));
        in.read(raw.data(), raw.size() * sizeof(std::uint32_t), "triangle indices");
        indices.reserve(raw.size());
        for (std::size_t t = 0; t < triangles; ++t) {
            const std::uint32_t *c = &raw[3 * t];
            for (int k = 0; k < 3; ++k)
                if (c[k] >= vertices)
                    fail(PPM_ERROR_PARSE, where_ + ": triangle " + std::to_string(t) + " names vertex " +
                                              std::to_string(c[k]) + ", but the mesh has " + std::to_string(vertices) +
                                              " vertices");
            if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
            indices.insert(indices.end(), c, c + 3);
        }
        if (indices.empty()) fail(PPM_ERROR_PARSE, where_ + ": every triangle repeats a vertex: no area left");
    }

    const std::string &bytes_;
    const std::string &name_;
    std::uint32_t shape_index_;
    std::uint16_t version_ = 0;
    std::string where_;
};

} // namespace

SerializedMesh parse_serialized(const std::string &bytes, const std::string &name, std::uint32_t shape_index) {
    return SerializedReader(bytes, name, shape_index).read();
}

SerializedMesh read_serialized_file(const std::string &path, std::uint32_t shape_index) {
    return parse_serialized(read_text_file(path), path, shape_index);
}

} // namespace ppm
