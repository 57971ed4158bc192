# SPDX-License-Identifier: Apache-2.0
"""The one-call helpers: load_file (JSON and Mitsuba XML with parameters), load_dict,
load_string, render; the exceptions Python code expects; camera defaults."""
import dataclasses
import json
import os
import warnings

import numpy as np
import pytest

import libppm

from conftest import REPO, TEAPOT

SMALL_BOX = REPO / "tests" / "data" / "scenes" / "small_box.json"

BOX_XML = """<scene version="3.0.0">
  <default name="res" value="20"/>
  <default name="spp" value="3"/>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, -5, 1" target="0, 0, 1" up="0, 0, 1"/></transform>
    <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
    <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="16"/></film>
  </sensor>
  <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.5"/></bsdf>
  <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform><ref id="grey"/></shape>
  <shape type="sphere"><point name="center" x="0" y="0" z="1"/><float name="radius" value="0.5"/>
    <ref id="grey"/></shape>
  <emitter type="point"><point name="position" x="0" y="-2" z="3"/><rgb name="intensity" value="10"/></emitter>
</scene>
"""

SMALL_DICT = {
    "integrator": {"photons_per_pass": 2000},
    "sensor": {"fov": 40, "film": {"width": 12, "height": 10},
               "to_world": {"look_at": {"origin": [0, -5, 1], "target": [0, 0, 1], "up": [0, 0, 1]}}},
    "bsdfs": {"grey": {"type": "diffuse", "reflectance": 0.5}},
    "emitters": [{"type": "point", "position": [0, -2, 3], "intensity": 10}],
    "shapes": [{"type": "sphere", "center": [0, 0, 1], "radius": 0.5, "bsdf": "grey"},
               {"type": "rectangle", "bsdf": "grey", "to_world": {"scale": 3}}],
}


@pytest.fixture
def box_xml(tmp_path):
    path = tmp_path / "box.xml"
    path.write_text(BOX_XML)
    return path


def test_load_file_reads_xml_with_its_defaults_and_parameters(box_xml):
    with libppm.load_file(box_xml) as f:
        assert (f.camera.width, f.camera.height, f.passes) == (20, 16, 3)
        assert f.camera.fov == pytest.approx(40)
    with libppm.load_file(box_xml, res=8, spp=2) as f:  # Mitsuba's -D res=8 -D spp=2
        assert (f.camera.width, f.passes) == (8, 2)
    with pytest.raises(libppm.ParseError, match=r"box\.xml:\d+:\d+"):
        libppm.load_file(box_xml, res="wide")
    with pytest.raises(ValueError, match="apply to Mitsuba XML scene files only"):
        libppm.load_file(REPO / "examples" / "scenes" / "teapot-cornell.json", spp=4)


def test_lenient_xml_substitutes_with_a_python_warning(tmp_path):
    path = tmp_path / "rough.xml"
    path.write_text(BOX_XML.replace('<bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.5"/>',
                                    '<bsdf type="hair" id="grey">'))
    with pytest.raises(libppm.ParseError, match="hair"):
        libppm.load_file(path)
    with pytest.warns(libppm.Warning, match=r"rough\.xml:\d+:\d+: <bsdf>"):
        f = libppm.load_file(path, lenient=True)
    with f:
        assert f.create_renderer(photons_per_pass=1000).render(1).mean() > 0


def test_load_dict_and_load_string_render_what_they_say():
    with libppm.load_dict(SMALL_DICT) as f:
        assert (f.camera.width, f.camera.height) == (12, 10)
        image = libppm.render(f, passes=2)
    assert image.shape == (10, 12, 3) and image.dtype == np.float32 and image.mean() > 0
    with libppm.load_string(json.dumps(SMALL_DICT)) as f:
        assert libppm.render(f, passes=2, seed=0).shape == (10, 12, 3)
    with libppm.load_string(BOX_XML, spp=5) as f:
        assert (f.camera.width, f.passes) == (20, 5)

    # File names inside are relative to `folder`.
    teapot = {**SMALL_DICT, "shapes": [{"type": "bezier", "filename": TEAPOT.name, "bsdf": "grey"}]}
    with libppm.load_dict(teapot, folder=TEAPOT.parent) as f:
        assert f.scene.bounds[1][2] > f.scene.bounds[0][2]
    with pytest.raises(libppm.FileNotFoundError, match=TEAPOT.name):
        libppm.load_dict(teapot)


def test_load_dict_errors_name_the_key():
    bad = json.loads(json.dumps(SMALL_DICT))
    bad["shapes"][0]["radius"] = -1
    with pytest.raises(libppm.ParseError, match=r"shapes\[0\]\.radius"):
        libppm.load_dict(bad)
    with pytest.raises(TypeError, match="not JSON data"):
        libppm.load_dict({"shapes": [object()]})
    with pytest.raises(TypeError, match="not JSON data"):
        libppm.load_dict({"sensor": {"fov": float("nan")}})


def test_render_one_call_is_deterministic_in_the_seed(tmp_path):
    path = tmp_path / "small.json"
    path.write_text(json.dumps(SMALL_DICT))
    a = libppm.render(path, passes=2, seed=3)
    b = libppm.render(str(path), passes=2, seed=3)
    c = libppm.render(path, passes=2, seed=4)
    assert np.array_equal(a, b) and not np.array_equal(a, c)
    # A time budget alone renders at least one pass and stops.
    assert libppm.render(path, time=0.01).mean() > 0
    with pytest.raises(ValueError):
        libppm.render(path, passes=0)


def test_python_exceptions_where_python_raises_them(tmp_path):
    missing = tmp_path / "missing.json"
    with pytest.raises(FileNotFoundError) as info:
        libppm.load_file(missing)
    assert isinstance(info.value, libppm.FileError) and isinstance(info.value, OSError)
    assert isinstance(info.value, libppm.Error) and "missing.json" in str(info.value)

    path = tmp_path / "small.json"
    path.write_text(json.dumps(SMALL_DICT))
    # A mistyped keyword is a TypeError, as for any Python function, and a libppm.Error.
    with pytest.raises(TypeError, match="photns_per_pass") as info:
        libppm.render(path, passes=1, photns_per_pass=1000)
    assert isinstance(info.value, libppm.UnknownKeyError) and isinstance(info.value, libppm.Error)
    with libppm.load_file(path) as f, f.create_renderer() as renderer:
        with pytest.raises(TypeError, match="alhpa"):
            renderer.set(alhpa=0.5)
        with pytest.raises(TypeError, match="alhpa"):
            renderer.get("alhpa")
        with pytest.raises(ValueError):  # a known key with a bad value stays a ValueError
            renderer.set(alpha=-1.0)


def test_camera_defaults_are_those_of_a_scene_file_without_sensor(tmp_path):
    scene = {key: value for key, value in SMALL_DICT.items() if key != "sensor"}
    with libppm.load_dict(scene) as f:
        from_file = f.camera
    default = libppm.Camera()
    for field in dataclasses.fields(libppm.Camera):
        if field.name == "crop":  # no crop window: None
            assert from_file.crop is None and default.crop is None
            continue
        if field.name == "pixel_filter":
            assert from_file.pixel_filter == default.pixel_filter == "box"
            continue
        np.testing.assert_allclose(getattr(from_file, field.name), getattr(default, field.name),
                                   err_msg=field.name)


@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
def test_warnings_can_be_errors_without_breaking_the_load(box_xml):
    # A filter that turns libppm warnings into errors must not crash the extension.
    path = box_xml.parent / "hair.xml"
    path.write_text(BOX_XML.replace('<bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.5"/>',
                                    '<bsdf type="hair" id="grey">'))
    with warnings.catch_warnings():
        warnings.simplefilter("error", libppm.Warning)
        with libppm.load_file(path, lenient=True) as f:
            assert f.camera.width == 20
    assert os.path.exists(path)


def test_principal_point_offset_slides_the_image(tmp_path):
    """An offset of (a / width, b / height) renders the window a crop at (a, b) renders, and a
    Mitsuba sensor's principal_point_offset_x / _y reaches the Python camera."""
    scene = libppm.load_file(SMALL_BOX)
    cropped = libppm.render(scene, passes=8, width=24, height=18, crop=(6, 3, 18, 12),
                            photons_per_pass=2000)
    offset = libppm.render(scene, passes=8, width=24, height=18, crop=(0, 0, 12, 9),
                           principal_point_offset=(6 / 24, 3 / 18), photons_per_pass=2000)
    np.testing.assert_allclose(offset, cropped, rtol=1e-6, atol=1e-7)
    scene.close()
    path = tmp_path / "offset.xml"
    path.write_text('<scene version="3.0.0"><sensor type="perspective">'
                    '<float name="principal_point_offset_x" value="0.25"/></sensor>'
                    '<shape type="sphere"/><emitter type="point"/></scene>')
    with libppm.load_file(path) as f:
        assert f.camera.principal_point_offset == (0.25, 0.0)
        with f.create_renderer() as renderer:
            assert renderer.camera.principal_point_offset == (0.25, 0.0)
    with pytest.raises(ValueError, match="principal_point_offset"):
        libppm.Camera(principal_point_offset=(1.0,))._as_tuple()


def test_pixel_filter_of_a_scene_file(tmp_path):
    """A Mitsuba scene without an rfilter has Mitsuba's gaussian; a tent keeps its radius; the
    filter smooths an image, which keeps its mean."""
    path = tmp_path / "filtered.xml"
    path.write_text('<scene version="3.0.0"><sensor type="perspective"><film type="hdrfilm">'
                    '<integer name="width" value="16"/><integer name="height" value="16"/></film></sensor>'
                    '<shape type="sphere"><point name="center" value="0, 0, 6"/></shape>'
                    '<emitter type="point"><point name="position" value="0, 1, 2"/>'
                    '<rgb name="intensity" value="10"/></emitter></scene>')
    with libppm.load_file(path) as f:
        assert (f.camera.pixel_filter, f.camera.pixel_filter_parameter) == ("gaussian", 0.0)
        smooth = libppm.render(f, passes=16, photons_per_pass=2000)
        sharp = libppm.render(f, passes=16, photons_per_pass=2000, pixel_filter="box")
    assert abs(smooth.mean() / sharp.mean() - 1) < 0.05
    # Horizontal neighbours differ less through the filter.
    assert np.abs(np.diff(smooth, axis=1)).mean() < np.abs(np.diff(sharp, axis=1)).mean()
    with pytest.raises(ValueError, match="pixel_filter"):
        libppm.Camera(pixel_filter="mitchell")._as_tuple()


def test_size_and_crop_of_a_scene_file(tmp_path):
    """Keywords of the camera change the file's camera: another size, or a crop window whose
    pixels converge to those of the whole image at the same place."""
    scene = libppm.load_file(SMALL_BOX)
    with scene.create_renderer(width=24, height=18, photons_per_pass=2000) as whole:
        assert (whole.width, whole.height) == (24, 18)
        assert whole.camera.width == 24 and whole.camera.crop is None
        full = whole.render(32)
    assert full.shape == (18, 24, 3)
    cropped = libppm.render(scene, passes=32, width=24, height=18, crop=(6, 3, 18, 12),
                            photons_per_pass=2000)
    assert cropped.shape == (9, 12, 3)
    window = full[3:12, 6:18]
    # Same place: the difference is noise; one pixel to the side it is the image's structure.
    same = np.abs(cropped - window).mean()
    shifted = np.abs(cropped - full[3:12, 7:19]).mean()
    assert same < 0.5 * shifted
    with pytest.raises(libppm.InvalidArgumentError, match="crop window"):
        scene.create_renderer(width=24, height=18, crop=(0, 0, 25, 5))
    with pytest.raises(ValueError, match="camera crop"):
        scene.create_renderer(crop=(0, 0, 5))
    scene.close()
