#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Renders the Utah teapot in a Cornell-like box with progressive photon mapping and plots
the image error against render time.

The error is the relative RMS difference from a *reference render*: the same scene rendered
independently (another seed) for longer, so its own noise is below the curve for most of
the run; where the curve flattens it has reached the reference's noise. (Comparing against
the run's own final image would force the last point to zero.) The teapot is coated
(glazed porcelain) and the box is lit by an area light in the ceiling.

    python3 teapot_convergence.py                 # under 2 minutes on 2 cores
    python3 teapot_convergence.py --time 60 --reference-time 240 -o convergence.png

Writes the figure (image, error curve) to --output and prints the curve as a table.
"""
from __future__ import annotations

import argparse
import pathlib
import sys
from typing import Any, List, Mapping, Tuple

import numpy as np
import numpy.typing as npt

import libppm

REPO = pathlib.Path(__file__).resolve().parents[3]
TEAPOT = REPO / "tests" / "data" / "teapot.bpt"

Image = npt.NDArray[np.float32]


def build_scene(teapot_path: str) -> libppm.Scene:
    """A 10 x 10 x 10 box (z up, open towards -y) with red and green side walls, the teapot
    on the floor and a 3 x 3 area light under the ceiling."""
    scene = libppm.Scene()
    white = scene.add_diffuse_material(0.75)
    red = scene.add_diffuse_material((0.63, 0.065, 0.05))
    green = scene.add_diffuse_material((0.14, 0.45, 0.091))
    porcelain = scene.add_coated_material((0.75, 0.6, 0.35))
    s = 5.0
    scene.add_quad((-s, -s, 0), (2 * s, 0, 0), (0, 2 * s, 0), material=white)       # floor
    scene.add_quad((-s, -s, 2 * s), (2 * s, 0, 0), (0, 2 * s, 0), material=white)   # ceiling
    scene.add_quad((-s, s, 0), (2 * s, 0, 0), (0, 0, 2 * s), material=white)        # back
    scene.add_quad((-s, -s, 0), (0, 2 * s, 0), (0, 0, 2 * s), material=red)         # left
    scene.add_quad((s, -s, 0), (0, 2 * s, 0), (0, 0, 2 * s), material=green)        # right
    # edge_u x edge_v points down, into the box: the side that emits.
    light = scene.add_quad((-1.5, -1.5, 2 * s - 0.01), (0, 3, 0), (3, 0, 0), material=white)
    scene.set_emission(light, 12.0)
    teapot = scene.load_bpt(teapot_path, material=porcelain)
    # Turned a little towards the camera, scaled up, standing on the floor.
    angle = np.radians(-30)
    c, si, k = np.cos(angle), np.sin(angle), 1.3
    scene.set_transform(teapot, [[k * c, -k * si, 0, 0], [k * si, k * c, 0, 0.5], [0, 0, k, 0]])
    scene.commit()
    return scene


def make_renderer(scene: libppm.Scene, args: argparse.Namespace, seed: int) -> libppm.Renderer:
    camera = libppm.Camera(origin=(0, -19, 5), target=(0, 0, 4), up=(0, 0, 1), fov=38,
                        width=args.width, height=args.height)
    return libppm.Renderer(scene, camera, photons_per_pass=args.photons, seed=seed)


def relative_rms(image: Image, reference: Image) -> float:
    return float(np.sqrt(np.mean((image - reference) ** 2)) / np.mean(reference))


def run(scene: libppm.Scene,
        args: argparse.Namespace) -> Tuple[npt.NDArray[np.float64], Image, Image]:
    """The measured run: (seconds, passes, error) after each pass, and the final image."""
    reference = reference_image(scene, args)
    points: List[Tuple[float, int, float]] = []
    with make_renderer(scene, args, seed=1) as renderer:

        def record(index: int, stats: Mapping[str, Any]) -> None:
            # The clock includes reading the image and this error: about a millisecond.
            err = relative_rms(renderer.image(), reference)
            points.append((stats["elapsed"], stats["passes"], err))
            print(f"  {stats['elapsed']:7.2f} s  pass {stats['passes']:4d}  error {err:.4f}",
                  file=sys.stderr)

        image = renderer.render(args.max_passes, progress=record, time_limit=args.time)
    return np.array(points), image, reference


def reference_image(scene: libppm.Scene, args: argparse.Namespace) -> Image:
    if args.reference and pathlib.Path(args.reference).exists():
        print(f"reference: {args.reference}", file=sys.stderr)
        reference: Image = np.load(args.reference)
        return reference
    print(f"reference: {args.reference_time:g} s of rendering (seed 2) ...", file=sys.stderr)
    with make_renderer(scene, args, seed=2) as renderer:
        image = renderer.render(10**6, time_limit=args.reference_time)
        print(f"reference: {renderer.passes} passes, {renderer.photons_emitted:,} photons",
              file=sys.stderr)
    if args.reference:
        np.save(args.reference, image)
    return image


def to_srgb(image: Image) -> npt.NDArray[np.uint8]:
    """Exposure to the 99th percentile, sRGB transfer, 8-bit."""
    scaled = np.clip(image / np.percentile(image, 99), 0, 1)
    srgb = np.where(scaled <= 0.0031308, 12.92 * scaled, 1.055 * scaled ** (1 / 2.4) - 0.055)
    return (srgb * 255 + 0.5).astype(np.uint8)


def plot(points: npt.NDArray[np.float64], image: Image, args: argparse.Namespace) -> None:
    import matplotlib  # type: ignore[import-untyped, unused-ignore]
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # type: ignore[import-untyped, unused-ignore]

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2), gridspec_kw={"width_ratios": [1, 1.2]})
    left.imshow(to_srgb(image))
    left.set_title(f"{int(points[-1, 1])} passes, {points[-1, 0]:.0f} s")
    left.axis("off")
    seconds, errors = points[:, 0], points[:, 2]
    right.loglog(seconds, errors, "o-", ms=3, label="SPPM (alpha = 2/3)")
    # MSE ~ N^(-2/3) for alpha = 2/3: RMS error ~ time^(-1/3) at a constant pass rate.
    guide = errors[0] * (seconds / seconds[0]) ** (-1 / 3)
    right.loglog(seconds, guide, "--", color="grey", label="slope -1/3")
    right.set_xlabel("render time (s)")
    right.set_ylabel("relative RMS error vs reference")
    right.set_title(f"{args.width} x {args.height}, {args.photons:,} photons/pass; "
                    f"reference: {args.reference_time:g} s, other seed", fontsize=9)
    right.grid(True, which="both", alpha=0.3)
    right.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("-o", "--output", default="teapot_convergence.png", help="PNG to write")
    parser.add_argument("--time", type=float, default=20, help="seconds of the measured run")
    parser.add_argument("--reference-time", type=float, default=80,
                        help="seconds of the reference render")
    parser.add_argument("--reference", metavar="FILE.npy",
                        help="reuse this reference image if it exists, else save it there")
    parser.add_argument("--max-passes", type=int, default=10000, help="stop the run after these")
    parser.add_argument("--width", type=int, default=160)
    parser.add_argument("--height", type=int, default=120)
    parser.add_argument("--photons", type=int, default=50000, help="photons per pass")
    parser.add_argument("--threads", type=int, default=0, help="worker threads, 0 = all")
    parser.add_argument("--teapot", default=str(TEAPOT), help=".bpt file")
    args = parser.parse_args()

    libppm.default_context().threads = args.threads
    with build_scene(args.teapot) as scene:
        points, image, _ = run(scene, args)
    plot(points, image, args)
    print("seconds  passes  relative_rms_error")
    for seconds, passes, err in points:
        print(f"{seconds:7.2f}  {int(passes):6d}  {err:.5f}")
    print(f"wrote {args.output}", file=sys.stderr)


if __name__ == "__main__":
    main()
