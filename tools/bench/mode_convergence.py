#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Error against pass count and against time of the renderer's modes on one scene, against an
independent reference image (e.g. Mitsuba 3's path tracer through tools/validate/to_mitsuba.py).

For each mode, one render of --passes passes; after passes 1, 2, 4, ... the RMSE
sqrt(mean((x - ref)^2)) and the relative MSE mean((x - ref)^2 / (ref^2 + 0.01)) over every
pixel and channel, with the wall time of the passes so far (the metric itself not counted).
Writes a CSV and a log-log chart (error against passes, error against seconds).

  python3 tools/validate/to_mitsuba.py examples/scenes/teapot-cornell.json \\
      --render ref.exr --spp 4096 --width 160 --height 120
  python3 tools/bench/mode_convergence.py --scene examples/scenes/teapot-cornell.json \\
      --reference ref.exr --passes 256 --photons 20000 --modes sppm,pppm \\
      --csv docs/bench/mode-convergence.csv --chart docs/bench/mode-convergence.png

Needs the libppm Python package, OpenImageIO's Python module or imageio for reading the
reference (python3-openimageio on Debian), and matplotlib for the chart.
"""
import argparse
import csv
import dataclasses
import math
import time

import numpy as np

import libppm


def read_exr(path):
    try:
        import OpenImageIO as oiio
        image = oiio.ImageInput.open(path)
        if image is None:
            raise SystemExit(f"{path}: {oiio.geterror()}")
        pixels = image.read_image(format="float")
        image.close()
        return np.asarray(pixels)[..., :3]
    except ImportError:
        import mitsuba as mi  # the reference came from Mitsuba: its Bitmap reads EXR
        mi.set_variant("scalar_rgb")
        return np.asarray(mi.Bitmap(path))[..., :3]


def metrics(image, reference):
    d = image.astype(np.float64) - reference
    return math.sqrt(np.mean(d * d)), float(np.mean(d * d / (reference * reference + 0.01)))


def run_mode(scene, mode, passes, settings, width, height, reference):
    with libppm.load(scene) as f:
        camera = dataclasses.replace(f.camera, width=width, height=height)
        renderer = libppm.Renderer(f.scene, camera, mode=mode, **settings)
        rows, elapsed, checkpoint = [], 0.0, 1
        for done in range(1, passes + 1):
            start = time.perf_counter()
            renderer.render_pass()
            elapsed += time.perf_counter() - start
            if done == checkpoint or done == passes:
                rmse, rel = metrics(renderer.image(), reference)
                rows.append(dict(mode=mode, passes=done, seconds=elapsed, rmse=rmse, relmse=rel))
                print(f"{mode:5s} {done:5d} passes {elapsed:8.2f} s  RMSE {rmse:.5f}  relMSE {rel:.3e}")
                checkpoint *= 2
        renderer.close()
    return rows


def chart(rows, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for mode in sorted({r["mode"] for r in rows}):
        mine = [r for r in rows if r["mode"] == mode]
        axes[0].loglog([r["passes"] for r in mine], [r["rmse"] for r in mine], "o-", label=mode)
        axes[1].loglog([r["seconds"] for r in mine], [r["rmse"] for r in mine], "o-", label=mode)
    axes[0].set_xlabel("passes")
    axes[1].set_xlabel("seconds (2 threads)")
    for ax in axes:
        ax.set_ylabel("RMSE against the reference")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scene", required=True)
    parser.add_argument("--reference", required=True, help="linear EXR of the same camera and size")
    parser.add_argument("--passes", type=int, default=64)
    parser.add_argument("--photons", type=int, default=20000)
    parser.add_argument("--modes", default="sppm,pppm")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="another render setting for every mode, repeatable")
    parser.add_argument("--csv")
    parser.add_argument("--chart")
    args = parser.parse_args()
    reference = read_exr(args.reference).astype(np.float64)
    height, width = reference.shape[:2]
    settings = {"photons_per_pass": args.photons}
    for item in args.set:
        key, value = item.split("=", 1)
        try:
            settings[key] = int(value)
        except ValueError:
            try:
                settings[key] = float(value)
            except ValueError:
                settings[key] = value
    rows = []
    for mode in args.modes.split(","):
        rows += run_mode(args.scene, mode, args.passes, settings, width, height, reference)
    if args.csv:
        with open(args.csv, "w", newline="") as out:
            writer = csv.DictWriter(out, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)
    if args.chart:
        chart(rows, args.chart, f"{args.scene.split('/')[-1]}, {width} x {height}, "
              f"{args.photons} photons per pass")


if __name__ == "__main__":
    main()
