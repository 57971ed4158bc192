// SPDX-License-Identifier: Apache-2.0
// The PLY and Mitsuba serialized mesh readers: the same quad written as ASCII, binary little
// and big endian PLY and as serialized (versions 3 and 4, float and double) reads back to the
// same mesh; every kind of damage is a located error; skipped data is reported.
#include "core/error.h"
#include "io/ply_reader.h"
#include "io/serialized_reader.h"

#include "test_support.h"

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

using namespace ppm;

namespace {

// A unit square in z = 0 with normals +z and uvs at its corners, as one quad.
const double kPositions[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const double kUvs[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};

void assert_unit_square(const MeshData &mesh, bool with_normals, bool with_uvs) {
    assert_int_equal(mesh.positions.size(), 4);
    for (int i = 0; i < 4; ++i) {
        assert_true(mesh.positions[i].x == kPositions[i][0]);
        assert_true(mesh.positions[i].y == kPositions[i][1]);
        assert_true(mesh.positions[i].z == kPositions[i][2]);
    }
    // Fanned from the first corner: (0 1 2) and (0 2 3).
    const std::vector<std::uint32_t> expected = {0, 1, 2, 0, 2, 3};
    assert_true(mesh.indices == expected);
    assert_int_equal(mesh.normals.size(), with_normals ? 4 : 0);
    for (const Vec3 &n : mesh.normals) assert_true(n.x == 0 && n.y == 0 && n.z == 1);
    assert_int_equal(mesh.uvs.size(), with_uvs ? 8 : 0);
    for (std::size_t i = 0; i < mesh.uvs.size(); ++i) assert_true(mesh.uvs[i] == kUvs[i / 2][i % 2]);
}

// Runs `load` and checks that it throws a PARSE error whose message contains every fragment.
template <class Load> void assert_parse_error(Load &&load, std::initializer_list<const char *> fragments) {
    try {
        load();
    } catch (const Error &e) {
        assert_int_equal(e.status(), PPM_ERROR_PARSE);
        for (const char *fragment : fragments)
            if (std::string(e.what()).find(fragment) == std::string::npos)
                fail_msg("message '%s' lacks '%s'", e.what(), fragment);
        return;
    }
    fail_msg("no error thrown");
}

const char *kAsciiHeader = "ply\n"
                           "format ascii 1.0\n"
                           "comment a unit square\n"
                           "element vertex 4\n"
                           "property float x\nproperty float y\nproperty float z\n"
                           "property float nx\nproperty float ny\nproperty float nz\n"
                           "property float u\nproperty float v\n"
                           "element face 1\n"
                           "property list uchar int vertex_indices\n"
                           "end_header\n";

std::string ascii_square() {
    std::string text = kAsciiHeader;
    for (int i = 0; i < 4; ++i)
        text += std::to_string(kPositions[i][0]) + " " + std::to_string(kPositions[i][1]) + " " +
                std::to_string(kPositions[i][2]) + " 0 0 1 " + std::to_string(kUvs[i][0]) + " " +
                std::to_string(kUvs[i][1]) + "\n";
    return text + "4 0 1 2 3\n";
}

template <class T> void put(std::string &out, T value, bool big_endian) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof value);
    if (big_endian)
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    out.append(reinterpret_cast<const char *>(raw), sizeof raw);
}

// The square as binary PLY, with a vertex colour and an extra element to be skipped.
std::string binary_square(bool big_endian) {
    std::string bytes = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                        " 1.0\n"
                        "element vertex 4\n"
                        "property double x\nproperty double y\nproperty double z\n"
                        "property uchar red\n"
                        "property float s\nproperty float t\n"
                        "element face 1\n"
                        "property list uint8 uint32 vertex_index\n"
                        "property short flags\n"
                        "element edge 1\n"
                        "property int vertex1\nproperty int vertex2\n"
                        "end_header\n";
    for (int i = 0; i < 4; ++i) {
        for (int a = 0; a < 3; ++a) put<double>(bytes, kPositions[i][a], big_endian);
        put<std::uint8_t>(bytes, 200, big_endian);
        put<float>(bytes, static_cast<float>(kUvs[i][0]), big_endian);
        put<float>(bytes, static_cast<float>(kUvs[i][1]), big_endian);
    }
    put<std::uint8_t>(bytes, 4, big_endian);
    for (std::uint32_t k = 0; k < 4; ++k) put<std::uint32_t>(bytes, k, big_endian);
    put<std::int16_t>(bytes, 7, big_endian);
    put<std::int32_t>(bytes, 0, big_endian);
    put<std::int32_t>(bytes, 1, big_endian);
    return bytes;
}

void ascii_ply_reads_positions_normals_uvs_and_fans_polygons(void **) {
    const PlyMesh ply = parse_ply(ascii_square(), "square.ply");
    assert_unit_square(ply.mesh, true, true);
    assert_true(ply.warnings.empty());
}

void binary_ply_reads_the_same_in_both_byte_orders_and_reports_what_it_skips(void **) {
    for (bool big_endian : {false, true}) {
        const PlyMesh ply = parse_ply(binary_square(big_endian), "square.ply");
        assert_unit_square(ply.mesh, false, true);
        std::string all;
        for (const std::string &w : ply.warnings) all += w + "\n";
        assert_non_null(std::strstr(all.c_str(), "square.ply: vertex colours are ignored"));
        assert_non_null(std::strstr(all.c_str(), "face properties ignored: flags"));
        assert_non_null(std::strstr(all.c_str(), "element 'edge' skipped"));
        assert_int_equal(ply.warnings.size(), 3);
    }
}

void ply_damage_is_a_located_error(void **) {
    const std::string good = ascii_square();
    auto replaced = [&](const std::string &from, const std::string &to) {
        std::string text = good;
        const std::size_t at = text.find(from);
        assert_true(at != std::string::npos);
        return text.replace(at, from.size(), to);
    };
    assert_parse_error([&] { parse_ply("solid cube\n", "a.ply"); }, {"a.ply", "not a PLY file"});
    assert_parse_error([&] { parse_ply(replaced("4 0 1 2 3", "4 0 1 2 9"), "a.ply"); },
                       {"a.ply:20:", "face 0", "vertex index 9 is out of range", "4 vertices"});
    assert_parse_error([&] { parse_ply(replaced("4 0 1 2 3", "2 0 1"), "a.ply"); },
                       {"a.ply:20:", "at least 3 corners"});
    assert_parse_error([&] { parse_ply(replaced("4 0 1 2 3", "3 0 1 1"), "a.ply"); }, {"face 0", "no area"});
    assert_parse_error([&] { parse_ply(replaced("element face 1", "element face 99999"), "a.ply"); },
                       {"a.ply: header line 13", "claims 99999 entries"});
    assert_parse_error([&] { parse_ply(replaced("property float x", "property float q"), "a.ply"); },
                       {"header line 4", "needs the properties x, y and z"});
    assert_parse_error([&] { parse_ply(replaced("format ascii 1.0", "format ascii 2.0"), "a.ply"); },
                       {"header line 2", "version '2.0'"});
    assert_parse_error([&] { parse_ply(replaced("property float u", "property quad u"), "a.ply"); },
                       {"header line 11", "unknown type 'quad'"});
    assert_parse_error([&] { parse_ply(good.substr(0, good.find("end_header")), "a.ply"); },
                       {"ends before 'end_header'"});
    assert_parse_error([&] { parse_ply(good.substr(0, good.size() - 4), "a.ply"); },
                       {"a.ply:20:", "ends inside face 0"});
    assert_parse_error([&] { parse_ply(good + "5\n", "a.ply"); }, {"a.ply:21:", "data after the last element"});
    assert_parse_error([&] { parse_ply(replaced("\n1.000000 0.000000 0.000000", "\nnan 0 0"), "a.ply"); },
                       {"a.ply:17:", "vertex 1", "not finite"});
    assert_parse_error([&] { parse_ply(replaced("\n1.000000 0.000000 0.000000", "\n1e300 0 0"), "a.ply"); },
                       {"vertex 1", "beyond"});
    assert_parse_error([&] { parse_ply(replaced("\n1.000000 0.000000 0.000000", "\none 0 0"), "a.ply"); },
                       {"a.ply:17:", "vertex 1", "'one' is not a number"});
    assert_parse_error([&] { parse_ply(replaced("4 0 1 2 3", "4 0 1.5 2 3"), "a.ply"); }, {"not an integer"});

    // Binary: a truncated body names the byte where data ran out.
    const std::string binary = binary_square(false);
    assert_parse_error([&] { parse_ply(binary.substr(0, binary.size() - 10), "b.ply"); },
                       {"b.ply: byte", "ends inside face 0"});
    std::string bad_index = binary;
    const std::size_t list = bad_index.find("end_header\n") + 11 + 4 * (3 * 8 + 1 + 2 * 4);
    bad_index[list + 1 + 4 * 3] = 42; // the fourth corner becomes vertex 42
    assert_parse_error([&] { parse_ply(bad_index, "b.ply"); }, {"b.ply: byte", "vertex index 42 is out of range"});
}

// A serialized mesh stream: header, then the zlib-compressed body. `flag_precision` false
// leaves the single-precision bit out, as some writers do.
std::string serialized_mesh(std::uint16_t version, bool doubles, std::uint32_t extra_flags, const char *name,
                            bool flag_precision = true) {
    std::string body;
    const std::uint32_t precision = doubles ? 0x2000 : flag_precision ? 0x1000 : 0;
    const std::uint32_t flags = 0x0001 | 0x0002 | precision | extra_flags;
    put<std::uint32_t>(body, flags, false);
    if (version == 4) body.append(name, std::strlen(name) + 1);
    put<std::uint64_t>(body, 4, false);
    put<std::uint64_t>(body, 2, false);
    auto real = [&](double value) {
        if (doubles)
            put<double>(body, value, false);
        else
            put<float>(body, static_cast<float>(value), false);
    };
    for (int i = 0; i < 4; ++i)
        for (int a = 0; a < 3; ++a) real(kPositions[i][a]);
    for (int i = 0; i < 4; ++i) real(0), real(0), real(1);
    for (int i = 0; i < 4; ++i) real(kUvs[i][0]), real(kUvs[i][1]);
    if (extra_flags & 0x0008)
        for (int i = 0; i < 12; ++i) real(0.5);
    for (std::uint32_t index : {0u, 1u, 2u, 0u, 2u, 3u}) put<std::uint32_t>(body, index, false);
    std::vector<unsigned char> compressed(compressBound(body.size()));
    uLongf size = compressed.size();
    assert_int_equal(compress(compressed.data(), &size, reinterpret_cast<const Bytef *>(body.data()), body.size()),
                     Z_OK);
    std::string mesh;
    put<std::uint16_t>(mesh, 0x041C, false);
    put<std::uint16_t>(mesh, version, false);
    mesh.append(reinterpret_cast<const char *>(compressed.data()), size);
    return mesh;
}

// Meshes one after another and the index of their offsets at the end.
std::string serialized_file(std::uint16_t version, const std::vector<std::string> &meshes) {
    std::string file;
    std::vector<std::uint64_t> offsets;
    for (const std::string &mesh : meshes) {
        offsets.push_back(file.size());
        file += mesh;
    }
    for (std::uint64_t offset : offsets)
        if (version == 4)
            put<std::uint64_t>(file, offset, false);
        else
            put<std::uint32_t>(file, static_cast<std::uint32_t>(offset), false);
    put<std::uint32_t>(file, static_cast<std::uint32_t>(meshes.size()), false);
    return file;
}

void serialized_meshes_read_in_both_versions_and_precisions(void **) {
    for (std::uint16_t version : {3, 4})
        for (bool doubles : {false, true}) {
            const std::string file =
                serialized_file(version, {serialized_mesh(version, doubles, 0, "first"),
                                          serialized_mesh(version, !doubles, 0x0008 | 0x0010, "second")});
            const SerializedMesh first = parse_serialized(file, "m.serialized", 0);
            assert_unit_square(first.mesh, true, true);
            assert_string_equal(first.name.c_str(), version == 4 ? "first" : "");
            assert_false(first.face_normals);
            const SerializedMesh second = parse_serialized(file, "m.serialized", 1);
            assert_unit_square(second.mesh, false, true); // face normals asked for: none kept
            assert_true(second.face_normals && second.had_colours);
        }
}

// Mitsuba's loader reads doubles exactly when 0x2000 is set and ignores the bits it does not
// know; public files carry flags such as 259 (0x0100 | normals | texture coordinates).
void serialized_flags_are_read_as_mitsuba_reads_them(void **) {
    const std::string file = serialized_file(
        4, {serialized_mesh(4, false, 0x0100, "unflagged", false), serialized_mesh(4, true, 0x0100 | 0x1000, "both")});
    const SerializedMesh single = parse_serialized(file, "m.serialized", 0);
    assert_unit_square(single.mesh, true, true);
    assert_false(single.face_normals || single.had_colours);
    assert_unit_square(parse_serialized(file, "m.serialized", 1).mesh, true, true);
}

void serialized_damage_is_a_located_error(void **) {
    const std::string file = serialized_file(4, {serialized_mesh(4, false, 0, "only")});
    assert_parse_error([&] { parse_serialized(file, "m.serialized", 1); },
                       {"m.serialized", "shape_index 1 is out of range", "holds 1 mesh"});
    assert_parse_error([&] { parse_serialized("PLY!", "m.serialized", 0); }, {"not a Mitsuba serialized mesh"});
    std::string version = file;
    version[2] = 9;
    assert_parse_error([&] { parse_serialized(version, "m.serialized", 0); }, {"version 9"});
    assert_parse_error([&] { parse_serialized(file.substr(0, 40), "m.serialized", 0); },
                       {"m.serialized: mesh 0 (at byte 0)", "ends inside"});
    std::string corrupt = file;
    for (std::size_t i = 12; i < 40; ++i) corrupt[i] = static_cast<char>(corrupt[i] ^ 0x5A);
    try {
        parse_serialized(corrupt, "m.serialized", 0);
        fail_msg("corrupt data was read");
    } catch (const Error &e) {
        assert_int_equal(e.status(), PPM_ERROR_PARSE);
        assert_non_null(std::strstr(e.what(), "m.serialized: mesh 0"));
    }
    // An index claiming more meshes than the file can hold (a single mesh without an index).
    std::string huge_index = file;
    const std::uint32_t claimed = 0x7FFFFFFF;
    std::memcpy(&huge_index[huge_index.size() - 4], &claimed, 4);
    assert_parse_error([&] { parse_serialized(huge_index, "m.serialized", 3); }, {"claims 2147483647 meshes"});
}

void files_that_do_not_exist_are_io_errors(void **) {
    for (int kind = 0; kind < 2; ++kind) {
        try {
            if (kind == 0)
                read_ply_file("/nonexistent/mesh.ply");
            else
                read_serialized_file("/nonexistent/mesh.serialized", 0);
            fail_msg("a missing file was read");
        } catch (const Error &e) {
            assert_int_equal(e.status(), PPM_ERROR_IO);
            assert_non_null(std::strstr(e.what(), "/nonexistent/mesh."));
        }
    }
}

} // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(ascii_ply_reads_positions_normals_uvs_and_fans_polygons),
        cmocka_unit_test(binary_ply_reads_the_same_in_both_byte_orders_and_reports_what_it_skips),
        cmocka_unit_test(ply_damage_is_a_located_error),
        cmocka_unit_test(serialized_meshes_read_in_both_versions_and_precisions),
        cmocka_unit_test(serialized_flags_are_read_as_mitsuba_reads_them),
        cmocka_unit_test(serialized_damage_is_a_located_error),
        cmocka_unit_test(files_that_do_not_exist_are_io_errors),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
