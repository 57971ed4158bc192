// SPDX-License-Identifier: Apache-2.0
// ppm-tess: tessellates the Bezier patches of a .bpt or scene file into an OBJ (or PLY) triangle mesh
// through libppm's public API, and reports how far the mesh lies from the surface.
#include <ppm/ppm.h>

#include "common/command_line.h"
#include "common/handle.h"
#include "common/status.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

const char *const description =
    "Tessellates bicubic Bezier patches into triangles whose distance from the surface is\n"
    "measured and held within a tolerance, or into a uniform grid. INPUT is a .bpt file or a\n"
    "scene file (.json or Mitsuba 3 .xml, docs/scene-format.md): then every Bezier shape,\n"
    "placed by its to_world, goes into one mesh.";
const char *const footer = "The triangle count and the measured deviation (absolute and relative) go to stderr.\n"
                           "Exit status: 0 ok, 1 usage error, 2 runtime error.";

struct Options {
    std::string input, output;
    double tolerance = 1e-3;
    bool relative = true; // the default tolerance is relative; an explicit one is absolute
    uint32_t grid = 0;
    bool ply = false;
};

bool ends_with(const std::string &text, const char *suffix) {
    const size_t n = std::strlen(suffix);
    return text.size() >= n && text.compare(text.size() - n, n, suffix) == 0;
}

void add_options(CLI::App &app, Options &o, CLI::Option *&tolerance, CLI::Option *&relative, CLI::Option *&grid) {
    app.add_option("INPUT", o.input, "a .bpt file or a scene file")->required()->type_name("");
    app.add_option("-o,--output", o.output,
                   "OBJ (v, vt, vn, f v/vt/vn; seam vertices welded;\n"
                   "vt = patch (u, 1 - v), the OBJ convention),\n"
                   "or PLY when PATH ends in .ply")
        ->required()
        ->type_name("PATH");
    tolerance = app.add_option("--tolerance", o.tolerance,
                               "largest distance from the surface, absolute\n"
                               "(default: 1e-3 of the bounding-box diagonal of\n"
                               "the control points)")
                    ->check(CLI::PositiveNumber)
                    ->type_name("E");
    relative = app.add_flag("--relative", "E is relative to that diagonal");
    grid = app.add_option("--grid", o.grid, "uniform N x N quads per patch instead (1..4096)")
               ->check(CLI::Range(1, 4096))
               ->type_name("N");
    app.add_flag("--ply", o.ply,
                 "write ASCII PLY (x y z nx ny nz u v per vertex;\n"
                 "seam vertices repeated once per patch)");
    grid->excludes(tolerance)->excludes(relative);
}

// What CLI11 cannot check alone: the output's format against its name.
void check_output(Options &o, bool tolerance_given, bool relative_given) {
    if (tolerance_given) o.relative = relative_given;
    const bool ply_name = ends_with(o.output, ".ply") || ends_with(o.output, ".PLY");
    const bool obj_name = ends_with(o.output, ".obj") || ends_with(o.output, ".OBJ");
    if (!ply_name && !obj_name)
        throw ppm_tools::UsageError("output '" + o.output + "' must end in .obj or .ply (the formats ppm-tess writes)");
    if (o.ply && obj_name)
        throw ppm_tools::UsageError("--ply asks for PLY, but the output '" + o.output + "' ends in .obj");
    o.ply = ply_name;
}

bool is_scene_file(const std::string &path) {
    return ends_with(path, ".json") || ends_with(path, ".JSON") || ends_with(path, ".xml") || ends_with(path, ".XML");
}

// ppm-tess's messages name the status: "reading the scene: parse error: FILE:LINE: ...".
using ppm_tools::check_with_status;

// The patches of a .bpt file, or the world-space patches of every Bezier shape of a scene file
// (.json or .xml), read by libppm (whose errors name the file, line and key).
std::vector<double> read_patches(const std::string &path) {
    ppm_tools::Context context;
    ppm_tools::SceneFile file;
    ppm_tools::Scene scene;
    check_with_status(ppm_context_create(context.out()), "creating a context");
    if (is_scene_file(path)) {
        check_with_status(ppm_scene_file_load(context, path.c_str(), file.out()), "reading the scene");
        check_with_status(ppm_scene_file_get_scene(file, scene.out()), path);
    } else {
        check_with_status(ppm_scene_create(context, scene.out()), "creating a scene");
        check_with_status(ppm_scene_load_bpt(scene, path.c_str(), nullptr), "reading the patches");
        check_with_status(ppm_scene_commit(scene), path);
    }
    size_t geometries = 0;
    check_with_status(ppm_scene_get_geometry_count(scene, &geometries), path);
    std::vector<double> points;
    for (uint32_t g = 0; g < geometries; ++g) {
        size_t count = 0;
        check_with_status(ppm_scene_get_primitive_count(scene, g, &count), path);
        std::vector<double> patch_points(count * 48);
        // Other shapes (spheres, quads, meshes) are not patch sets: skipped.
        if (ppm_scene_get_bezier_patches(scene, g, patch_points.data(), patch_points.size()) == PPM_OK)
            points.insert(points.end(), patch_points.begin(), patch_points.end());
    }
    if (points.empty()) throw std::runtime_error(path + ": the scene has no Bezier patches");
    return points;
}

double diagonal(const std::vector<double> &points) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t k = 0; k < points.size(); ++k) {
        lo[k % 3] = std::fmin(lo[k % 3], points[k]);
        hi[k % 3] = std::fmax(hi[k % 3], points[k]);
    }
    return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                     (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

// Shortest of %.15g / %.17g that reads back as the same double: exact, and short for the
// many coordinates that are short decimals.
const char *exact(double value, char buffer[32]) {
    std::snprintf(buffer, 32, "%.15g", value);
    if (std::strtod(buffer, nullptr) != value) std::snprintf(buffer, 32, "%.17g", value);
    return buffer;
}

struct MeshView {
    const double *positions = nullptr, *normals = nullptr, *uvs = nullptr;
    size_t vertex_count = 0;
    const uint32_t *indices = nullptr;
    size_t triangle_count = 0;
    const uint32_t *welded = nullptr;
    size_t welded_count = 0;
};

void write_obj(std::FILE *out, const MeshView &m, const std::string &input) {
    std::fprintf(out, "# ppm-tess %s from %s: %zu triangles\n", ppm_version_string(), input.c_str(), m.triangle_count);
    // One v per distinct position, vt and vn per vertex: the faces share positions across
    // seams (the mesh is closed there) while keeping each patch's (u, v) and normal.
    std::vector<size_t> first(m.welded_count, SIZE_MAX);
    for (size_t v = 0; v < m.vertex_count; ++v)
        if (first[m.welded[v]] == SIZE_MAX) first[m.welded[v]] = v;
    char a[32], b[32], c[32];
    for (size_t w = 0; w < m.welded_count; ++w) {
        const double *p = m.positions + 3 * first[w];
        std::fprintf(out, "v %s %s %s\n", exact(p[0], a), exact(p[1], b), exact(p[2], c));
    }
    for (size_t v = 0; v < m.vertex_count; ++v)
        // OBJ readers (Mitsuba's, libppm's) take vt's v as 1 - v: written so, they get the patch's v.
        std::fprintf(out, "vt %s %s\n", exact(m.uvs[2 * v], a), exact(1.0 - m.uvs[2 * v + 1], b));
    for (size_t v = 0; v < m.vertex_count; ++v) {
        const double *n = m.normals + 3 * v;
        std::fprintf(out, "vn %s %s %s\n", exact(n[0], a), exact(n[1], b), exact(n[2], c));
    }
    for (size_t t = 0; t < m.triangle_count; ++t) {
        const uint32_t *c = m.indices + 3 * t;
        std::fprintf(out, "f %u/%u/%u %u/%u/%u %u/%u/%u\n", m.welded[c[0]] + 1, c[0] + 1, c[0] + 1, m.welded[c[1]] + 1,
                     c[1] + 1, c[1] + 1, m.welded[c[2]] + 1, c[2] + 1, c[2] + 1);
    }
}

void write_ply(std::FILE *out, const MeshView &m, const std::string &input) {
    std::fprintf(out,
                 "ply\nformat ascii 1.0\ncomment ppm-tess %s from %s\nelement vertex %zu\n"
                 "property double x\nproperty double y\nproperty double z\n"
                 "property double nx\nproperty double ny\nproperty double nz\n"
                 "property double u\nproperty double v\n"
                 "element face %zu\nproperty list uchar uint vertex_indices\nend_header\n",
                 ppm_version_string(), input.c_str(), m.vertex_count, m.triangle_count);
    char text[8][32];
    for (size_t v = 0; v < m.vertex_count; ++v) {
        const double *p = m.positions + 3 * v, *n = m.normals + 3 * v, *t = m.uvs + 2 * v;
        std::fprintf(out, "%s %s %s %s %s %s %s %s\n", exact(p[0], text[0]), exact(p[1], text[1]), exact(p[2], text[2]),
                     exact(n[0], text[3]), exact(n[1], text[4]), exact(n[2], text[5]), exact(t[0], text[6]),
                     exact(t[1], text[7]));
    }
    for (size_t t = 0; t < m.triangle_count; ++t)
        std::fprintf(out, "3 %u %u %u\n", m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]);
}

// Writes through a temporary file in the same folder, renamed over `path` only when complete,
// so that a failure never leaves a truncated file under the final name.
template <class Write> void write_atomically(const std::string &path, Write &&write) {
    std::string temp = path + ".XXXXXX";
    const int fd = mkstemp(&temp[0]);
    if (fd < 0) throw std::runtime_error(path + ": cannot create a temporary file beside it: " + std::strerror(errno));
    std::FILE *out = fdopen(fd, "w");
    if (!out) {
        close(fd);
        std::remove(temp.c_str());
        throw std::runtime_error(path + ": " + std::strerror(errno));
    }
    write(out);
    const bool failed = std::ferror(out) != 0;
    const int saved_errno = errno;
    if (std::fclose(out) != 0 || failed) {
        std::remove(temp.c_str());
        throw std::runtime_error(path + ": write failed: " + std::strerror(failed ? saved_errno : errno));
    }
    // mkstemp creates the file 0600; give it the permissions a plain fopen would have.
    const mode_t mask = umask(0);
    umask(mask);
    chmod(temp.c_str(), 0666 & ~mask);
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
        const int error = errno;
        std::remove(temp.c_str());
        throw std::runtime_error(path + ": cannot rename the temporary file: " + std::strerror(error));
    }
}

int run(const Options &o) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<double> points = read_patches(o.input);
    const size_t patch_count = points.size() / 48;
    const double diag = diagonal(points);
    const double tolerance = o.relative ? o.tolerance * diag : o.tolerance;

    ppm_tools::Mesh mesh;
    check_with_status(ppm_tessellate_patches(points.data(), patch_count, tolerance, o.grid, mesh.out()), o.input);
    MeshView m;
    double deviation = 0;
    check_with_status(ppm_mesh_get_vertices(mesh, &m.positions, &m.normals, &m.uvs, &m.vertex_count), o.input);
    check_with_status(ppm_mesh_get_triangles(mesh, &m.indices, &m.triangle_count), o.input);
    check_with_status(ppm_mesh_get_welded_vertices(mesh, &m.welded, &m.welded_count), o.input);
    check_with_status(ppm_mesh_get_double(mesh, "max_deviation", &deviation), o.input);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (o.grid)
        std::fprintf(stderr, "ppm-tess: %s: %zu patches, uniform grid %u: ", o.input.c_str(), patch_count, o.grid);
    else
        std::fprintf(stderr, "ppm-tess: %s: %zu patches, tolerance %.6g (%.6g of the diagonal %.6g): ", o.input.c_str(),
                     patch_count, tolerance, tolerance / diag, diag);
    std::fprintf(stderr,
                 "%zu triangles, %zu vertices (%zu distinct positions); measured max deviation %.6g "
                 "(%.6g of the diagonal); %.2f s\n",
                 m.triangle_count, m.vertex_count, m.welded_count, deviation, deviation / diag, seconds);
    write_atomically(o.output, [&](std::FILE *out) {
        if (o.ply)
            write_ply(out, m, o.input);
        else
            write_obj(out, m, o.input);
    });
    std::fprintf(stderr, "ppm-tess: wrote %s\n", o.output.c_str());
    return 0;
}

} // namespace

int main(int argc, char **argv) {
    CLI::App app(description, "ppm-tess");
    ppm_tools::configure(app, footer);
    Options options;
    CLI::Option *tolerance = nullptr, *relative = nullptr, *grid = nullptr;
    add_options(app, options, tolerance, relative, grid);
    const int parsed = ppm_tools::parse(app, argc, argv);
    if (parsed >= 0) return parsed;
    try {
        check_output(options, tolerance->count() > 0, relative->count() > 0);
    } catch (const ppm_tools::UsageError &e) {
        return ppm_tools::report_usage_error(app, e.what());
    }
    try {
        return run(options);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "ppm-tess: %s\n", e.what());
        return ppm_tools::kExitRuntime;
    }
}
