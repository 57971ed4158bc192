#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""A sphere of each dielectric-family material in a grey box under a small area light, rendered
by libppm (ppm-render, SPPM) and by Mitsuba 3's path tracer (the same JSON through
to_mitsuba.py); prints the per-channel ratios of the image means (libppm / Mitsuba), over the
whole image and over the sphere. The same box as the conductors' comparison.

  compare_dielectric_scenes.py [--only NAME ...] [--passes 64] [--photons 100000] [--spp 256]
                               [--size 64] [--keep DIR] [--ppm-render PATH]
Mitsuba: /tmp/mitsuba-venv/bin/python. Not run by CI.
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

CASES = {
    "thindielectric": {"type": "thindielectric"},
    "roughdielectric-beckmann-0.1": {"type": "roughdielectric"},
    "roughdielectric-ggx-0.3": {"type": "roughdielectric", "distribution": "ggx", "alpha": 0.3},
    "roughplastic-beckmann-0.1": {"type": "roughplastic", "diffuse_reflectance": [0.8, 0.4, 0.2]},
    "roughplastic-ggx-0.4": {"type": "roughplastic", "distribution": "ggx", "alpha": 0.4,
                             "diffuse_reflectance": [0.2, 0.5, 0.8]},
}


def scene(bsdf, size, passes, photons):
    def quad(origin, eu, ev, **extra):
        return dict({"type": "quad", "origin": origin, "edge_u": eu, "edge_v": ev, "bsdf": "grey"}, **extra)
    walls = [
        quad([-1, 0, -1], [0, 0, 4], [2, 0, 0]), quad([-1, 2, -1], [2, 0, 0], [0, 0, 4]),
        quad([-1, 0, -1], [2, 0, 0], [0, 2, 0]), quad([-1, 0, 3], [0, 2, 0], [2, 0, 0]),
        quad([-1, 0, -1], [0, 2, 0], [0, 0, 4]), quad([1, 0, -1], [0, 0, 4], [0, 2, 0]),
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
                  "black": {"type": "diffuse", "reflectance": 0.0}, "test": bsdf},
        "shapes": walls + [light, sphere],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--only", nargs="*")
    parser.add_argument("--passes", type=int, default=64)
    parser.add_argument("--photons", type=int, default=100000)
    parser.add_argument("--spp", type=int, default=256)
    parser.add_argument("--size", type=int, default=64)
    parser.add_argument("--keep", metavar="DIR")
    parser.add_argument("--ppm-render", default=os.path.join(REPO, "build", "tools", "render", "ppm-render"))
    args = parser.parse_args()
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    work = args.keep or tempfile.mkdtemp(prefix="compare-dielectrics-")
    os.makedirs(work, exist_ok=True)
    print(f"Mitsuba {mi.__version__}; {args.size}x{args.size}, libppm {args.passes} passes x {args.photons} "
          f"photons, Mitsuba path tracer {args.spp} spp")
    fmt = lambda v: "[" + ", ".join(f"{x:.4f}" for x in v) + "]"
    for name in args.only or list(CASES):
        path = os.path.join(work, name + ".json")
        with open(path, "w") as f:
            json.dump(scene(CASES[name], args.size, args.passes, args.photons), f, indent=1)
        ours, ref = os.path.join(work, name + "-ppm.exr"), os.path.join(work, name + "-mitsuba.exr")
        subprocess.run(["nice", "-n", "10", args.ppm_render, path, "-o", ours, "--quiet"], check=True)
        subprocess.run(["nice", "-n", "10", sys.executable, os.path.join(HERE, "to_mitsuba.py"), path,
                        "--render", ref, "--spp", str(args.spp)], check=True, stdout=subprocess.DEVNULL)
        a = np.array(mi.Bitmap(ours), dtype=np.float64)[:, :, :3]
        b = np.array(mi.Bitmap(ref), dtype=np.float64)[:, :, :3]
        s = args.size
        box = (slice(int(0.45 * s), int(0.85 * s)), slice(int(0.3 * s), int(0.7 * s)))  # on the sphere
        print(f"{name}: image ratio {fmt(a.mean(axis=(0, 1)) / b.mean(axis=(0, 1)))}, "
              f"sphere ratio {fmt(a[box].mean(axis=(0, 1)) / b[box].mean(axis=(0, 1)))}", flush=True)


if __name__ == "__main__":
    main()
