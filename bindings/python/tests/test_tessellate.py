# SPDX-License-Identifier: Apache-2.0
"""Tessellation: shapes and counts, vertices on the surface, measured deviation."""
import numpy as np
import pytest

import libppm

from conftest import bezier


def test_uniform_grid_shapes_and_vertices_on_the_surface(teapot_points):
    mesh = libppm.tessellate(teapot_points, grid=4)
    n = len(teapot_points)
    assert mesh.triangles.shape == (2 * 4 * 4 * n, 3) and mesh.triangles.dtype == np.uint32
    v = mesh.vertices.shape[0]
    assert mesh.vertices.shape == (v, 3) and mesh.normals.shape == (v, 3) and mesh.uvs.shape == (v, 2)
    assert mesh.vertices.dtype == np.float64
    assert mesh.triangle_patches.shape == (2 * 16 * n,) and mesh.welded_ids.shape == (v,)
    assert mesh.triangles.max() < v and mesh.welded_ids.max() == mesh.welded_count - 1
    assert mesh.tolerance == 0
    # Vertices, normals and uvs agree with the numpy model of their patch.
    patch_of_vertex = np.empty(v, dtype=np.int64)
    patch_of_vertex[mesh.triangles.reshape(-1)] = np.repeat(mesh.triangle_patches, 3)
    s, su, sv = bezier(teapot_points[patch_of_vertex], mesh.uvs[:, 0], mesh.uvs[:, 1])
    np.testing.assert_allclose(mesh.vertices, s, atol=1e-12)
    cross = np.cross(su, sv)
    norm = np.linalg.norm(cross, axis=-1)
    regular = norm > 1e-6
    np.testing.assert_allclose(mesh.normals[regular], cross[regular] / norm[regular, None], atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(mesh.normals, axis=-1), 1.0, atol=1e-12)


def test_arrays_are_read_only_and_outlive_the_mesh(teapot_points):
    mesh = libppm.tessellate(teapot_points[:2], grid=2)
    with pytest.raises(ValueError):
        mesh.vertices[0, 0] = 1.0
    vertices = mesh.vertices
    del mesh
    assert np.isfinite(vertices).all()


def deviation_along_normals(points, mesh):
    """Distance from each triangle's centroid to the exact surface along the facet normal,
    measured with libppm's exact ray intersector on the patches themselves."""
    tri = mesh.vertices[mesh.triangles]
    centroid = tri.mean(axis=1)
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    area2 = np.linalg.norm(normal, axis=-1)
    keep = area2 > 1e-12
    normal = normal[keep] / area2[keep, None]
    centroid = centroid[keep]
    with libppm.Scene() as scene:
        scene.add_bezier_patches(points)
        scene.commit()
        reach = 0.05
        both = scene.intersect(np.concatenate([centroid, centroid]),
                               np.concatenate([normal, -normal]), tfar=reach)
    t = np.minimum(both.t[:len(centroid)], both.t[len(centroid):])
    return t


@pytest.mark.parametrize("tolerance", [1e-2, 1e-3])
def test_adaptive_deviation_within_tolerance(teapot_points, tolerance):
    mesh = libppm.tessellate(teapot_points, tolerance=tolerance)
    assert mesh.tolerance == tolerance
    assert 0 < mesh.max_deviation <= tolerance
    t = deviation_along_normals(teapot_points, mesh)
    assert np.isfinite(t).mean() > 0.99
    # Along the facet normal the surface can only be farther than its nearest point: allow
    # a little for that, nothing for a mesh that is simply too coarse.
    assert np.nanmax(np.where(np.isfinite(t), t, np.nan)) <= 1.5 * tolerance


def test_uniform_deviation_falls_with_the_grid(teapot_points):
    deviations = [libppm.tessellate(teapot_points, grid=g).max_deviation for g in (4, 8, 16)]
    assert deviations[0] > deviations[1] > deviations[2] > 0
    # Second order: doubling the grid divides the deviation by about 4.
    assert 2.5 < deviations[1] / deviations[2] < 6


def test_argument_errors(teapot_points):
    with pytest.raises(TypeError, match="exactly one"):
        libppm.tessellate(teapot_points)
    with pytest.raises(TypeError, match="exactly one"):
        libppm.tessellate(teapot_points, tolerance=1e-3, grid=4)
    with pytest.raises(ValueError, match="control_points"):
        libppm.tessellate(teapot_points[:, :8], grid=4)
    with pytest.raises(ValueError, match="grid"):
        libppm.tessellate(teapot_points, grid=-1)
    with pytest.raises(libppm.InvalidArgumentError):
        libppm.tessellate(teapot_points, tolerance=-1.0)
    with pytest.raises(libppm.InvalidArgumentError):
        libppm.tessellate(teapot_points, grid=5000)
    bad = teapot_points.copy()
    bad[1, 2, 0] = np.inf
    with pytest.raises(libppm.InvalidArgumentError, match="patch 1"):
        libppm.tessellate(bad, grid=2)
    with pytest.raises(libppm.InvalidArgumentError):
        libppm.tessellate(np.zeros((0, 16, 3)), grid=2)
