// SPDX-License-Identifier: Apache-2.0
// Reader for PLY meshes (the Stanford polygon format, version 1.0, ASCII and binary in either
// byte order), as Blender, Mitsuba's tools and 3D scanners write them.
//
// Read: vertex x, y, z; normals nx, ny, nz (when all three are there); texture coordinates
// u, v (or texture_u, texture_v, or s, t: Mitsuba 3's order of preference), kept as they are
// (PLY has no vertical convention of its own; Mitsuba 3 does not flip them either); faces from
// the list property vertex_indices (or vertex_index), polygons fanned from their first corner.
// Everything else (vertex colours, other properties, other elements) is skipped, and each kind
// skipped is reported once in `warnings`, so that nothing is dropped without a word.
//
// Every count in the header is checked against the bytes the file has left before anything is
// allocated, every coordinate against the scene's limits and every index against the vertex
// count; errors say where: "path: header line N: ...", "path:LINE: ..." in an ASCII body,
// "path: byte B: ..." in a binary one.
#pragma once

#include "geometry/mesh_data.h"

#include <string>
#include <vector>

namespace ppm {

struct PlyMesh {
    MeshData mesh;
    std::vector<std::string> warnings; // one line per kind of data skipped
};

// Throws ppm::Error: IO if the file cannot be read, PARSE for anything wrong inside it.
PlyMesh read_ply_file(const std::string &path);
PlyMesh parse_ply(const std::string &bytes, const std::string &name);

} // namespace ppm
