# SPDX-License-Identifier: Apache-2.0
"""Shapes by their Mitsuba names (Scene.add_shape) and the type lists (libppm.type_names)."""
import numpy as np
import pytest

import libppm

from conftest import read_bpt, TEAPOT


def test_type_names_list_what_the_tables_hold():
    assert libppm.type_names("mode") == ["sppm", "ppm", "pppm", "vcm", "bpt", "vm"]
    shapes = libppm.type_names("shape")
    for name in ("sphere", "rectangle", "disk", "cylinder", "cube", "obj", "ply", "serialized", "bezier"):
        assert name in shapes
    assert "diffuse" in libppm.type_names("material")
    assert "point" in libppm.type_names("light")
    assert "bitmap" in libppm.type_names("texture")
    with pytest.raises(libppm.InvalidArgumentError, match="unknown kind 'bsdf'"):
        libppm.type_names("bsdf")


def test_shapes_by_name_hit_where_mitsuba_places_them():
    with libppm.Scene() as scene:
        grey = scene.add_material("diffuse", reflectance=0.5)
        to_world = np.eye(4)
        to_world[:3, 3] = (3, 0, 0)
        sphere = scene.add_shape("sphere", radius=2.0, to_world=to_world, bsdf=grey)
        # Mitsuba's cylinder around z from 0 to 1, radius 1, scaled along its axis by 4.
        cylinder = scene.add_shape("cylinder", to_world=np.diag([1.0, 1.0, 4.0, 1.0]) @ np.eye(4))
        scene.commit()
        hits = scene.intersect([[3, -10, 0], [0, -10, 2]], [[0, 1, 0], [0, 1, 0]])
        assert list(hits.geom_id) == [sphere, cylinder]
        np.testing.assert_allclose(hits.t, [8.0, 9.0], rtol=0, atol=1e-9)


def test_bezier_patches_by_name_are_the_patches_given():
    patches = read_bpt(TEAPOT)[:4]
    with libppm.Scene() as scene:
        geom = scene.add_shape("bezier", patches=patches)
        scene.commit()
        np.testing.assert_array_equal(scene.bezier_patches(geom), patches)


def test_a_misspelt_parameter_is_refused_with_a_suggestion():
    with libppm.Scene() as scene:
        with pytest.raises(libppm.InvalidArgumentError, match="did you mean 'radius'"):
            scene.add_shape("sphere", radiuss=1.0)
        with pytest.raises(libppm.InvalidArgumentError, match="unknown shape type 'spere'"):
            scene.add_shape("spere")
