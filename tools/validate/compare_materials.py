#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Render small material test scenes with libppm (ppm-render on a JSON scene) and with
Mitsuba 3's path tracer (the same JSON translated by to_mitsuba.py), and print the per-channel
ratios of the image means (libppm / Mitsuba), over the whole image and over the object.

The scene: a closed grey box (diffuse 0.5, 2 x 2 x 4) lit by a small area light under the
ceiling, with a sphere of the material under test in the middle, seen from inside the box.
Each material family has its own function returning its cases (name -> bsdf object in the
JSON format, docs/scene-format.md), so other materials can be added beside the conductors.

Usage (Mitsuba: /tmp/mitsuba-venv/bin/python, or any Python with mitsuba and numpy):
  compare_materials.py [--only NAME ...] [--passes 256] [--photons 100000] [--spp 512]
                       [--size 64] [--keep DIR] [--ppm-render PATH]
Not run by CI (Mitsuba is a big download); the figures are in docs/how-it-works.md
("Glossy visible points"), e.g.
  compare_materials.py --only roughconductor-Al-ggx-0.3 --passes 128 --photons 100000 --spp 256
  roughconductor-Al-ggx-0.3: image ratio [0.9998, 0.9998, 0.9998], sphere ratio [0.9967, ...]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


# ---- the cases, one function per material family ---------------------------------------------

def conductor_cases():
    return {
        "conductor-Au": {"type": "conductor", "material": "Au"},
        "conductor-eta-k": {"type": "conductor", "eta": [0.2, 0.9, 1.1], "k": [3.9, 2.4, 2.2],
                            "specular_reflectance": [0.9, 0.8, 0.7]},
        # alpha 0.1 (Mitsuba's default) is below glossy_gather_alpha: continued like a mirror.
        "roughconductor-Cu-beckmann-0.1": {"type": "roughconductor", "material": "Cu"},
        # alpha 0.3: gathered at visible points.
        "roughconductor-Al-ggx-0.3": {"type": "roughconductor", "material": "Al", "distribution": "ggx",
                                      "alpha": 0.3},
        "roughconductor-Au-beckmann-0.5": {"type": "roughconductor", "material": "Au",
                                           "distribution": "beckmann", "alpha": 0.5},
    }


FAMILIES = [conductor_cases]


# ---- the scene --------------------------------------------------------------------------------

def scene(bsdf, size, passes, photons):
    def quad(origin, eu, ev, **extra):
        return dict({"type": "quad", "origin": origin, "edge_u": eu, "edge_v": ev, "bsdf": "grey"}, **extra)
    # Box x in [-1, 1], y in [0, 2], z in [-1, 3]; every normal points inwards.
    walls = [
        quad([-1, 0, -1], [0, 0, 4], [2, 0, 0]),   # floor, +y
        quad([-1, 2, -1], [2, 0, 0], [0, 0, 4]),   # ceiling, -y
        quad([-1, 0, -1], [2, 0, 0], [0, 2, 0]),   # back, +z
        quad([-1, 0, 3], [0, 2, 0], [2, 0, 0]),    # front, -z
        quad([-1, 0, -1], [0, 2, 0], [0, 0, 4]),   # left, +x
        quad([1, 0, -1], [0, 0, 4], [0, 2, 0]),    # right, -x
    ]
    light = quad([-0.25, 1.98, -0.25], [0.5, 0, 0], [0, 0, 0.5],
                 emitter={"type": "area", "radiance": [20, 20, 20]}, bsdf="black")
    sphere = {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "bsdf": "test"}
    return {
        "version": 1,
        "integrator": {"type": "sppm", "passes": passes, "photons_per_pass": photons, "max_depth": 16},
        "sensor": {"type": "perspective", "fov": 45,
                   "to_world": {"look_at": {"origin": [0, 1.0, 2.9], "target": [0, 0.6, 0], "up": [0, 1, 0]}},
                   "film": {"width": size, "height": size}},
        "bsdfs": {"grey": {"type": "diffuse", "reflectance": 0.5},
                  "black": {"type": "diffuse", "reflectance": 0.0},
                  "test": bsdf},
        "shapes": walls + [light, sphere],
    }


def read_exr(path):
    import mitsuba as mi
    return np.array(mi.Bitmap(path), dtype=np.float64)[:, :, :3]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--only", nargs="*", help="case names to run (default: all)")
    parser.add_argument("--passes", type=int, default=256)
    parser.add_argument("--photons", type=int, default=100000)
    parser.add_argument("--spp", type=int, default=512)
    parser.add_argument("--size", type=int, default=64)
    parser.add_argument("--keep", metavar="DIR", help="keep scenes and images in DIR")
    parser.add_argument("--ppm-render", default=os.path.join(REPO, "build", "tools", "render", "ppm-render"))
    args = parser.parse_args()

    cases = {}
    for family in FAMILIES:
        cases.update(family())
    names = args.only or list(cases)
    work = args.keep or tempfile.mkdtemp(prefix="compare-materials-")
    os.makedirs(work, exist_ok=True)
    import mitsuba as mi
    print(f"Mitsuba {mi.__version__}; {args.size}x{args.size}, libppm {args.passes} passes x {args.photons} "
          f"photons, Mitsuba path tracer {args.spp} spp")
    for name in names:
        path = os.path.join(work, name + ".json")
        with open(path, "w") as f:
            json.dump(scene(cases[name], args.size, args.passes, args.photons), f, indent=1)
        ours, ref = os.path.join(work, name + "-ppm.exr"), os.path.join(work, name + "-mitsuba.exr")
        subprocess.run([args.ppm_render, path, "-o", ours, "--quiet"], check=True)
        subprocess.run(["nice", "-n", "10", sys.executable, os.path.join(HERE, "to_mitsuba.py"), path,
                        "--render", ref, "--spp", str(args.spp)], check=True, stdout=subprocess.DEVNULL)
        a, b = read_exr(ours), read_exr(ref)
        s = args.size
        box = (slice(int(0.45 * s), int(0.85 * s)), slice(int(0.3 * s), int(0.7 * s)))  # on the sphere
        fmt = lambda v: "[" + ", ".join(f"{x:.4f}" for x in v) + "]"
        print(f"{name}: image ratio {fmt(a.mean(axis=(0, 1)) / b.mean(axis=(0, 1)))}, "
              f"sphere ratio {fmt(a[box].mean(axis=(0, 1)) / b[box].mean(axis=(0, 1)))} "
              f"(sphere means libppm {fmt(a[box].mean(axis=(0, 1)))}, mitsuba {fmt(b[box].mean(axis=(0, 1)))})",
              flush=True)


if __name__ == "__main__":
    main()
