# SPDX-License-Identifier: Apache-2.0
"""Scene files and checkpoints."""
import json

import numpy as np
import pytest

import libppm

from conftest import TEAPOT



def write_scene(folder, **integrator):
    """The example of docs/scene-format.md, smaller; the teapot is referred to by path."""
    scene = {
        "version": 1,
        "integrator": {"type": "sppm", "photons_per_pass": 5000, **integrator},
        "sensor": {
            "type": "perspective", "fov": 39.3,
            "to_world": {"look_at": {"origin": [0, 1, 6.8], "target": [0, 1, 0], "up": [0, 1, 0]}},
            "film": {"width": 24, "height": 16},
        },
        "bsdfs": {"white": {"type": "diffuse", "reflectance": [0.75, 0.75, 0.75]}},
        "emitters": [{"type": "point", "position": [0, 1.9, 0], "intensity": [10, 10, 10]}],
        "shapes": [
            {"type": "rectangle", "bsdf": "white",
             "to_world": [{"scale": 2}, {"rotate": {"axis": [1, 0, 0], "angle": -90}}]},
            {"type": "bezier", "filename": str(TEAPOT), "bsdf": "white",
             "to_world": [{"rotate": {"axis": [1, 0, 0], "angle": -90}}, {"scale": 0.3}]},
        ],
    }
    path = folder / "scene.json"
    path.write_text(json.dumps(scene, indent=2))
    return path


def test_load_scene_file(tmp_path):
    path = write_scene(tmp_path, passes=3, time=1.5)
    with libppm.load(path) as f:
        assert f.passes == 3 and f.time == 1.5
        assert f.get("passes") == 3 and isinstance(f.get("passes"), int)
        assert f.get("time") == 1.5 and isinstance(f.get("time"), float)
        with pytest.raises(TypeError, match="unknown scene file value 'pases'"):
            f.get("pases")
        cam = f.camera
        assert (cam.width, cam.height) == (24, 16) and cam.fov == pytest.approx(39.3)
        np.testing.assert_allclose(cam.origin, (0, 1, 6.8))
        hits = f.scene.intersect((0, 1, 6.8), (0, -0.2, -1))
        assert hits.hit
        with f.create_renderer(seed=2) as r:
            assert r.get("photons_per_pass") == 5000 and r.get("seed") == 2
            image = r.render(2)
            assert image.shape == (16, 24, 3) and image.mean() > 0


def test_scene_file_errors(tmp_path):
    with pytest.raises(libppm.FileError):
        libppm.load(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{"version": 1, "shapes": [{"type": "sphere", "radius": -1}]}')
    with pytest.raises(libppm.ParseError, match="radius"):
        libppm.load(bad)


def test_scene_outlives_its_file(tmp_path):
    f = libppm.load(write_scene(tmp_path))
    scene = f.scene
    f.close()
    assert scene.intersect((0, 1, 6.8), (0, -0.2, -1)).hit


def small_renderer(scene, **settings):
    camera = libppm.Camera(origin=(0, -8, 3), target=(0, 0, 1.5), up=(0, 0, 1), fov=40,
                        width=16, height=12)
    return libppm.Renderer(scene, camera, photons_per_pass=3000, seed=4, **settings)


@pytest.fixture
def teapot_scene():
    with libppm.Scene() as s:
        s.load_bpt(TEAPOT, material=s.add_diffuse_material(0.7))
        s.add_point_light((2, -4, 6), 40)
        s.commit()
        yield s


def test_checkpoint_resumes_bit_for_bit(tmp_path, teapot_scene):
    checkpoint = tmp_path / "run.ckpt"
    with small_renderer(teapot_scene) as straight:
        expected = straight.render(4)
    with small_renderer(teapot_scene) as first:
        first.render(2)
        first.save_checkpoint(checkpoint)
    with small_renderer(teapot_scene) as resumed:
        resumed.load_checkpoint(checkpoint)
        assert resumed.passes == 2
        image = resumed.render(2)
    assert np.array_equal(image, expected)


def test_checkpoint_errors(tmp_path, teapot_scene):
    with small_renderer(teapot_scene) as r:
        with pytest.raises(libppm.FileError):
            r.load_checkpoint(tmp_path / "missing.ckpt")
        junk = tmp_path / "junk.ckpt"
        junk.write_bytes(b"not a checkpoint")
        with pytest.raises(libppm.ParseError):
            r.load_checkpoint(junk)
        r.render_pass()
        r.save_checkpoint(tmp_path / "one.ckpt")
        with pytest.raises(libppm.InvalidOperationError):
            r.load_checkpoint(tmp_path / "one.ckpt")
    with small_renderer(teapot_scene, direct_lighting=0) as other:
        with pytest.raises(libppm.InvalidArgumentError):
            other.load_checkpoint(tmp_path / "one.ckpt")
