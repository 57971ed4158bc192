#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Render every scene of the Mitsuba XML corpus (tests/data/mitsuba/*.xml) with Mitsuba 3 and
with libppm, unchanged, and print one table row per scene.

Each scene is rendered twice by each renderer (seeds 0 and 1). A row gives the image-mean
ratio libppm / Mitsuba per channel, the relative MSE mean((ours - mi)^2 / (mi^2 + 0.01)) and
its ratio to the relMSE that the two renderers' noise alone predicts (half the mean squared
difference of each renderer's two renders): near 1, the images differ by noise only. Not run
by CI (Mitsuba is a large download).

  compare_corpus.py [--spp 256] [--passes 64] [--res 64] [--only NAME ...]
                    [--ppm-render build/tools/render/ppm-render] [--variant scalar_rgb]

Mitsuba: `python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy`; run this script
with that Python.
"""
import argparse
import glob
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_xml import render_libppm, render_mitsuba, repository_root  # noqa: E402


def compare(scene, args, folder):
    defines = [("res", str(args.res)), ("spp", str(args.spp))]
    name = os.path.splitext(os.path.basename(scene))[0]
    ours = [render_libppm(args.ppm_render, scene, defines, args.passes, os.path.join(folder, f"{name}-{s}.exr"),
                          seed=s) for s in (0, 1)]
    theirs = [render_mitsuba(scene, defines, args.spp, args.variant, seed=s) for s in (0, 1)]
    if ours[0].shape != theirs[0].shape:
        return f"{name:28s} image sizes differ: libppm {ours[0].shape}, Mitsuba {theirs[0].shape}"
    weight = 1.0 / (theirs[0] ** 2 + 0.01)
    ratio = ours[0].mean(axis=(0, 1)) / theirs[0].mean(axis=(0, 1))
    rel_mse = ((ours[0] - theirs[0]) ** 2 * weight).mean()
    predicted = (0.5 * ((ours[0] - ours[1]) ** 2 + (theirs[0] - theirs[1]) ** 2) * weight).mean()
    return (f"{name:28s} {ratio[0]:.4f} {ratio[1]:.4f} {ratio[2]:.4f}   {rel_mse:.2e}   "
            f"{rel_mse / predicted:.3f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--spp", type=int, default=256)
    parser.add_argument("--passes", type=int, default=64)
    parser.add_argument("--res", type=int, default=64)
    parser.add_argument("--only", nargs="+", default=[], metavar="NAME")
    parser.add_argument("--variant", default="scalar_rgb")
    parser.add_argument("--ppm-render", default=os.path.join(repository_root(), "build/tools/render/ppm-render"))
    args = parser.parse_args()
    scenes = sorted(glob.glob(os.path.join(repository_root(), "tests/data/mitsuba/*.xml")))
    if args.only:
        scenes = [s for s in scenes if os.path.splitext(os.path.basename(s))[0] in args.only]
    if not scenes:
        sys.exit("no corpus scene matches")
    print(f"{args.res}x{args.res}, libppm {args.passes} passes (default mode), Mitsuba {args.variant} {args.spp} spp")
    print(f"{'scene':28s} {'mean ratio R G B':22s} relMSE     relMSE / noise")
    folder = tempfile.mkdtemp(prefix="ppm-corpus-")
    for scene in scenes:
        print(compare(scene, args, folder), flush=True)


if __name__ == "__main__":
    main()
