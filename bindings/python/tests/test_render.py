# SPDX-License-Identifier: Apache-2.0
"""The renderer: a diffuse plane under a point light against the closed form, settings,
layers, progress, cancellation."""
import math
import threading

import numpy as np
import pytest

import libppm

RHO, HEIGHT, INTENSITY, CAMERA_HEIGHT, FOV, SIZE = 0.8, 1.0, 2.0, 3.0, 60.0, 33


def plane_under_point_light(context=None):
    """Plane z = 0 (4 x 4, diffuse RHO), point light at HEIGHT over the origin."""
    scene = libppm.Scene(context)
    white = scene.add_diffuse_material(RHO)
    scene.add_quad((-2, -2, 0), (4, 0, 0), (0, 4, 0), material=white)
    scene.add_point_light((0, 0, HEIGHT), INTENSITY)
    scene.commit()
    return scene


def camera(size=SIZE):
    return libppm.Camera(origin=(0, 0, CAMERA_HEIGHT), target=(0, 0, 0), up=(0, 1, 0), fov=FOV,
                      width=size, height=size)


def analytic_radiance(x, y):
    d2 = x * x + y * y + HEIGHT * HEIGHT
    return RHO / math.pi * INTENSITY * (HEIGHT / math.sqrt(d2)) / d2


def pixel_average(px, py, size=SIZE, samples=8):
    """Mean analytic radiance over pixel (px, py) (x right, y down), as the jittered
    camera samples it. Mitsuba's frame looking down -z with up +y has left = -x."""
    tan = math.tan(math.radians(FOV) / 2)
    total = 0.0
    for i in range(samples):
        for j in range(samples):
            fx, fy = px + (i + 0.5) / samples, py + (j + 0.5) / samples
            x = -(1 - 2 * fx / size) * tan * CAMERA_HEIGHT
            y = (1 - 2 * fy / size) * tan * CAMERA_HEIGHT
            total += analytic_radiance(x, y)
    return total / samples**2


@pytest.fixture(scope="module")
def plane():
    with plane_under_point_light() as s:
        yield s


def test_centre_pixel_by_shadow_rays(plane):
    # One jittered shadow-ray sample per pixel and pass. Off centre the radiance changes by up
    # to 20 % across a pixel, so a pixel's mean of n samples is off by ~6 %/sqrt(n) (1 sigma);
    # 256 passes make the 2 % below a 5-sigma bound. Photons add nothing here (one plane).
    with libppm.Renderer(plane, camera(), mode="sppm", photons_per_pass=1000, direct_lighting=1) as r:
        image = r.render(256)
        assert image.shape == (SIZE, SIZE, 3) and image.dtype == np.float32
        c = SIZE // 2
        expected = RHO / math.pi * INTENSITY / HEIGHT**2
        assert pixel_average(c, c) == pytest.approx(expected, rel=5e-3)  # the footprint
        np.testing.assert_allclose(image[c, c], pixel_average(c, c), rtol=0.01)
        # Off-centre pixels too, and in the right place (x right, y down).
        for px, py in ((4, 16), (16, 4), (8, 26)):
            np.testing.assert_allclose(image[py, px], pixel_average(px, py), rtol=0.02)


def test_photons_only_converge_to_the_same_answer(plane):
    with libppm.Renderer(plane, camera(), mode="sppm", photons_per_pass=50000, direct_lighting=0, seed=1) as r:
        image = r.render(16)
        c = SIZE // 2
        block = image[c - 4:c + 5, c - 4:c + 5].mean()
        expected = np.mean([pixel_average(x, y) for x in range(c - 4, c + 5) for y in range(c - 4, c + 5)])
        assert block == pytest.approx(expected, rel=0.06)
        assert r.photons_emitted == 16 * 50000


def test_layers_properties_and_settings(plane):
    with libppm.Renderer(plane, camera(16)) as r:
        assert r.get("mode") == "vcm"  # the default
    with libppm.Renderer(plane, camera(16), mode="sppm", photons_per_pass=1000) as r:
        assert (r.width, r.height, r.passes, r.photons_emitted) == (16, 16, 0, 0)
        assert not r.image().any()  # nothing rendered yet
        r.set("alpha", 0.5)
        r.set(max_depth=4, hit_point_search="grid", initial_radius_pixels=2)
        assert r.get("alpha") == 0.5 and r.get("max_depth") == 4
        assert r.get("hit_point_search") == "grid" and r.get("mode") == "sppm"
        assert r.get("initial_radius_pixels") == 2.0
        r.render_pass()
        assert r.passes == 1 and r.photons_emitted == 1000 and r.get("passes") == 1
        radius = r.layer("radius")
        assert radius.shape == (16, 16) and radius.dtype == np.float32 and (radius > 0).all()
        assert r.layer("photons").shape == (16, 16)
        assert r.get("last_photon_pass_seconds") >= 0
        with pytest.raises(libppm.InvalidOperationError, match="seed"):
            r.set(seed=3)  # fixed after the first pass
        with pytest.raises(libppm.InvalidArgumentError, match="alpha"):
            r.set(alpha=2.0)
        with pytest.raises(libppm.InvalidArgumentError, match="unknown render setting 'speed'"):
            r.get("speed")
        with pytest.raises(libppm.InvalidArgumentError):
            r.set(speed=1)
        with pytest.raises(TypeError):
            r.set(alpha=[0.5])
        with pytest.raises(libppm.InvalidArgumentError):
            r.layer("depth")


def test_camera_as_keyword_arguments(plane):
    with libppm.Renderer(plane, origin=(0, 0, CAMERA_HEIGHT), target=(0, 0, 0), fov=FOV, width=SIZE,
                      height=SIZE, photons_per_pass=1000) as a, \
            libppm.Renderer(plane, camera(), photons_per_pass=1000) as b, \
            libppm.Renderer(plane, camera(), width=7, photons_per_pass=1000) as c:
        assert np.array_equal(a.render(1), b.render(1))
        assert (c.width, c.height, c.camera.fov) == (7, SIZE, FOV)


def test_settings_at_creation_and_bad_cameras(plane):
    with pytest.raises(libppm.InvalidArgumentError, match="mode"):
        libppm.Renderer(plane, camera(), mode="bdpt")
    with pytest.raises(libppm.InvalidArgumentError):
        libppm.Renderer(plane, libppm.Camera(origin=(0, 0, 3), target=(0, 0, 3), width=8, height=8))
    with pytest.raises(ValueError, match="width"):
        libppm.Renderer(plane, libppm.Camera(width=-4))
    with pytest.raises(TypeError, match="camera"):
        libppm.Renderer(plane, {"fov": 40})
    with libppm.Scene() as uncommitted:
        uncommitted.add_sphere((0, 0, 0), 1)
        with pytest.raises(libppm.InvalidOperationError):
            libppm.Renderer(uncommitted, camera())


def test_same_image_for_any_thread_count():
    images = []
    for threads in (1, 2):
        with libppm.Context(threads=threads) as ctx, plane_under_point_light(ctx) as scene, \
                libppm.Renderer(scene, camera(12), photons_per_pass=2000, direct_lighting=0, seed=5) as r:
            images.append(r.render(2))
    assert np.array_equal(images[0], images[1])


def test_progress_callback_can_stop(plane):
    seen = []

    def progress(index, stats):
        seen.append((index, stats["passes"], stats["photons_emitted"]))
        assert stats["elapsed"] >= 0 and "last_eye_pass_seconds" in stats
        assert 0 <= stats["last_search_build_seconds"] <= stats["last_eye_pass_seconds"]
        return index < 2  # False after the third pass

    with libppm.Renderer(plane, camera(8), mode="sppm", photons_per_pass=500) as r:
        r.render(10, progress=progress)
        assert r.passes == 3
        assert seen == [(0, 1, 500), (1, 2, 1000), (2, 3, 1500)]
        r.render(2, progress=lambda i, s: None)  # None does not stop
        assert r.passes == 5


def test_cancel_before_a_pass(plane):
    with libppm.Renderer(plane, camera(8), photons_per_pass=500) as r:
        r.cancel()
        with pytest.raises(libppm.CancelledError):
            r.render_pass()
        assert r.passes == 0
        r.render_pass()
        assert r.passes == 1


def test_cancel_from_another_thread_stops_a_running_pass(plane):
    """render_pass releases the GIL: the main thread cancels while the pass runs. A pass of
    this size takes about a minute on 2 cores; if the GIL were held, cancel() would only
    come after it, the pass would complete (passes == 1) and raise nothing."""
    with libppm.Renderer(plane, camera(8), photons_per_pass=50_000_000) as r:
        errors = []
        started = threading.Event()

        def run():
            started.set()
            try:
                r.render_pass()
            except libppm.CancelledError as e:
                errors.append(e)

        worker = threading.Thread(target=run)
        worker.start()
        started.wait()
        r.cancel()
        worker.join()
        assert len(errors) == 1 and r.passes == 0


def test_time_limit(plane):
    with libppm.Renderer(plane, camera(8), photons_per_pass=1000) as r:
        r.render(1000, time_limit=0.0)
        assert r.passes == 1
