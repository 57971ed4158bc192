#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Area lights on meshes, disks and cylinders against Mitsuba 3.

Writes a Cornell-like box (diffuse walls, white / red / green) lit by one of
  mesh      an OBJ sphere mesh (UV sphere, 960 triangles, vertex normals) hanging under the
            ceiling (tests/area lights on meshes, with shading normals);
  disk      a `disk` light just under the ceiling, facing down;
  cylinder  a horizontal open `cylinder` light under the ceiling, emitting outwards;
as Mitsuba 3 XML files, renders each with ppm-render and with Mitsuba's path tracer from the
same file, and prints the per-channel image means of both and their ratio (ours / Mitsuba).
Not run by CI (Mitsuba is a big download).

  python3 tools/validate/compare_lights.py --ppm-render build/tools/render/ppm-render \
      --out /tmp/compare_lights [--size 96] [--spp 256] [--passes 64] [--only disk]

Needs Mitsuba 3 (`import mitsuba`, variant scalar_rgb) in the running Python.

Measured (Mitsuba 3.9.1 scalar_rgb, --size 96 --spp 1024 --passes 256, 3.5 minutes on 2 cores),
ours / Mitsuba per channel mean:
  cylinder  0.9987 0.9983 0.9984
  disk      1.0000 0.9999 1.0000
  mesh      1.0003 1.0003 1.0005
"""
import argparse
import math
import os
import subprocess
import sys

import numpy as np

BOX = """<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="{depth}"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <string name="fov_axis" value="x"/>
        <transform name="to_world"><lookat origin="0, 1, 3.6" target="0, 1, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="{spp}"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="{size}"/><integer name="height" value="{size}"/>
            <rfilter type="box"/>
        </film>
    </sensor>
    <bsdf type="twosided" id="white"><bsdf type="diffuse"><rgb name="reflectance" value="0.75, 0.75, 0.75"/></bsdf></bsdf>
    <bsdf type="twosided" id="red"><bsdf type="diffuse"><rgb name="reflectance" value="0.75, 0.2, 0.2"/></bsdf></bsdf>
    <bsdf type="twosided" id="green"><bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.6, 0.25"/></bsdf></bsdf>
    <bsdf type="twosided" id="black"><bsdf type="diffuse"><rgb name="reflectance" value="0, 0, 0"/></bsdf></bsdf>
    <!-- floor y = 0, ceiling y = 2, back z = -1, left x = -1, right x = 1 -->
    <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/></transform><ref id="white"/></shape>
    <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="90"/><translate y="2"/></transform><ref id="white"/></shape>
    <shape type="rectangle"><transform name="to_world"><translate y="1" z="-1"/></transform><ref id="white"/></shape>
    <shape type="rectangle"><transform name="to_world"><rotate y="1" angle="90"/><translate x="-1" y="1"/></transform><ref id="red"/></shape>
    <shape type="rectangle"><transform name="to_world"><rotate y="1" angle="-90"/><translate x="1" y="1"/></transform><ref id="green"/></shape>
    <shape type="sphere"><point name="center" x="-0.35" y="0.35" z="-0.2"/><float name="radius" value="0.35"/><ref id="white"/></shape>
{light}
</scene>
"""

LIGHTS = {
    "mesh": """    <shape type="obj">
        <string name="filename" value="sphere_light.obj"/>
        <transform name="to_world"><scale value="0.22"/><translate x="0.3" y="1.55" z="0"/></transform>
        <ref id="black"/>
        <emitter type="area"><rgb name="radiance" value="6, 5, 4"/></emitter>
    </shape>""",
    "disk": """    <shape type="disk">
        <transform name="to_world"><scale value="0.35"/><rotate x="1" angle="90"/><translate y="1.98"/></transform>
        <ref id="black"/>
        <emitter type="area"><rgb name="radiance" value="8, 7, 5"/></emitter>
    </shape>""",
    "cylinder": """    <shape type="cylinder">
        <point name="p0" x="-0.5" y="1.7" z="0"/>
        <point name="p1" x="0.5" y="1.7" z="0"/>
        <float name="radius" value="0.06"/>
        <ref id="black"/>
        <emitter type="area"><rgb name="radiance" value="10, 9, 7"/></emitter>
    </shape>""",
}


def write_sphere_obj(path, rings=16, segments=32):
    """A UV sphere of radius 1 with outward vertex normals; 2 * 16 * 32 - 64 = 960 triangles."""
    lines, index = [], {}
    for i in range(rings + 1):
        for j in range(segments + 1):
            theta, phi = math.pi * i / rings, 2 * math.pi * j / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            lines.append("v %.9f %.9f %.9f" % n)
            lines.append("vn %.9f %.9f %.9f" % n)
            index[i, j] = len(index) + 1
    for i in range(rings):
        for j in range(segments):
            a, b, c, d = index[i, j], index[i + 1, j], index[i + 1, j + 1], index[i, j + 1]
            # (theta down, phi around) with y up and phi from +x towards +z: a, d, b is outward.
            if i > 0:
                lines.append("f %d//%d %d//%d %d//%d" % (a, a, d, d, b, b))
            if i + 1 < rings:
                lines.append("f %d//%d %d//%d %d//%d" % (d, d, c, c, b, b))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def read_exr(mi, path):
    return np.array(mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, False))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ppm-render", required=True)
    ap.add_argument("--out", default="/tmp/compare_lights")
    ap.add_argument("--size", type=int, default=96)
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--passes", type=int, default=64)
    ap.add_argument("--photons", type=int, default=100000)
    ap.add_argument("--depth", type=int, default=8, help="Mitsuba's max_depth (ours: one less)")
    ap.add_argument("--only", choices=sorted(LIGHTS), action="append")
    args = ap.parse_args()

    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    os.makedirs(args.out, exist_ok=True)
    write_sphere_obj(os.path.join(args.out, "sphere_light.obj"))
    worst = 0.0
    for name in args.only or sorted(LIGHTS):
        xml = os.path.join(args.out, name + ".xml")
        with open(xml, "w") as f:
            f.write(BOX.format(depth=args.depth, spp=args.spp, size=args.size, light=LIGHTS[name]))
        ours_path, theirs_path = os.path.join(args.out, name + "_ppm.exr"), os.path.join(args.out, name + "_mi.exr")
        subprocess.run([args.ppm_render, xml, "-o", ours_path, "--passes", str(args.passes), "--photons",
                        str(args.photons), "-q"], check=True)
        scene = mi.load_file(xml)
        mi.Bitmap(mi.render(scene, spp=args.spp)).write(theirs_path)
        ours, theirs = read_exr(mi, ours_path), read_exr(mi, theirs_path)
        m_ours, m_theirs = ours.reshape(-1, 3).mean(0), theirs.reshape(-1, 3).mean(0)
        ratio = m_ours / m_theirs
        worst = max(worst, float(np.max(np.abs(ratio - 1))))
        print("%-9s ours %s  mitsuba %s  ratio %s" % (name, np.round(m_ours, 5), np.round(m_theirs, 5),
                                                       np.round(ratio, 4)), flush=True)
    print("largest deviation of a channel mean: %.2f %%" % (100 * worst))
    return 0 if worst <= 0.01 else 1


if __name__ == "__main__":
    sys.exit(main())
