# SPDX-License-Identifier: Apache-2.0
"""Bad input and misuse give clear Python exceptions, never a crash."""
import gc
import threading

import numpy as np
import pytest

import libppm

from conftest import TEAPOT


def test_status_classes_carry_status_and_message(scene):
    with pytest.raises(libppm.InvalidArgumentError) as info:
        scene.add_sphere((0, 0, 0), -1.0)
    e = info.value
    assert e.status == libppm.Status.INVALID_ARGUMENT
    assert isinstance(e, libppm.Error) and isinstance(e, ValueError)
    assert "radius" in e.message and str(e) == e.message


def test_query_before_commit_is_invalid_operation(scene):
    scene.add_sphere((0, 0, 0), 1.0)
    with pytest.raises(libppm.InvalidOperationError, match="commit"):
        scene.intersect((0, 0, -5), (0, 0, 1))


def test_empty_scene_commit(scene):
    with pytest.raises(libppm.InvalidOperationError):
        scene.commit()


@pytest.mark.parametrize("bad", [
    np.zeros((2, 16, 3), dtype=complex),
    np.array([["a"] * 3] * 16),
    [[1, 2, 3], [4, 5]],
    object(),
])
def test_wrong_dtypes_are_type_errors(scene, bad):
    with pytest.raises(TypeError, match="control_points"):
        scene.add_bezier_patches(bad)


@pytest.mark.parametrize("shape", [(16, 3), (2, 16, 2), (2, 15, 3), (2, 4, 3, 3), (48,)])
def test_wrong_shapes_are_value_errors_naming_argument_and_shape(scene, shape):
    with pytest.raises(ValueError, match=r"control_points: expected shape \(n, 16, 3\) or \(n, 4, 4, 3\)"):
        scene.add_bezier_patches(np.zeros(shape))


def test_convertible_input_is_accepted(scene, teapot_points):
    as_float32 = teapot_points.astype(np.float32)
    as_list = teapot_points[:2].reshape(2, 4, 4, 3).tolist()
    assert scene.add_bezier_patches(as_float32) == 0
    assert scene.add_bezier_patches(as_list) == 1
    assert scene.add_bezier_patches(np.asfortranarray(teapot_points[:3, :, :])) == 2
    assert scene.primitive_count(1) == 2


def test_nan_and_inf_go_to_the_library(scene, teapot_points):
    points = teapot_points.copy()
    points[3, 5, 1] = np.nan
    with pytest.raises(libppm.InvalidArgumentError, match="patch 3"):
        scene.add_bezier_patches(points)
    with pytest.raises(libppm.InvalidArgumentError):
        scene.add_sphere((0, np.inf, 0), 1.0)
    with pytest.raises(libppm.InvalidArgumentError):
        scene.add_quad((0, 0, 0), (1, 0, 0), (np.nan, 1, 0))
    # A failed add leaves the scene unchanged: the next id is still 0.
    assert scene.add_sphere((0, 0, 0), 1.0) == 0


def test_nan_rays_name_the_first_bad_index(scene):
    scene.add_sphere((0, 0, 0), 1.0)
    scene.commit()
    origins = np.zeros((5, 3))
    origins[:, 2] = -5
    origins[3, 0] = np.nan
    with pytest.raises(libppm.InvalidArgumentError, match="ray 3"):
        scene.intersect(origins, (0, 0, 1))
    with pytest.raises(libppm.InvalidArgumentError):
        scene.occluded((0, 0, -5), (0, 0, 0))
    with pytest.raises(libppm.InvalidArgumentError):
        scene.intersect((0, 0, -5), (0, 0, 1), tnear=2.0, tfar=1.0)


def test_ray_shapes(scene):
    scene.add_sphere((0, 0, 0), 1.0)
    scene.commit()
    with pytest.raises(ValueError, match=r"origins: expected shape \(\.\.\., 3\)"):
        scene.intersect(np.zeros((4, 2)), (0, 0, 1))
    with pytest.raises(ValueError, match="broadcast"):
        scene.intersect(np.zeros((4, 3)), np.ones((5, 3)))
    with pytest.raises(TypeError, match="directions"):
        scene.intersect((0, 0, -5), "up")


def test_mesh_argument_checks(scene):
    positions = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    with pytest.raises(TypeError, match="indices: expected integers"):
        scene.add_mesh(positions, [[0.0, 1.0, 2.0]])
    with pytest.raises(ValueError, match="indices: indices must lie"):
        scene.add_mesh(positions, [[0, 1, -2]])
    with pytest.raises(ValueError, match=r"normals: expected shape \(3, 3\)"):
        scene.add_mesh(positions, [[0, 1, 2]], normals=np.zeros((2, 3)))
    with pytest.raises(libppm.InvalidArgumentError, match="triangle 0 uses vertex 7"):
        scene.add_mesh(positions, [[0, 1, 7]])


def test_ids_must_be_uint32(scene):
    scene.add_sphere((0, 0, 0), 1.0)
    with pytest.raises(ValueError, match="geom_id"):
        scene.set_material(-1, 0)
    with pytest.raises(TypeError, match="material_id"):
        scene.set_material(0, "glass")
    with pytest.raises(libppm.InvalidArgumentError):
        scene.set_material(5, 0)


def test_files(scene, tmp_path):
    with pytest.raises(libppm.FileError, match="nothing.bpt"):
        scene.load_bpt(tmp_path / "nothing.bpt")
    bad = tmp_path / "bad.bpt"
    bad.write_text("1\n3 3\n0 0 0\n")
    with pytest.raises(libppm.ParseError, match="bad.bpt"):
        scene.load_bpt(bad)
    with pytest.raises(libppm.FileError):
        scene.load_obj(tmp_path / "nothing.obj")


def test_unknown_settings(scene):
    with pytest.raises(libppm.InvalidArgumentError, match="colour"):
        scene.set("colour", 1.0)
    with pytest.raises(libppm.InvalidArgumentError):
        scene.tolerance = 1.0
    with pytest.raises(libppm.InvalidArgumentError, match="speed"):
        libppm.Context().set("speed", 3)


def test_use_after_close_is_a_clear_error():
    scene = libppm.Scene()
    scene.add_sphere((0, 0, 0), 1.0)
    scene.close()
    scene.close()  # idempotent
    assert scene.closed
    for call in (scene.commit, lambda: scene.add_sphere((0, 0, 0), 1.0),
                 lambda: scene.intersect((0, 0, -5), (0, 0, 1)), lambda: scene.bounds):
        with pytest.raises(libppm.ClosedError, match="Scene is closed"):
            call()
    assert issubclass(libppm.ClosedError, libppm.Error) and issubclass(libppm.ClosedError, ValueError)


def test_context_manager_closes():
    with libppm.Context(threads=1) as ctx:
        assert ctx.threads == 1
    assert ctx.closed
    with pytest.raises(libppm.ClosedError):
        ctx.threads
    with pytest.raises(libppm.ClosedError):
        libppm.Scene(ctx)


def test_children_keep_parents_alive():
    ctx = libppm.Context(threads=2)
    scene = libppm.Scene(ctx)
    scene.load_bpt(TEAPOT)
    scene.add_point_light((0, -5, 5), 10)
    ctx.close()
    scene.commit()  # the C scene holds its context
    camera = libppm.Camera(origin=(0, -10, 2), target=(0, 0, 1.5), up=(0, 0, 1), width=8, height=8)
    renderer = libppm.Renderer(scene, camera, photons_per_pass=1000)
    scene.close()
    del scene
    gc.collect()
    renderer.render_pass()
    assert renderer.passes == 1
    renderer.close()


def test_errors_are_per_thread():
    """Each thread sees the message of its own failed call."""
    messages = {}

    def fail(name, radius):
        with libppm.Scene() as s:
            try:
                s.add_sphere((0, 0, 0), radius)
            except libppm.InvalidArgumentError as e:
                messages[name] = e.message

    threads = [threading.Thread(target=fail, args=(n, r)) for n, r in (("a", -1.0), ("b", np.nan))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert set(messages) == {"a", "b"} and all(messages.values())
