# SPDX-License-Identifier: Apache-2.0
"""Materials, textures, patch uv rectangles and lights through the Python API."""
import math

import numpy as np
import pytest

import libppm

from conftest import TEAPOT


def write_png(path, rgb8):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.imsave(path, np.asarray(rgb8, dtype=np.uint8))


def srgb_to_linear(c):
    c = c / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def test_texture_replaces_the_reflectance(tmp_path):
    """A plane under a point light with a one-texel texture: L = texel / pi * I / h^2."""
    texel = np.array([255, 128, 0])
    png = tmp_path / "texel.png"
    write_png(png, texel[None, None, :])
    with libppm.Scene() as scene:
        material = scene.add_diffuse_material(0.3)
        scene.set_texture(material, png, scale=(2, 2), offset=(0.1, 0))
        scene.add_quad((-2, -2, 0), (4, 0, 0), (0, 4, 0), material=material)
        scene.add_point_light((0, 0, 1), 2.0)
        scene.commit()
        camera = libppm.Camera(origin=(0, 0, 3), target=(0, 0, 0), fov=10, width=5, height=5)
        # sppm: its shadow rays give the direct light in two passes
        with libppm.Renderer(scene, camera, mode="sppm", photons_per_pass=1000) as r:
            centre = r.render(2)[2, 2]
    np.testing.assert_allclose(centre, srgb_to_linear(texel) / math.pi * 2.0, rtol=0.01, atol=1e-6)


def test_texture_errors(scene, tmp_path):
    glass = scene.add_dielectric_material()
    diffuse = scene.add_diffuse_material()
    with pytest.raises(libppm.FileError, match="missing.png"):
        scene.set_texture(diffuse, tmp_path / "missing.png")
    png = tmp_path / "t.png"
    write_png(png, np.zeros((2, 2, 3)))
    with pytest.raises(libppm.InvalidArgumentError):
        scene.set_texture(glass, png)
    with pytest.raises(ValueError, match="scale"):
        scene.set_texture(diffuse, png, scale=(1, 1, 1))
    with pytest.raises(libppm.InvalidArgumentError):
        scene.set_texture(diffuse, png, scale=(0, 1))


def test_patch_uv_rects(scene):
    teapot = scene.load_bpt(TEAPOT)
    sphere = scene.add_sphere((0, 0, 0), 1)
    rects = np.column_stack([np.arange(32) / 32, np.zeros(32), np.arange(1, 33) / 32, np.ones(32)])
    scene.set_patch_uv_rects(teapot, rects)
    with pytest.raises(ValueError, match="rects"):
        scene.set_patch_uv_rects(teapot, rects[:31])
    with pytest.raises(ValueError, match=r"rects: expected shape \(n, 4\)"):
        scene.set_patch_uv_rects(teapot, rects[:, :3])
    bad = rects.copy()
    bad[4, 2] = np.nan
    with pytest.raises(libppm.InvalidArgumentError):
        scene.set_patch_uv_rects(teapot, bad)
    with pytest.raises(libppm.InvalidArgumentError):
        scene.set_patch_uv_rects(sphere, [[0, 0, 1, 1]])


def test_material_and_light_values_are_checked(scene):
    assert [scene.add_diffuse_material((0.2, 0.4, 0.6)), scene.add_mirror_material(),
            scene.add_coated_material(0.5, int_ior=1.49), scene.add_dielectric_material(1.33)] == [0, 1, 2, 3]
    with pytest.raises(libppm.InvalidArgumentError, match="reflectance"):
        scene.add_diffuse_material(1.5)
    with pytest.raises(ValueError, match="reflectance"):
        scene.add_diffuse_material((0.1, 0.2))
    with pytest.raises(libppm.InvalidArgumentError):
        scene.add_dielectric_material(-1.0)
    with pytest.raises(libppm.InvalidArgumentError):
        scene.add_spot_light((0, 0, 1), (0, 0, 0), 1.0, cutoff_angle=10, beam_width=20)
    assert scene.add_spot_light((0, 0, 1), (0, 0, 0), (1, 2, 3)) == 0
    assert scene.add_point_light((0, 0, 1), 1.0) == 1
    mesh = scene.add_mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    scene.set_emission(mesh, 1.0)  # meshes are area lights too
    with pytest.raises(libppm.InvalidArgumentError, match="radiance"):
        scene.set_emission(mesh, -1.0)
    quad = scene.add_quad((0, 0, 0), (1, 0, 0), (0, 1, 0))
    with pytest.raises(libppm.InvalidArgumentError):
        scene.set_emission(quad, -1.0)


def test_area_light_seen_directly():
    """A camera looking at the emitting side of a quad light sees its radiance."""
    with libppm.Scene() as scene:
        light = scene.add_quad((-5, -5, 0), (10, 0, 0), (0, 10, 0))  # normal +z
        scene.set_emission(light, (1.0, 2.0, 3.0))
        scene.commit()
        camera = libppm.Camera(origin=(0, 0, 2), target=(0, 0, 0), fov=30, width=6, height=4)
        with libppm.Renderer(scene, camera, photons_per_pass=1000) as r:
            image = r.render(1)
    np.testing.assert_allclose(image.reshape(-1, 3).mean(axis=0), [1, 2, 3], rtol=1e-5)


def plane_under_light(build):
    """Centre pixel of a plane of the material `build(scene)` returns, under a point light 1 m above."""
    with libppm.Scene() as scene:
        material = build(scene)
        scene.add_quad((-2, -2, 0), (4, 0, 0), (0, 4, 0), material=material)
        scene.add_light("point", position=(0, 0, 1), intensity=2.0)
        scene.commit()
        camera = libppm.Camera(origin=(0, 0, 3), target=(0, 0, 0), fov=10, width=5, height=5)
        # sppm: its shadow rays give the direct light in two passes
        with libppm.Renderer(scene, camera, mode="sppm", photons_per_pass=1000) as r:
            return r.render(2)[2, 2]


def test_named_parameters_as_in_load_dict(tmp_path):
    """add_material / add_texture / add_light take Mitsuba's names; a texture id feeds a colour."""
    grey = plane_under_light(lambda s: s.add_material("diffuse", reflectance=(0.2, 0.4, 0.6)))
    np.testing.assert_allclose(grey, np.array([0.2, 0.4, 0.6]) / math.pi * 2.0, rtol=0.01)

    texel = np.array([255, 128, 0])
    png = tmp_path / "texel.png"
    write_png(png, texel[None, None, :])

    def textured(scene):
        texture = scene.add_texture("bitmap", filename=png, to_uv=np.diag([2.0, 2.0, 1.0, 1.0]))
        assert isinstance(texture, libppm.TextureId)
        inner = scene.add_material("diffuse", reflectance=texture)
        return scene.add_material("twosided", bsdf=inner)

    np.testing.assert_allclose(plane_under_light(textured), srgb_to_linear(texel) / math.pi * 2.0, rtol=0.01)


def test_named_parameters_refuse_misuse():
    with libppm.Scene() as scene:
        with pytest.raises(libppm.InvalidArgumentError, match="did you mean 'reflectance'"):
            scene.add_material("diffuse", reflectanse=0.5)
        with pytest.raises(libppm.InvalidArgumentError, match="unknown material type 'difuse'"):
            scene.add_material("difuse")
        with pytest.raises(libppm.InvalidArgumentError, match="'reflectance' must be at most 1"):
            scene.add_material("diffuse", reflectance=(0.5, 2, 0.5))
        with pytest.raises(libppm.InvalidArgumentError, match="'bsdf' must be a material id"):
            scene.add_material("twosided", bsdf=0)  # a plain int is a number, not an id
        with pytest.raises(ValueError, match="to_world"):
            scene.add_light("spot", to_world=np.zeros((3, 3, 3)))


def test_scene_files_reach_every_registered_type():
    """A JSON type outside the builder's own list goes to the API's table, errors located."""
    scene = {
        "bsdfs": {"grey": {"type": "diffuse", "reflectance": 0.5},
                  "shell": {"type": "twosided", "bsdf": "grey"}},
        "emitters": [{"type": "point", "position": [0, 0, 3], "intensity": 1}],
        "shapes": [{"type": "sphere", "bsdf": "shell"}],
    }
    assert libppm.load_dict(scene) is not None
    scene["bsdfs"]["shell"]["bsdff"] = "grey"
    with pytest.raises(libppm.ParseError, match=r"bsdfs\.shell\.bsdff: twosided material has no parameter"):
        libppm.load_dict(scene)
    del scene["bsdfs"]["shell"]["bsdff"]
    scene["bsdfs"]["shell"]["bsdf"] = "nothing"
    with pytest.raises(libppm.ParseError, match="no bsdf named 'nothing'"):
        libppm.load_dict(scene)


def test_checkerboard_through_the_generic_path():
    """add_texture("checkerboard", ...) feeds a colour like a bitmap; to_uv moves its cells."""
    color0, color1 = np.array([0.2, 0.4, 0.6]), np.array([0.6, 0.3, 0.1])

    def checkered(du, dv):
        def build(scene):
            to_uv = np.eye(4)
            to_uv[0, 3], to_uv[1, 3] = du, dv
            texture = scene.add_texture("checkerboard", color0=tuple(color0), color1=tuple(color1), to_uv=to_uv)
            assert isinstance(texture, libppm.TextureId)
            return scene.add_material("diffuse", reflectance=texture)
        return build

    # The centre pixel sees (u, v) = (0.5, 0.5) + (du, dv): color0 where both fractional parts
    # are > 0.5 or both are not (Mitsuba 3), color1 elsewhere.
    np.testing.assert_allclose(plane_under_light(checkered(0.25, 0.25)), color0 / math.pi * 2.0, rtol=0.01)
    np.testing.assert_allclose(plane_under_light(checkered(0.25, 0.75)), color1 / math.pi * 2.0, rtol=0.01)
    with libppm.Scene() as scene:
        with pytest.raises(libppm.InvalidArgumentError, match="'color1' must be >= 0"):
            scene.add_texture("checkerboard", color1=-1.0)


def test_lights_at_infinity_and_face_normals():
    """A diffuse sphere under a constant environment L shows rho * L (it sees only the sky);
    face normals flatten a mesh's shading normals."""
    with libppm.Scene() as scene:
        grey = scene.add_material("diffuse", reflectance=0.5)
        scene.add_sphere((0, 0, 0), 1.0, material=grey)
        scene.add_light("constant", radiance=2.0)
        scene.commit()
        # Every pixel sees the sphere; one light sample per pixel and pass: 5184 in all.
        camera = libppm.Camera(origin=(0, 0, 4), target=(0, 0, 0), fov=10, width=9, height=9)
        with libppm.Renderer(scene, camera, photons_per_pass=20000) as r:
            image = r.render(64)
    np.testing.assert_allclose(image.mean(axis=(0, 1)), 1.0, rtol=0.04)
    with libppm.Scene() as scene:
        positions = [(-1, -1, 0), (1, -1, 0), (0, 1, 0)]
        mesh = scene.add_mesh(positions, [(0, 1, 2)], normals=[(0.6, 0, 0.8)] * 3)
        scene.set_face_normals(mesh)
        scene.commit()
        hit = scene.intersect((0.2, 0.2, 5), (0, 0, -1))
        np.testing.assert_allclose(np.abs(hit.ns), [0, 0, 1], atol=1e-9)
    with libppm.Scene() as scene:
        scene.add_sphere((0, 0, 0), 1.0)
        with pytest.raises(libppm.InvalidArgumentError, match="face_normals"):
            scene.set_face_normals(0)
