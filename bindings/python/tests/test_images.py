# SPDX-License-Identifier: Apache-2.0
"""libppm.write_image and check_image_path: EXR with its layers, 8-bit formats as sRGB of the
exposed radiance, and a path that cannot be written refused before any work."""
import os

import numpy as np
import pytest

import libppm


def test_exr_holds_the_radiance_and_the_layers(tmp_path):
    """The EXR header (read here without an EXR library) lists R, G, B and the layers."""
    image = np.full((5, 7, 3), 0.25, np.float32)
    path = tmp_path / "radiance.exr"
    libppm.write_image(path, image, layers={"radius": np.ones((5, 7)), "photons": np.zeros((5, 7))})
    data = path.read_bytes()
    assert data[:4] == bytes([0x76, 0x2F, 0x31, 0x01])  # the OpenEXR magic number
    channels = data[data.index(b"channels\x00chlist\x00"):][:200]
    for name in (b"R", b"G", b"B", b"radius", b"photons"):
        assert b"\x00" + name + b"\x00" in channels
    assert [p.name for p in tmp_path.iterdir()] == ["radiance.exr"]  # no temporary file left


def test_png_is_srgb_of_the_exposed_radiance(tmp_path):
    pyplot = pytest.importorskip("matplotlib.image")
    image = np.zeros((2, 3, 3), np.float32)
    image[0, 0] = 0.5            # sRGB(0.5) = 0.7354 -> 188
    image[0, 1] = 2.0            # clamped to 1 -> 255
    image[1, 2] = (0.25, 0, 0)   # at exposure +1: 0.5 -> 188
    libppm.write_image(tmp_path / "a.png", image)
    libppm.write_image(tmp_path / "b.png", image, exposure=1)
    a = np.round(pyplot.imread(str(tmp_path / "a.png"))[..., :3] * 255).astype(int)
    b = np.round(pyplot.imread(str(tmp_path / "b.png"))[..., :3] * 255).astype(int)
    assert tuple(a[0, 0]) == (188, 188, 188)
    assert tuple(a[0, 1]) == (255, 255, 255)
    assert tuple(a[1, 0]) == (0, 0, 0)
    assert tuple(b[1, 2]) == (188, 0, 0)


def test_bad_paths_are_refused_before_writing(tmp_path):
    with pytest.raises(libppm.InvalidArgumentError, match="no file extension"):
        libppm.check_image_path(tmp_path / "image")
    with pytest.raises(ValueError, match="cannot write this format"):
        libppm.check_image_path(tmp_path / "image.xyz")
    with pytest.raises(libppm.FileError, match="nowhere") as missing:
        libppm.check_image_path(tmp_path / "nowhere" / "image.exr")
    assert isinstance(missing.value, OSError)
    (tmp_path / "file").write_text("not a folder")
    with pytest.raises(OSError, match="is not a folder"):
        libppm.check_image_path(tmp_path / "file" / "image.exr")
    if os.geteuid() != 0:  # root may write anywhere
        locked = tmp_path / "locked"
        locked.mkdir()
        locked.chmod(0o500)
        with pytest.raises(libppm.FileError, match="cannot write into the folder"):
            libppm.check_image_path(locked / "image.exr")
    libppm.check_image_path(tmp_path / "fine.exr")  # a writable folder and a known format


def test_bad_images_are_refused(tmp_path):
    with pytest.raises(ValueError, match=r"expected shape \(H, W, 3\)"):
        libppm.write_image(tmp_path / "x.exr", np.zeros((4, 4)))
    with pytest.raises(ValueError, match="layer 'radius'"):
        libppm.write_image(tmp_path / "x.exr", np.zeros((4, 4, 3)), layers={"radius": np.zeros(3)})
    with pytest.raises(libppm.FileError):
        libppm.write_image(tmp_path / "missing" / "x.exr", np.zeros((4, 4, 3)))
