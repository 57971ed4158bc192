// SPDX-License-Identifier: Apache-2.0
// Reader for Mitsuba's `serialized` meshes: one or more zlib-compressed triangle meshes in a
// file, with an index of their offsets at its end (format versions 3 and 4, as Mitsuba 0.5 to
// 3 write them; the layout is described in serialized_reader.cpp).
#pragma once

#include "geometry/mesh_data.h"

#include <cstdint>
#include <string>

namespace ppm {

struct SerializedMesh {
    MeshData mesh;
    std::string name;          // the mesh's name in the file (version 4), else empty
    bool face_normals = false; // the file asks for flat shading (its normals are then dropped)
    bool had_colours = false;  // vertex colours were in the file and are ignored
};

// Mesh number `shape_index` (0 is the first) of the file. Throws ppm::Error: IO if the file
// cannot be read, PARSE with "path: ..." naming the mesh and byte offset otherwise (not a
// serialized file, an index beyond the meshes the file holds, corrupt or truncated data).
SerializedMesh read_serialized_file(const std::string &path, std::uint32_t shape_index);
SerializedMesh parse_serialized(const std::string &bytes, const std::string &name, std::uint32_t shape_index);

} // namespace ppm
