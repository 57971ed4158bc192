#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Render-farm scaling of libppm.distributed on a Dask LocalCluster, and a model of larger farms.

Measures, on this machine, for one scene:
  - the wall time of a render of P passes on 1 worker and on W workers (one libppm thread
    each, chunks of K passes), and the speed-up;
  - the per-chunk costs: loading the scene file (parsing, tessellation, BVH build) once per
    worker process, the time per pass, the partial's size in bytes per pixel, the driver's
    time to decode and merge one partial, and its time to rewrite the checkpoint and image
    (once per round of merges);
  - the same pass time, partial size and merge time at a target film size (default
    1920 x 1080), from one pass rendered here;
and from those a model of the speed-up on larger farms: with C = P / K chunks, each worker
renders ceil(C / W) chunks after one scene load, while the driver merges the C partials one
after the other and writes once per round of arrivals (a round merges every chunk that came
in during the previous round's write, so writes do not add up per chunk), so
    T(W) = max(load + ceil(C / W) K t_pass,  C t_merge) + t_merge + t_write
and S(W) = T(1) / T(W). The chunk size to choose is the smallest K whose chunks take well
over the merge time (K t_pass >> W t_merge keeps the driver from falling behind) while
C >> W keeps the workers busy until the end.

  python3 tools/bench/farm_scaling.py [--scene examples/scenes/teapot-cornell.json]
      [--passes 16] [--chunk 2] [--workers 2] [--photons 50000] [--target 1920x1080]

Needs the libppm Python package with Dask (pip install ".[dask]" from the repository root).
"""
import argparse
import dataclasses
import math
import os
import pathlib
import tempfile
import time

import libppm
import libppm.distributed

REPO = pathlib.Path(__file__).resolve().parents[2]


def timed(f, *args, **kwargs):
    start = time.perf_counter()
    result = f(*args, **kwargs)
    return time.perf_counter() - start, result


def farm_render(scene, passes, chunk, workers, settings, folder):
    from dask.distributed import Client, LocalCluster
    import logging
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                      dashboard_address=None, silence_logs=logging.ERROR) as cluster, \
            Client(cluster) as client:
        # Workers up and libppm imported before the clock starts, as on a running farm.
        client.run(lambda: __import__("libppm"))
        merges = []

        def note(partial, chunk_range):
            merges.append(time.perf_counter())

        seconds, image = timed(libppm.distributed.render, scene, passes=passes, chunk_passes=chunk,
                               client=client, output=os.path.join(folder, f"farm-{workers}.exr"),
                               checkpoint=os.path.join(folder, f"farm-{workers}.ppmpart"),
                               progress=False, callback=note, threads_per_task=1, **settings)
    return seconds, image


def pass_costs(scene, settings, width=None, height=None):
    """Scene load, one-thread pass time, partial bytes, merge + write time at a film size."""
    context = libppm.Context(threads=1)
    load_seconds, scene_file = timed(libppm.load, scene, context)
    camera = scene_file.camera
    if width:
        camera = dataclasses.replace(camera, width=width, height=height)
    renderer = libppm.Renderer(scene_file.scene, camera, mode="pppm", **settings)
    renderer.render_pass_index(0)  # the first pass also makes the film's slots
    pass_seconds, _ = timed(renderer.render_pass_index, 1)
    merged = renderer.partial()
    data = merged.to_bytes()
    other = libppm.Renderer(scene_file.scene, camera, mode="pppm", **settings)
    other.render_pass_index(2)
    incoming_bytes = other.partial().to_bytes()
    def merge():  # what the driver does per chunk
        incoming = libppm.Partial.from_bytes(incoming_bytes)
        merged.merge(incoming)
        incoming.close()
    merge_seconds, _ = timed(merge)
    with tempfile.TemporaryDirectory() as folder:
        def write():  # what the driver does per round of merges
            merged.save(os.path.join(folder, "checkpoint.ppmpart"))
            libppm.write_image(os.path.join(folder, "image.exr"), merged.image())
        write_seconds, _ = timed(write)
    pixels = camera.width * camera.height
    for obj in (merged, other, renderer, scene_file, context):
        obj.close()
    return dict(load=load_seconds, pass_seconds=pass_seconds, bytes_per_pixel=len(data) / pixels,
                merge=merge_seconds, write=write_seconds, width=camera.width, height=camera.height)


def model(costs, passes, chunk, workers):
    chunks = math.ceil(passes / chunk)
    t_chunk = chunk * costs["pass_seconds"]
    return max(costs["load"] + math.ceil(chunks / workers) * t_chunk, chunks * costs["merge"]) + \
        costs["merge"] + costs["write"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scene", default=str(REPO / "examples" / "scenes" / "teapot-cornell.json"))
    parser.add_argument("--passes", type=int, default=16)
    parser.add_argument("--chunk", type=int, default=2)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--photons", type=int, default=50000)
    parser.add_argument("--target", default="1920x1080")
    parser.add_argument("--model-passes", type=int, default=1024,
                        help="passes of the modelled large render (default 1024)")
    args = parser.parse_args()
    settings = {"photons_per_pass": args.photons}
    target_w, target_h = (int(v) for v in args.target.lower().split("x"))

    with tempfile.TemporaryDirectory() as folder:
        t1, image1 = farm_render(args.scene, args.passes, args.chunk, 1, settings, folder)
        tw, image_w = farm_render(args.scene, args.passes, args.chunk, args.workers, settings, folder)
    identical = (image1 == image_w).all()
    print(f"scene {os.path.basename(args.scene)}, {args.passes} passes of {args.photons} photons, "
          f"chunks of {args.chunk}")
    print(f"  1 worker: {t1:.2f} s; {args.workers} workers: {tw:.2f} s; speed-up {t1 / tw:.2f}; "
          f"images bit-identical: {bool(identical)}")

    here = pass_costs(args.scene, settings)
    big = pass_costs(args.scene, settings, target_w, target_h)
    for label, c in (("scene film", here), ("target film", big)):
        print(f"  {label} {c['width']} x {c['height']}: scene load + BVH {c['load']:.3f} s, "
              f"pass (1 thread) {c['pass_seconds']:.3f} s, partial {c['bytes_per_pixel']:.1f} "
              f"bytes/pixel ({c['bytes_per_pixel'] * c['width'] * c['height'] / 1e6:.1f} MB), "
              f"decode + merge {c['merge']:.3f} s, checkpoint + image write {c['write']:.3f} s")
    print(f"model, {target_w} x {target_h}, {args.model_passes} passes:")
    for chunk in (1, 4, 16, 64):
        t_one = model(big, args.model_passes, chunk, 1)
        row = ", ".join(f"{w} workers x{t_one / model(big, args.model_passes, chunk, w):.1f}"
                        for w in (2, 8, 64, 512))
        print(f"  chunks of {chunk:2d}: {row}")


if __name__ == "__main__":
    main()
