#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Cross-check libppm against Mitsuba 3 on textures and layered materials.

Each scene is one Mitsuba XML file, read by both renderers: a plane under a point light seen
from above, with a checkerboard, a bitmap (nearest filter, clamp wrap), a blendbsdf of two
diffuse colours, and a black mask over the lit plane. Prints the per-channel ratio of the
image means (libppm / Mitsuba). libppm through ctypes over libppm.so, Mitsuba 3 (`scalar_rgb`
or `llvm_ad_rgb`) through `import mitsuba`. Not run by CI: Mitsuba is a big download.

  /tmp/mitsuba-venv/bin/python tools/validate/compare_textures.py --lib build/lib/libppm.so
"""
import argparse
import ctypes as C
import os
import sys
import tempfile

import numpy as np

SIZE = 64

HEAD = """<scene version="3.0.0">
 <integrator type="path"><integer name="max_depth" value="8"/></integrator>
 <sensor type="perspective"><float name="fov" value="60"/>
  <transform name="to_world"><lookat origin="0, 0, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
  <sampler type="independent"><integer name="sample_count" value="{spp}"/></sampler>
  <film type="hdrfilm"><integer name="width" value="{size}"/><integer name="height" value="{size}"/>
   <rfilter type="box"/></film></sensor>
 <emitter type="point"><point name="position" x="0" y="0" z="1"/><rgb name="intensity" value="2, 2, 2"/></emitter>
"""
PLANE = """ <shape type="rectangle"><transform name="to_world"><scale value="2"/></transform>
  {bsdf}</shape>
"""

SCENES = {
    "checkerboard": PLANE.format(bsdf="""<bsdf type="diffuse"><texture type="checkerboard" name="reflectance">
   <rgb name="color0" value="0.8, 0.3, 0.1"/><rgb name="color1" value="0.1, 0.4, 0.7"/>
   <transform name="to_uv"><scale x="4" y="4"/></transform></texture></bsdf>"""),
    "bitmap_nearest_clamp": PLANE.format(bsdf="""<bsdf type="diffuse"><texture type="bitmap" name="reflectance">
   <string name="filename" value="{png}"/><string name="filter_type" value="nearest"/>
   <string name="wrap_mode" value="clamp"/>
   <transform name="to_uv"><translate x="-0.25" y="-0.25"/><scale x="1.5" y="1.5"/></transform></texture></bsdf>"""),
    "blendbsdf": PLANE.format(bsdf="""<bsdf type="blendbsdf"><float name="weight" value="0.3"/>
   <bsdf type="diffuse" name="bsdf_0"><rgb name="reflectance" value="0.8, 0.2, 0.1"/></bsdf>
   <bsdf type="diffuse" name="bsdf_1"><rgb name="reflectance" value="0.1, 0.4, 0.9"/></bsdf></bsdf>"""),
    "mask": PLANE.format(bsdf="""<bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.5, 0.3"/></bsdf>""")
    + """ <shape type="rectangle"><transform name="to_world"><scale value="2"/><translate z="1.5"/></transform>
  <bsdf type="mask"><float name="opacity" value="0.4"/>
   <bsdf type="diffuse"><rgb name="reflectance" value="0, 0, 0"/></bsdf></bsdf></shape>
""",
}


def write_png(path):
    """A 4 x 4 8-bit image of distinct colours."""
    import mitsuba as mi
    rng = np.random.default_rng(7)
    pixels = rng.integers(20, 250, size=(4, 4, 3)).astype(np.uint8)
    mi.Bitmap(pixels, mi.Bitmap.PixelFormat.RGB).write(path)


def render_libppm(lib, path, passes, photons):
    ppm = C.CDLL(lib)
    ppm.ppm_last_error_message.restype = C.c_char_p
    ctx, file, renderer = C.c_void_p(), C.c_void_p(), C.c_void_p()

    def check(status):
        if status != 0:
            sys.exit("libppm: " + ppm.ppm_last_error_message().decode())

    check(ppm.ppm_context_create(C.byref(ctx)))
    check(ppm.ppm_scene_file_load(ctx, path.encode(), C.byref(file)))
    check(ppm.ppm_scene_file_create_renderer(file, C.byref(renderer)))
    check(ppm.ppm_renderer_set_int(renderer, b"photons_per_pass", C.c_int64(photons)))
    for _ in range(passes):
        check(ppm.ppm_renderer_render_pass(renderer))
    rgb = (C.c_float * (SIZE * SIZE * 3))()
    check(ppm.ppm_renderer_get_layer(renderer, b"radiance", rgb, C.c_size_t(SIZE * SIZE * 3)))
    ppm.ppm_renderer_release(renderer)
    ppm.ppm_scene_file_release(file)
    ppm.ppm_context_release(ctx)
    return np.frombuffer(rgb, dtype=np.float32).reshape(SIZE, SIZE, 3).astype(np.float64)


def render_mitsuba(path):
    import mitsuba as mi
    return np.array(mi.render(mi.load_file(path)), dtype=np.float64)[:, :, :3]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lib", default="build/lib/libppm.so")
    parser.add_argument("--spp", type=int, default=256, help="Mitsuba samples per pixel")
    parser.add_argument("--passes", type=int, default=64, help="libppm passes")
    parser.add_argument("--photons", type=int, default=20000, help="libppm photons per pass")
    parser.add_argument("--only", help="one scene name")
    parser.add_argument("--keep", help="folder to write the scenes and images to")
    args = parser.parse_args()
    import mitsuba as mi
    for variant in ("scalar_rgb", "llvm_ad_rgb"):
        try:
            mi.set_variant(variant)
            break
        except Exception:  # pragma: no cover
            continue
    folder = args.keep or tempfile.mkdtemp(prefix="ppm-compare-textures-")
    os.makedirs(folder, exist_ok=True)
    png = os.path.join(folder, "texels.png")
    write_png(png)
    worst = 0.0
    for name, body in SCENES.items():
        if args.only and name != args.only:
            continue
        path = os.path.join(folder, name + ".xml")
        with open(path, "w") as f:
            f.write(HEAD.format(spp=args.spp, size=SIZE) + body.replace("{png}", png) + "</scene>\n")
        ours = render_libppm(os.path.abspath(args.lib), path, args.passes, args.photons)
        theirs = render_mitsuba(path)
        if args.keep:
            np.save(os.path.join(folder, name + "_libppm.npy"), ours)
            np.save(os.path.join(folder, name + "_mitsuba.npy"), theirs)
        ratio = ours.mean(axis=(0, 1)) / theirs.mean(axis=(0, 1))
        worst = max(worst, float(np.max(np.abs(ratio - 1))))
        # Pixel by pixel, on 4 x 4 blocks (less noise): RMS difference relative to the mean.
        blocks = [im.reshape(SIZE // 4, 4, SIZE // 4, 4, 3).mean(axis=(1, 3)) for im in (ours, theirs)]
        rms = np.sqrt(np.mean((blocks[0] - blocks[1]) ** 2)) / theirs.mean()
        print(f"{name:22s} mean ratio libppm / Mitsuba  r {ratio[0]:.4f}  g {ratio[1]:.4f}  b {ratio[2]:.4f}"
              f"   4x4-block rms {100 * rms:.2f} %")
    print(f"largest deviation {100 * worst:.2f} %")


if __name__ == "__main__":
    main()
