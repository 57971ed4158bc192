// SPDX-License-Identifier: Apache-2.0
// Vertex normals computed for meshes without any, as Mitsuba 3 computes them: angle-weighted
// unit face normals, checked on a cube (three right angles at each corner: the diagonal), a
// fan whose corner angles differ (the weights are the angles, not areas or counts), and
// degenerate input.
#include "geometry/vertex_normals.h"

#include "test_support.h"

#include <cmath>

using namespace ppm;

namespace {

void assert_vec_close(const Vec3 &a, const Vec3 &b, double tolerance) {
    assert_close(a.x, b.x, tolerance);
    assert_close(a.y, b.y, tolerance);
    assert_close(a.z, b.z, tolerance);
}

// Every corner of a cube gets its diagonal: each of the three sides meets it at a right
// angle, split between one or two of its triangles.
void a_cube_corner_gets_its_diagonal(void **) {
    MeshData cube;
    for (int x = -1; x <= 1; x += 2)
        for (int y = -1; y <= 1; y += 2)
            for (int z = -1; z <= 1; z += 2) cube.positions.push_back({double(x), double(y), double(z)});
    const uint32_t quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (const auto &q : quads)
        for (uint32_t i : {q[0], q[1], q[2], q[0], q[2], q[3]}) cube.indices.push_back(i);
    const std::vector<Vec3> normals = angle_weighted_vertex_normals(cube);
    assert_int_equal(normals.size(), 8);
    for (std::size_t i = 0; i < 8; ++i) {
        const Vec3 &p = cube.positions[i];
        // The quads above face outwards except where listed inwards; either way the sum of
        // three orthogonal unit normals of equal weight is a diagonal.
        assert_close(std::fabs(normals[i].x), 1 / std::sqrt(3.0), 1e-15);
        assert_close(std::fabs(normals[i].y), 1 / std::sqrt(3.0), 1e-15);
        assert_close(std::fabs(normals[i].z), 1 / std::sqrt(3.0), 1e-15);
        assert_true(dot(normals[i], p) > 0); // outwards: the quads are wound outwards
    }
}

// Two triangles meeting at vertex 0 with angles 90 and 45 degrees, tilted apart: vertex 0's
// normal is (pi/2 n1 + pi/4 n2) normalised.
void corner_angles_weigh_the_face_normals(void **) {
    MeshData mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, 1}};
    // Triangle 0 in the plane z = 0 (normal +z, right angle at vertex 0); triangle 1 in the
    // plane x = 0 from vertex 0 to (0, 0, 1) and (0, 1, 1) (normal +x, 45 degrees at vertex 0).
    mesh.indices = {0, 1, 2, 0, 3, 4};
    const std::vector<Vec3> normals = angle_weighted_vertex_normals(mesh);
    const Vec3 n1{0, 0, 1}, n2 = normalize(cross(Vec3{0, 0, 1}, Vec3{0, 1, 1}));
    assert_vec_close(normals[0], normalize(n1 * (M_PI / 2) + n2 * (M_PI / 4)), 1e-15);
    assert_vec_close(normals[1], n1, 1e-15);
    assert_vec_close(normals[3], n2, 1e-15);
}

// A degenerate triangle adds nothing; a vertex with nothing gets Mitsuba's (1, 0, 0).
void degenerate_triangles_add_nothing(void **) {
    MeshData mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {5, 5, 5}};
    mesh.indices = {0, 1, 2, 0, 1, 3};
    const std::vector<Vec3> normals = angle_weighted_vertex_normals(mesh);
    assert_vec_close(normals[0], {0, 0, 1}, 0);
    assert_vec_close(normals[3], {1, 0, 0}, 0);
    assert_vec_close(normals[4], {1, 0, 0}, 0);
}

} // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_cube_corner_gets_its_diagonal),
        cmocka_unit_test(corner_angles_weigh_the_face_normals),
        cmocka_unit_test(degenerate_triangles_add_nothing),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
