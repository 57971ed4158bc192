// SPDX-License-Identifier: Apache-2.0
// Loading speed of the mesh readers: a grid mesh of about 1M triangles written as binary
// PLY, ASCII PLY, Mitsuba serialized and OBJ, each parsed from memory a few times. Prints the
// best CPU time of each and its ratio to the binary PLY; then the binary PLY loaded from a file
// into a scene through the C API (ppm_scene_load_ply) and committed (Embree's BVH), in CPU
// seconds of all threads. Not a test (timings are not checked).
//
//     bench_mesh_readers [triangles]
#include <ppm/ppm.h>

#include "io/obj_reader.h"
#include "io/ply_reader.h"
#include "io/serialized_reader.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

using namespace ppm;

namespace {

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

template <class T> void put(std::string &out, T value) {
    out.append(reinterpret_cast<const char *>(&value), sizeof value);
}

// An n x n grid of quads over a bumpy surface, 2 n^2 triangles.
struct Grid {
    int n;
    std::size_t vertices() const { return static_cast<std::size_t>(n + 1) * (n + 1); }
    std::size_t triangles() const { return 2 * static_cast<std::size_t>(n) * n; }
    void vertex(std::size_t i, float *p) const {
        const double x = static_cast<double>(i % (n + 1)) / n, y = static_cast<double>(i / (n + 1)) / n;
        p[0] = static_cast<float>(x), p[1] = static_cast<float>(y),
        p[2] = static_cast<float>(0.1 * std::sin(9 * x) * std::cos(7 * y));
    }
    template <class Emit> void each_triangle(Emit &&emit) const {
        for (int row = 0; row < n; ++row)
            for (int column = 0; column < n; ++column) {
                const std::uint32_t a = row * (n + 1) + column, b = a + 1, c = a + n + 1, d = c + 1;
                emit(a, b, d);
                emit(a, d, c);
            }
    }
};

std::string binary_ply(const Grid &g) {
    std::string out = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(g.vertices()) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                      std::to_string(g.triangles()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    for (std::size_t i = 0; i < g.vertices(); ++i) {
        float p[3];
        g.vertex(i, p);
        for (float c : p) put(out, c);
    }
    g.each_triangle([&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        put<std::uint8_t>(out, 3);
        for (std::uint32_t k : {a, b, c}) put(out, static_cast<std::int32_t>(k));
    });
    return out;
}

std::string ascii_ply(const Grid &g) {
    std::string out = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(g.vertices()) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                      std::to_string(g.triangles()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    char line[128];
    for (std::size_t i = 0; i < g.vertices(); ++i) {
        float p[3];
        g.vertex(i, p);
        out.append(line, std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", p[0], p[1], p[2]));
    }
    g.each_triangle([&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        out.append(line, std::snprintf(line, sizeof line, "3 %u %u %u\n", a, b, c));
    });
    return out;
}

std::string obj(const Grid &g) {
    std::string out;
    char line[128];
    for (std::size_t i = 0; i < g.vertices(); ++i) {
        float p[3];
        g.vertex(i, p);
        out.append(line, std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p[0], p[1], p[2]));
    }
    g.each_triangle([&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        out.append(line, std::snprintf(line, sizeof line, "f %u %u %u\n", a + 1, b + 1, c + 1));
    });
    return out;
}

std::string serialized(const Grid &g) {
    std::string body;
    put<std::uint32_t>(body, 0x1000);
    body.push_back('\0');
    put<std::uint64_t>(body, g.vertices());
    put<std::uint64_t>(body, g.triangles());
    for (std::size_t i = 0; i < g.vertices(); ++i) {
        float p[3];
        g.vertex(i, p);
        for (float c : p) put(body, c);
    }
    g.each_triangle([&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        for (std::uint32_t k : {a, b, c}) put(body, k);
    });
    std::vector<unsigned char> packed(compressBound(body.size()));
    uLongf size = packed.size();
    if (compress(packed.data(), &size, reinterpret_cast<const Bytef *>(body.data()), body.size()) != Z_OK) std::abort();
    std::string out;
    put<std::uint16_t>(out, 0x041C);
    put<std::uint16_t>(out, 4);
    out.append(reinterpret_cast<const char *>(packed.data()), size);
    return out;
}

// Best of `runs` CPU times of load(); checks that every run read the whole mesh.
template <class Load> double best_seconds(Load &&load, std::size_t triangles, int runs) {
    double best = INFINITY;
    for (int r = 0; r < runs; ++r) {
        const double start = cpu_seconds();
        const MeshData mesh = load();
        best = std::min(best, cpu_seconds() - start);
        if (mesh.indices.size() != 3 * triangles) {
            std::fprintf(stderr, "read %zu triangles, expected %zu\n", mesh.indices.size() / 3, triangles);
            std::exit(2);
        }
    }
    return best;
}

} // namespace

int main(int argc, char **argv) {
    const double wanted = argc > 1 ? std::atof(argv[1]) : 1e6;
    const Grid grid{std::max(1, static_cast<int>(std::lround(std::sqrt(wanted / 2))))};
    const std::size_t triangles = grid.triangles();
    const std::string files[] = {binary_ply(grid), ascii_ply(grid), serialized(grid), obj(grid)};
    std::printf("mesh: %zu triangles, %zu vertices (best CPU time of 3 parses from memory)\n", triangles,
                grid.vertices());
    const double seconds[] = {
        best_seconds([&] { return parse_ply(files[0], "binary.ply").mesh; }, triangles, 3),
        best_seconds([&] { return parse_ply(files[1], "ascii.ply").mesh; }, triangles, 3),
        best_seconds([&] { return parse_serialized(files[2], "mesh.serialized", 0).mesh; }, triangles, 3),
        best_seconds([&] { return parse_obj(files[3], "mesh.obj"); }, triangles, 3),
    };
    const char *names[] = {"PLY binary", "PLY ASCII", "serialized", "OBJ"};
    for (int k = 0; k < 4; ++k)
        std::printf("%-11s %9.1f MiB  %7.3f s  %5.2fx the binary PLY's time\n", names[k], files[k].size() / 1048576.0,
                    seconds[k], seconds[k] / seconds[0]);

    // The whole path a scene file takes: the file read, checked and handed to Embree.
    const std::string path = "/tmp/ppm-bench-mesh-" + std::to_string(static_cast<long>(std::time(nullptr))) + ".ply";
    std::ofstream(path, std::ios::binary) << files[0];
    ppm_context context = nullptr;
    ppm_scene scene = nullptr;
    if (ppm_context_create(&context) != PPM_OK || ppm_scene_create(context, &scene) != PPM_OK) return 2;
    const double start = cpu_seconds();
    const ppm_status loaded = ppm_scene_load_ply(scene, path.c_str(), nullptr);
    const double load = cpu_seconds() - start;
    const ppm_status committed = ppm_scene_commit(scene);
    const double commit = cpu_seconds() - start - load;
    std::remove(path.c_str());
    if (loaded != PPM_OK || committed != PPM_OK) {
        std::fprintf(stderr, "loading the PLY file failed: %s\n", ppm_last_error_message());
        return 2;
    }
    std::printf("ppm_scene_load_ply from a file: %.3f s CPU; ppm_scene_commit (BVH): %.3f s CPU\n", load, commit);
    ppm_scene_release(scene);
    ppm_context_release(context);
    return 0;
}
