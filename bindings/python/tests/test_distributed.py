# SPDX-License-Identifier: Apache-2.0
"""Render farms: chunks of passes on Dask (2 worker processes) and Ray, merged into the same
bits as one process rendering all passes; a killed worker, a stopped and resumed driver and
foreign partials. Skipped (with the reason) where an engine cannot be imported."""
import logging
import os
import pathlib
import signal
import time

import numpy as np
import pytest

import libppm
import libppm.distributed

REPO = pathlib.Path(__file__).resolve().parents[3]
SCENE = REPO / "tests" / "data" / "scenes" / "small_box.json"
PASSES = 8
SETTINGS = {"photons_per_pass": 3000}


def single_process_image(passes=PASSES, **settings):
    with libppm.load(SCENE) as f:
        renderer = f.create_renderer(**{"mode": "pppm", **SETTINGS, **settings})
        for _ in range(passes):
            renderer.render_pass()
        return renderer.image()


@pytest.fixture(scope="module")
def reference():
    return single_process_image()


@pytest.fixture(scope="module")
def dask_client():
    distributed = pytest.importorskip("dask.distributed", reason="dask[distributed] is not installed")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=logging.ERROR)
    client = distributed.Client(cluster)
    yield client
    client.close()
    cluster.close()


def test_partials_merge_exactly_without_an_engine(tmp_path, reference):
    parts = [libppm.Partial.from_bytes(libppm.distributed.render_chunk(SCENE, a, b, SETTINGS, PASSES))
             for a, b in [(5, 8), (0, 2), (2, 5)]]
    merged = parts[0].merge(parts[1]).merge(parts[2])
    assert merged.passes == [(0, PASSES)] and merged.missing() == []
    np.testing.assert_array_equal(merged.image(), reference)
    assert reference.sum() > 0
    merged.save(tmp_path / "all.ppmpart")
    again = libppm.Partial.load(tmp_path / "all.ppmpart")
    assert again.to_bytes() == merged.to_bytes()


def test_vcm_chunks_merge_exactly(dask_client):
    """The bidirectional modes are pass-independent too: chunks on the engine give the bits
    of one process."""
    expected = single_process_image(mode="vcm")
    image = libppm.distributed.render(SCENE, passes=PASSES, chunk_passes=3, client=dask_client, progress=False,
                                      mode="vcm", **SETTINGS)
    np.testing.assert_array_equal(image, expected)
    assert expected.sum() > 0


def test_merge_refuses_foreign_and_overlapping_partials():
    a = libppm.Partial.from_bytes(libppm.distributed.render_chunk(SCENE, 0, 2, SETTINGS, 4))
    overlapping = libppm.Partial.from_bytes(libppm.distributed.render_chunk(SCENE, 1, 3, SETTINGS, 4))
    foreign = libppm.Partial.from_bytes(
        libppm.distributed.render_chunk(SCENE, 2, 4, {**SETTINGS, "seed": 99}, 4))
    with pytest.raises(libppm.InvalidArgumentError, match="both hold pass 1"):
        a.merge(overlapping)
    with pytest.raises(libppm.InvalidArgumentError, match="seed is 99"):
        a.merge(foreign)
    assert a.passes == [(0, 2)] and a.missing() == [(2, 4)]
    with pytest.raises(libppm.ParseError, match="not a libppm partial render"):
        libppm.Partial.from_bytes(b"not a partial render at all")


def test_dask_merged_image_equals_one_process(tmp_path, dask_client, reference):
    output = tmp_path / "image.exr"
    image = libppm.distributed.render(SCENE, passes=PASSES, chunk_passes=3, client=dask_client,
                                      output=output, checkpoint=tmp_path / "image.ppmpart",
                                      progress=False, **SETTINGS)
    np.testing.assert_array_equal(image, reference)
    assert output.stat().st_size > 0
    assert libppm.Partial.load(tmp_path / "image.ppmpart").passes == [(0, PASSES)]


def test_dask_killed_worker_changes_nothing(tmp_path, dask_client, reference):
    killed = []

    def kill_a_worker(partial, chunk):
        if not killed:  # after the first merge, while other chunks run
            pids = dask_client.run(os.getpid)
            victim = sorted(pids.values())[0]
            os.kill(victim, signal.SIGKILL)
            killed.append(victim)

    image = libppm.distributed.render(SCENE, passes=PASSES, chunk_passes=1, client=dask_client,
                                      progress=False, callback=kill_a_worker, **SETTINGS)
    assert killed
    np.testing.assert_array_equal(image, reference)
    # The nanny restarts the worker; wait so that later tests have two again.
    dask_client.wait_for_workers(2, timeout=60)


def test_dask_driver_stopped_and_resumed(tmp_path, dask_client, reference):
    checkpoint = tmp_path / "resume.ppmpart"
    first_run = []

    def stop_after_two(partial, chunk):
        first_run.append(chunk)
        return len(first_run) < 2

    partial_image = libppm.distributed.render(SCENE, passes=PASSES, chunk_passes=2, client=dask_client,
                                              checkpoint=checkpoint, progress=False,
                                              callback=stop_after_two, **SETTINGS)
    held = libppm.Partial.load(checkpoint)
    assert held.pass_count == 4 and partial_image.sum() > 0
    second_run = []
    image = libppm.distributed.render(SCENE, passes=PASSES, chunk_passes=2, client=dask_client,
                                      checkpoint=checkpoint, progress=False,
                                      callback=lambda p, c: second_run.append(c), **SETTINGS)
    np.testing.assert_array_equal(image, reference)
    # Only the passes the checkpoint lacked were rendered again.
    assert sum(e - f for f, e in second_run) == PASSES - 4
    assert not set(range(PASSES)).difference(p for f, e in first_run + second_run for p in range(f, e))


def test_dask_resume_refuses_another_renders_checkpoint(tmp_path, dask_client):
    checkpoint = tmp_path / "other.ppmpart"
    libppm.Partial.from_bytes(
        libppm.distributed.render_chunk(SCENE, 0, 1, {**SETTINGS, "seed": 5}, PASSES)).save(checkpoint)
    with pytest.raises(libppm.InvalidArgumentError, match="seed"):
        libppm.distributed.render(SCENE, passes=PASSES, chunk_passes=4, client=dask_client,
                                  checkpoint=checkpoint, progress=False, **SETTINGS)


def test_argument_errors(dask_client, tmp_path):
    with pytest.raises(ValueError, match="either client"):
        libppm.distributed.render(SCENE, passes=2)
    with pytest.raises(ValueError, match="pass-independent mode"):
        libppm.distributed.render(SCENE, passes=2, client=dask_client, mode="sppm")
    with pytest.raises(libppm.InvalidArgumentError, match="cannot write this format"):
        libppm.distributed.render(SCENE, passes=2, client=dask_client, output=tmp_path / "x.nope")
    with pytest.raises(FileNotFoundError):
        libppm.distributed.render(tmp_path / "missing.json", passes=2, client=dask_client)


def test_ray_merged_image_equals_one_process(tmp_path, reference):
    ray = pytest.importorskip("ray", reason="ray is not installed")
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        image = libppm.distributed.render(SCENE, passes=PASSES, chunk_passes=3, ray=True,
                                          output=tmp_path / "ray.png", progress=False, **SETTINGS)
    finally:
        ray.shutdown()
    np.testing.assert_array_equal(image, reference)
    assert (tmp_path / "ray.png").stat().st_size > 0
