# SPDX-License-Identifier: Apache-2.0
"""Typed settings of scenes and contexts (ppm.h "Typed settings"): ints stay ints, whole floats
are accepted for integer keys, and wrong types and unknown keys are clear errors."""
import pytest

import libppm


def test_patch_presplit_is_an_int(scene):
    assert scene.patch_presplit == 12  # the documented default
    assert isinstance(scene.get("patch_presplit"), int)
    scene.patch_presplit = 4
    assert scene.get("patch_presplit") == 4 and scene.patch_presplit == 4
    scene.set("patch_presplit", 6.0)  # a whole float goes through ppm_scene_set_double
    assert scene.patch_presplit == 6


def test_tolerance_is_a_float(scene):
    scene.set("tolerance", 1e-6)
    value = scene.get("tolerance")
    assert isinstance(value, float) and value == 1e-6


def test_patch_presplit_errors(scene):
    with pytest.raises(libppm.InvalidArgumentError, match="whole number"):
        scene.set("patch_presplit", 2.5)
    with pytest.raises(libppm.InvalidArgumentError, match="patch_presplit"):
        scene.patch_presplit = 33
    with pytest.raises(TypeError, match="patch_presplit"):
        scene.patch_presplit = 2.0
    with pytest.raises(TypeError, match="patch_presplit"):
        scene.patch_presplit = True
    assert scene.patch_presplit == 12  # unchanged by the failures


def test_scene_unknown_key_and_wrong_type(scene):
    with pytest.raises(libppm.InvalidArgumentError,
                       match=r"unknown scene setting 'presplit' \(known: tolerance \(double\), "
                             r"patch_presplit \(int\)\)"):
        scene.get("presplit")
    with pytest.raises(libppm.InvalidArgumentError, match="unknown scene setting 'colour'"):
        scene.set("colour", 3)
    with pytest.raises(TypeError, match="expected int or float"):
        scene.set("tolerance", "1e-6")


def test_patch_presplit_reaches_the_commit(scene):
    # A flat patch S(u, v) = (u, v, 0): its control points lie on a regular grid.
    points = [[(j / 3, i / 3, 0.0) for i in range(4) for j in range(4)]]
    scene.add_bezier_patches(points)
    scene.patch_presplit = 2
    scene.commit()
    hit = scene.intersect((0.25, 0.75, 1.0), (0.0, 0.0, -1.0))
    assert hit.t == pytest.approx(1.0, abs=1e-9)
    assert (hit.u, hit.v) == (pytest.approx(0.25, abs=1e-9), pytest.approx(0.75, abs=1e-9))


def test_context_settings_through_floats():
    with libppm.Context() as context:
        context.set("threads", 2.0)
        assert context.get("threads") == 2 and context.threads == 2
        with pytest.raises(libppm.InvalidArgumentError, match="threads"):
            context.set("threads", 1.5)
        with pytest.raises(libppm.InvalidArgumentError, match="unknown context setting 'speed'"):
            context.set("speed", 1.0)
        with pytest.raises(TypeError):
            context.set("threads", "2")
        assert context.threads == 2
