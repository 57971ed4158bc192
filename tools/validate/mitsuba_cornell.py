#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Cross-check libppm's renderer against Mitsuba 3's path tracer on a diffuse Cornell box.

Builds the same scene twice - through libppm's C API (ctypes over libppm.so) and as a Mitsuba 3
dictionary (`pip install mitsuba`) - renders both and prints the relative mean squared error
mean((a - b)^2 / (b^2 + 0.01)) per channel and the ratio of the image means. Not run by CI:
Mitsuba is a large download and the renders take a minute.

  python3 tools/validate/mitsuba_cornell.py --lib build/lib/libppm.so
"""
import argparse
import ctypes as C
import sys

import numpy as np

# (origin, edge_u, edge_v, rgb reflectance); normals edge_u x edge_v face the inside.
WALLS = [
    ((-1, -1, 0), (2, 0, 0), (0, 2, 0), (0.75, 0.75, 0.75)),   # floor, z = 0
    ((-1, -1, 2), (0, 2, 0), (2, 0, 0), (0.75, 0.75, 0.75)),   # ceiling, z = 2
    ((-1, 1, 0), (0, 0, 2), (2, 0, 0), (0.75, 0.75, 0.75)),    # back, y = 1
    ((-1, -1, 0), (0, 2, 0), (0, 0, 2), (0.75, 0.20, 0.20)),   # left, x = -1
    ((1, -1, 0), (0, 0, 2), (0, 2, 0), (0.20, 0.60, 0.25)),    # right, x = 1
    ((-0.5, -0.4, 0.5), (0, 0.5, 0), (0.6, 0, 0), (0.6, 0.6, 0.6)),  # a panel over the floor: a shadow
]
LIGHT = ((-0.3, -0.3, 1.99), (0, 0.6, 0), (0.6, 0, 0), (12.0, 12.0, 12.0))
CAMERA = dict(origin=(0, -3.6, 1), target=(0, 0, 1), up=(0, 0, 1), fov=40.0)


class Camera(C.Structure):
    _fields_ = [("origin", C.c_double * 3), ("target", C.c_double * 3), ("up", C.c_double * 3),
                ("fov", C.c_double), ("width", C.c_uint32), ("height", C.c_uint32),
                ("aperture_radius", C.c_double), ("focus_distance", C.c_double),
                ("near_clip", C.c_double)]


def vec(v):
    return (C.c_double * 3)(*v)


def render_libppm(lib_path, size, passes, photons):
    lib = C.CDLL(lib_path)
    lib.ppm_last_error_message.restype = C.c_char_p

    def check(status, what):
        if status != 0:
            sys.exit(f"{what}: {lib.ppm_last_error_message().decode()}")

    ctx, scene = C.c_void_p(), C.c_void_p()
    check(lib.ppm_context_create(C.byref(ctx)), "ppm_context_create")
    check(lib.ppm_scene_create(ctx, C.byref(scene)), "ppm_scene_create")
    for origin, eu, ev, rgb in WALLS + [LIGHT[:3] + ((0.0, 0.0, 0.0),)]:
        material, geom = C.c_uint32(), C.c_uint32()
        check(lib.ppm_scene_add_diffuse_material(scene, vec(rgb), C.byref(material)), "material")
        check(lib.ppm_scene_add_quad(scene, vec(origin), vec(eu), vec(ev), C.byref(geom)), "quad")
        check(lib.ppm_scene_set_geometry_material(scene, geom, material), "set material")
    check(lib.ppm_scene_set_geometry_emission(scene, C.c_uint32(len(WALLS)), vec(LIGHT[3])), "emission")
    check(lib.ppm_scene_commit(scene), "commit")
    cam = Camera(vec(CAMERA["origin"]), vec(CAMERA["target"]), vec(CAMERA["up"]), CAMERA["fov"],
                 size, size, 0.0, 0.0, 0.0)
    renderer = C.c_void_p()
    check(lib.ppm_renderer_create(scene, C.byref(cam), C.byref(renderer)), "renderer")
    check(lib.ppm_renderer_set_int(renderer, b"photons_per_pass", C.c_int64(photons)), "photons")
    for _ in range(passes):
        check(lib.ppm_renderer_render_pass(renderer), "pass")
    image = np.zeros((size, size, 3), dtype=np.float32)
    check(lib.ppm_renderer_get_layer(renderer, b"radiance", image.ctypes.data_as(C.POINTER(C.c_float)),
                                     C.c_size_t(image.size)), "layer")
    lib.ppm_renderer_release(renderer)
    lib.ppm_scene_release(scene)
    lib.ppm_context_release(ctx)
    return image


def render_mitsuba(size, spp):
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    T = mi.ScalarTransform4f

    def rectangle(origin, eu, ev):
        o, u, v = (np.array(x, dtype=float) for x in (origin, eu, ev))
        n = np.cross(u, v)
        n /= np.linalg.norm(n)
        m = np.identity(4)
        m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = u / 2, v / 2, n, o + (u + v) / 2
        return T(m.tolist())

    scene = {"type": "scene", "integrator": {"type": "path", "max_depth": 17},
             "sensor": {"type": "perspective", "fov": CAMERA["fov"], "fov_axis": "x", "near_clip": 1e-3,
                        "to_world": T().look_at(origin=CAMERA["origin"], target=CAMERA["target"],
                                                up=CAMERA["up"]),
                        "sampler": {"type": "independent", "sample_count": spp},
                        "film": {"type": "hdrfilm", "width": size, "height": size,
                                 "rfilter": {"type": "box"}}}}
    for i, (origin, eu, ev, rgb) in enumerate(WALLS):
        scene[f"wall{i}"] = {"type": "rectangle", "to_world": rectangle(origin, eu, ev),
                             "bsdf": {"type": "twosided", "bsdf": {"type": "diffuse",
                                      "reflectance": {"type": "rgb", "value": list(rgb)}}}}
    scene["light"] = {"type": "rectangle", "to_world": rectangle(*LIGHT[:3]),
                      "bsdf": {"type": "twosided", "bsdf": {"type": "diffuse",
                               "reflectance": {"type": "rgb", "value": [0.0, 0.0, 0.0]}}},
                      "emitter": {"type": "area", "radiance": {"type": "rgb", "value": list(LIGHT[3])}}}
    return np.array(mi.render(mi.load_dict(scene)), dtype=np.float32)[:, :, :3]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lib", default="build/lib/libppm.so")
    parser.add_argument("--size", type=int, default=64)
    parser.add_argument("--passes", type=int, default=200)
    parser.add_argument("--photons", type=int, default=100000)
    parser.add_argument("--spp", type=int, default=256)
    args = parser.parse_args()
    ours = render_libppm(args.lib, args.size, args.passes, args.photons)
    ref = render_mitsuba(args.size, args.spp)
    rel_mse = ((ours - ref) ** 2 / (ref ** 2 + 0.01)).mean(axis=(0, 1))
    print(f"image means: libppm {ours.mean(axis=(0, 1))}, mitsuba {ref.mean(axis=(0, 1))}")
    print(f"ratio of means (libppm / mitsuba): {ours.mean() / ref.mean():.4f}")
    print(f"relative MSE per channel: {rel_mse}")


if __name__ == "__main__":
    main()
