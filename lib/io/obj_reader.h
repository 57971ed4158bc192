// SPDX-License-Identifier: Apache-2.0
// Reader for Wavefront OBJ meshes (v, vn, vt, f; other statements are skipped). All objects
// become one triangle mesh; polygons are fanned from their first corner; normals and texture
// coordinates are kept when every face corner has them.
#pragma once

#include "geometry/mesh_data.h"

#include <string>

namespace ppm {

// Throws ppm::Error: IO if the file cannot be read, PARSE with "path:line: what" otherwise.
MeshData read_obj_file(const std::string &path);
MeshData parse_obj(const std::string &text, const std::string &name);

} // namespace ppm
