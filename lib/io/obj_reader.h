// Reader for Wavefront OBJ meshes through tinyobjloader. All shapes become one triangle mesh;
// polygons are triangulated; normals and texture coordinates are kept when every face
// corner has them.
#pragma once

#include "geometry/mesh_geometry.h"

#include <string>

namespace ppm {

// Throws ppm::Error: IO if the file cannot be read, PARSE with "path:line: what" otherwise.
MeshData read_obj_file(const std::string &path);
MeshData parse_obj(const std::string &text, const std::string &name);

} // namespace ppm
