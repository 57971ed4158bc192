# SPDX-License-Identifier: Apache-2.0
"""Disks, cylinders and mesh area lights from Python: hits against the analytic answers, and
the renderer accepting them as lights."""
import math

import numpy as np
import pytest

import libppm


def test_disk_and_cylinder_hits(scene):
    disk = scene.add_disk((0, 0, 0), (1, 0, 0), (0, 1, 0))
    tube = scene.add_cylinder((5, 0, 0), (5, 0, 2), 0.5)
    scene.commit()
    hits = scene.intersect([(0.3, 0.4, 3), (10, 0, 1)], [(0, 0, -1), (-1, 0, 0)])
    assert list(hits.geom_id) == [disk, tube]
    assert hits.t[0] == pytest.approx(3)
    assert hits.u[0] == pytest.approx(0.5)
    assert hits.v[0] == pytest.approx(math.atan2(0.4, 0.3) / (2 * math.pi))
    assert hits.t[1] == pytest.approx(4.5)
    assert hits.v[1] == pytest.approx(0.5)
    np.testing.assert_allclose(hits.ng[1], (1, 0, 0), atol=1e-12)


def test_flip_normals_and_mesh_light(scene):
    tri = scene.add_mesh([(0, 0, 1), (1, 0, 1), (0, 1, 1)], [(0, 1, 2)])
    scene.set_flip_normals(tri)
    scene.set_emission(tri, 1.0)
    scene.commit()
    hits = scene.intersect([(0.2, 0.2, 3)], [(0, 0, -1)])
    np.testing.assert_allclose(hits.ng[0], (0, 0, -1), atol=1e-12)


def test_bad_shapes(scene):
    with pytest.raises(libppm.InvalidArgumentError, match="p0 and p1"):
        scene.add_cylinder((1, 1, 1), (1, 1, 1), 1)
    with pytest.raises(libppm.InvalidArgumentError, match="radius"):
        scene.add_cylinder((0, 0, 0), (0, 0, 1), 0)
    with pytest.raises(libppm.InvalidArgumentError, match="no area"):
        scene.add_disk((0, 0, 0), (1, 0, 0), (2, 0, 0))
    sphere = scene.add_sphere((0, 0, 0), 1)
    with pytest.raises(libppm.InvalidArgumentError, match="flip_normals"):
        scene.set_flip_normals(sphere)
