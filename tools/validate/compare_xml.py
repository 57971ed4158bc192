#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Render one Mitsuba 3 XML scene file with Mitsuba 3 and with libppm, unchanged, and compare.

Both renderers read the same file: Mitsuba with `mitsuba.load_file`, libppm with ppm-render.
Prints each image's per-channel mean, their ratio (libppm / Mitsuba) and the relative MSE
mean((ours - mi)^2 / (mi^2 + 0.01)) per channel, as tools/validate/to_mitsuba.py does for
JSON scenes. Not run by CI (Mitsuba is a large download).

  compare_xml.py SCENE.xml [-D name=value ...] [--spp 256] [--passes 64] [--noise]
                 [--ppm-render build/tools/render/ppm-render] [--keep DIR]

Mitsuba: `python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy`; run this script
with that Python. --spp sets Mitsuba's samples per pixel (the sampler's sample_count),
--passes libppm's passes. The scene's `$name` parameters go to both (-D), e.g. -D res=128
for a scene whose film size is `$res`.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np


def repository_root():
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def render_mitsuba(scene_path, defines, spp, variant, seed=0):
    import mitsuba as mi
    mi.set_variant(variant)
    scene = mi.load_file(scene_path, **dict(defines))
    return np.array(mi.render(scene, spp=spp, seed=seed), dtype=np.float64)[..., :3]


def render_libppm(ppm_render, scene_path, defines, passes, out, seed=0):
    command = [ppm_render, scene_path, "-o", out, "--passes", str(passes), "--quiet", "--seed", str(seed)]
    for name, value in defines:
        command += ["-D", f"{name}={value}"]
    subprocess.run(command, check=True)
    import mitsuba as mi
    return np.array(mi.Bitmap(out), dtype=np.float64)[..., :3]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene")
    parser.add_argument("-D", dest="defines", action="append", default=[], metavar="NAME=VALUE")
    parser.add_argument("--spp", type=int, default=256)
    parser.add_argument("--passes", type=int, default=64)
    parser.add_argument("--variant", default="scalar_rgb")
    parser.add_argument("--ppm-render", default=os.path.join(repository_root(), "build/tools/render/ppm-render"))
    parser.add_argument("--keep", help="folder to keep both EXRs in (ours.exr, mitsuba.exr)")
    parser.add_argument("--noise", action="store_true",
                        help="render each a second time with another seed and compare the relative MSE "
                             "with what the two renderers' noise predicts")
    args = parser.parse_args()
    defines = []
    for d in args.defines:
        name, sep, value = d.partition("=")
        if not sep:
            parser.error(f"-D {d}: expected NAME=VALUE")
        defines.append((name, value))

    folder = args.keep or tempfile.mkdtemp(prefix="ppm-compare-")
    os.makedirs(folder, exist_ok=True)
    ours = render_libppm(args.ppm_render, args.scene, defines, args.passes, os.path.join(folder, "ours.exr"))
    theirs = render_mitsuba(args.scene, defines, args.spp, args.variant)
    if args.keep:
        import mitsuba as mi
        mi.Bitmap(theirs.astype(np.float32)).write(os.path.join(folder, "mitsuba.exr"))
    if ours.shape != theirs.shape:
        sys.exit(f"image sizes differ: libppm {ours.shape}, Mitsuba {theirs.shape}")
    mean_ours, mean_mi = ours.mean(axis=(0, 1)), theirs.mean(axis=(0, 1))
    rel_mse = ((ours - theirs) ** 2 / (theirs ** 2 + 0.01)).mean(axis=(0, 1))
    print(f"scene: {args.scene} ({ours.shape[1]}x{ours.shape[0]}, libppm {args.passes} passes, "
          f"Mitsuba {args.spp} spp)")
    for k, channel in enumerate("RGB"):
        print(f"  {channel}: libppm {mean_ours[k]:.5f}  Mitsuba {mean_mi[k]:.5f}  "
              f"ratio {mean_ours[k] / mean_mi[k]:.4f}  relMSE {rel_mse[k]:.2e}")
    print(f"  mean over channels: ratio {mean_ours.mean() / mean_mi.mean():.4f}")
    if args.noise:
        # Independent noise adds: E[(a - b)^2] = Var a + Var b + bias^2, and each variance is
        # half the mean squared difference of two renders with other seeds. A measured relMSE
        # close to the predicted one leaves no room for a difference beyond the noise.
        ours2 = render_libppm(args.ppm_render, args.scene, defines, args.passes, os.path.join(folder, "ours2.exr"),
                              seed=1)
        theirs2 = render_mitsuba(args.scene, defines, args.spp, args.variant, seed=1)
        weight = 1.0 / (theirs ** 2 + 0.01)
        predicted = (0.5 * ((ours - ours2) ** 2 + (theirs - theirs2) ** 2) * weight).mean(axis=(0, 1))
        for k, channel in enumerate("RGB"):
            print(f"  {channel}: relMSE {rel_mse[k]:.2e}, predicted by the noise {predicted[k]:.2e}, "
                  f"ratio {rel_mse[k] / predicted[k]:.3f}")


if __name__ == "__main__":
    main()
