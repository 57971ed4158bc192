#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Translate a libppm JSON scene (docs/scene-format.md) into a Mitsuba 3 scene, render it with
Mitsuba's path tracer, and compare the result with libppm's render.

The format was made to map one to one onto `mitsuba.load_dict`: this script reads the same
keys with the same defaults (transforms as ordered operation lists, colours as a number, an
[r, g, b] array or {"type": "rgb"}), and builds:
  - sensor: `perspective` / `thinlens` with the same `to_world`, fov along x (`fov_axis: "x"`),
    `hdrfilm` with a box reconstruction filter, an `independent` sampler;
  - integrator: `path` with max_depth = ours + 1 (Mitsuba also counts the emitter);
  - bsdfs: `diffuse`, `conductor` and `roughconductor` (named `material` or `eta`/`k`),
    `dielectric`, `plastic` and `roughplastic` (with their `nonlinear`); the opaque ones wrapped in `twosided`, as libppm's are two-sided;
    `bitmap` textures with to_uv = translate(offset) scale(scale), bilinear, repeating;
  - emitters: `point`, `spot`, and `area` emitters on shapes;
  - shapes: `sphere`, `rectangle`, `obj`; a `quad` becomes a `rectangle` whose to_world
    maps [-1, 1]^2 onto the parallelogram; `bezier` patches are tessellated by `ppm-tess`
    (within 1e-4 of the patches' bounding-box diagonal; inline patches go through a temporary
    .bpt file; with `uv_rects` each patch is tessellated on its own so its texture
    coordinates can be mapped into its rectangle) and loaded as an `obj` with the shape's
    to_world.

Usage (Mitsuba: `python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy`):

  to_mitsuba.py SCENE.json --print                      # the load_dict dictionary
  to_mitsuba.py SCENE.json --render OUT.exr --spp 256   # render with Mitsuba (also OUT.png
                                                        # with --png)
  to_mitsuba.py SCENE.json --render OUT.exr --compare OURS.exr
                    # compare: per-channel image means of both, their ratio (ours / Mitsuba)
                    # and the relative MSE mean((ours - mi)^2 / (mi^2 + 0.01)) per channel
  to_mitsuba.py SCENE.json --compare OURS.exr --reference MI.exr   # compare two EXRs only

Spheres of radius >= 1e4 (smallppm's walls) are rendered as planes: see --flatten.
Options --width/--height (or --scale) change the film size, e.g. for a quick look; the
comparison needs both images at the same size (ppm-render SCENE -o OURS.exr at the same size).
--tess names the ppm-tess executable (default: build/tools/tess/ppm-tess beside this
script's repository, then build-*/tools/tess/ppm-tess, then PATH). --variant picks the
Mitsuba variant (default scalar_rgb, which renders on all cores; llvm_ad_rgb needs a libLLVM
that Mitsuba's JIT accepts, or it aborts the process).

Exit status: 0 ok, 1 usage error or invalid scene, 2 runtime error.
"""
import argparse
import glob
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class SceneError(Exception):
    """An invalid scene: the message names the key path."""


# ---- reading: JSON with comments, duplicate keys refused -------------------------------------

def strip_comments(text):
    """Blanks out // and /* */ comments outside strings, keeping line and column numbers."""
    out, i, n = list(text), 0, len(text)
    in_string = False
    while i < n:
        c = text[i]
        if in_string:
            if c == "\\":
                i += 2
                continue
            if c == '"':
                in_string = False
            i += 1
        elif c == '"':
            in_string = True
            i += 1
        elif text.startswith("//", i):
            while i < n and text[i] != "\n":
                out[i] = " "
                i += 1
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            if end < 0:
                raise SceneError("unterminated /* comment")
            for k in range(i, end + 2):
                if text[k] != "\n":
                    out[k] = " "
            i = end + 2
        else:
            i += 1
    return "".join(out)


def no_duplicates(pairs):
    result = {}
    for key, value in pairs:
        if key in result:
            raise SceneError(f"duplicate key '{key}'")
        result[key] = value
    return result


def read_scene(path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    try:
        return json.loads(strip_comments(text), object_pairs_hook=no_duplicates)
    except json.JSONDecodeError as e:
        raise SceneError(f"{path}:{e.lineno}:{e.colno}: {e.msg}") from None


# ---- values ---------------------------------------------------------------------------------

def check_keys(obj, allowed, where):
    if not isinstance(obj, dict):
        raise SceneError(f"{where}: expected an object")
    for key in obj:
        if key not in allowed:
            raise SceneError(f"{where}.{key}: unknown key")


def number(value, where):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise SceneError(f"{where}: expected a number")
    return float(value)


def vector3(value, where):
    if not isinstance(value, list) or len(value) != 3:
        raise SceneError(f"{where}: expected [x, y, z]")
    return [number(v, f"{where}[{k}]") for k, v in enumerate(value)]


def colour(value, where):
    """A number (grey), [r, g, b] or {"type": "rgb", "value": [r, g, b]} -> [r, g, b]."""
    if isinstance(value, dict):
        check_keys(value, {"type", "value"}, where)
        if value.get("type") != "rgb":
            raise SceneError(f"{where}.type: expected \"rgb\"")
        return vector3(value.get("value"), f"{where}.value")
    if isinstance(value, list):
        return vector3(value, where)
    return [number(value, where)] * 3


def rgb(value):
    return {"type": "rgb", "value": value}


# ---- transforms -----------------------------------------------------------------------------

def translate(t):
    m = np.identity(4)
    m[:3, 3] = t
    return m


def scale(s):
    return np.diag([s[0], s[1], s[2], 1.0])


def rotate(axis, degrees):
    a = np.asarray(axis, dtype=float)
    a /= np.linalg.norm(a)
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    x, y, z = a
    m = np.identity(4)
    m[:3, :3] = [[c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s],
                 [y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s],
                 [z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)]]
    return m


def look_at(origin, target, up):
    """Mitsuba's Transform4f.look_at: columns left, up', dir, origin."""
    o, t, u = (np.asarray(v, dtype=float) for v in (origin, target, up))
    d = t - o
    d /= np.linalg.norm(d)
    left = np.cross(u, d)
    left /= np.linalg.norm(left)
    new_up = np.cross(d, left)
    m = np.identity(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = left, new_up, d, o
    return m


def transform(value, where):
    """One operation object or a list of them, the first acting first -> a 4x4 matrix."""
    if value is None:
        return np.identity(4)
    ops = value if isinstance(value, list) else [value]
    m = np.identity(4)
    for k, op in enumerate(ops):
        w = f"{where}[{k}]" if isinstance(value, list) else where
        if not isinstance(op, dict) or len(op) != 1:
            raise SceneError(f"{w}: each operation object has exactly one key")
        (name, arg), = op.items()
        if name == "translate":
            step = translate(vector3(arg, f"{w}.translate"))
        elif name == "scale":
            s = vector3(arg, f"{w}.scale") if isinstance(arg, list) else [number(arg, f"{w}.scale")] * 3
            if 0 in s:
                raise SceneError(f"{w}.scale: must be non-zero")
            step = scale(s)
        elif name == "rotate":
            check_keys(arg, {"axis", "angle"}, f"{w}.rotate")
            step = rotate(vector3(arg["axis"], f"{w}.rotate.axis"), number(arg["angle"], f"{w}.rotate.angle"))
        elif name == "matrix":
            if not isinstance(arg, list) or len(arg) != 16:
                raise SceneError(f"{w}.matrix: expected 16 numbers")
            step = np.array([number(v, f"{w}.matrix[{i}]") for i, v in enumerate(arg)]).reshape(4, 4)
        elif name == "look_at":
            check_keys(arg, {"origin", "target", "up"}, f"{w}.look_at")
            step = look_at(vector3(arg["origin"], f"{w}.look_at.origin"),
                           vector3(arg["target"], f"{w}.look_at.target"),
                           vector3(arg.get("up", [0, 1, 0]), f"{w}.look_at.up"))
        else:
            raise SceneError(f"{w}.{name}: unknown transform operation")
        m = step @ m
    return m


# ---- the translation ------------------------------------------------------------------------

class Translator:
    def __init__(self, scene_path, tess, workdir, width=None, height=None, film_scale=None, spp=64,
                 flatten=1e4):
        self.path = os.path.abspath(scene_path)
        self.folder = os.path.dirname(self.path)
        self.tess = tess
        self.workdir = workdir
        self.width, self.height, self.film_scale, self.spp = width, height, film_scale, spp
        self.flatten = flatten
        self.camera_origin = np.zeros(3)

    def file(self, name):
        return name if os.path.isabs(name) else os.path.normpath(os.path.join(self.folder, name))

    def matrix(self, m):
        import mitsuba as mi
        return mi.ScalarTransform4f(m.tolist())

    def tangent_plane(self, centre, radius):
        """A huge sphere (smallppm's walls: radius 1e5) as the square tangent to it where it
        is nearest the camera, 2 radius / 100 wide: Mitsuba intersects spheres in single
        precision, which leaves blotches on such walls; over that square the sphere departs
        from its plane by radius / 20000."""
        d = self.camera_origin - centre
        n = d / np.linalg.norm(d)
        helper = np.array([1.0, 0, 0]) if abs(n[0]) < 0.9 else np.array([0, 1.0, 0])
        u = np.cross(n, helper)
        u /= np.linalg.norm(u)
        v = np.cross(n, u)
        half = radius / 100
        q = np.identity(4)
        q[:3, 0], q[:3, 1], q[:3, 2], q[:3, 3] = u * half, v * half, n, centre + n * radius
        return q

    def translate_scene(self):
        scene = read_scene(self.path)
        check_keys(scene, {"version", "integrator", "sensor", "bsdfs", "emitters", "shapes"}, "scene")
        if scene.get("version", 1) != 1:
            raise SceneError("version: only 1 exists")
        out = {"type": "scene", "integrator": self.integrator(scene.get("integrator", {})),
               "sensor": self.sensor(scene.get("sensor", {}))}
        self.bsdfs = {}
        for name, b in scene.get("bsdfs", {}).items():
            self.bsdfs[name] = self.bsdf(b, f"bsdfs.{name}")
        for k, e in enumerate(scene.get("emitters", [])):
            out[f"emitter_{k}"] = self.emitter(e, f"emitters[{k}]")
        shapes = scene.get("shapes")
        if not isinstance(shapes, list) or not shapes:
            raise SceneError("shapes: required, not empty")
        for k, s in enumerate(shapes):
            out[f"shape_{k}"] = self.shape(s, f"shapes[{k}]")
        return out

    def integrator(self, i):
        check_keys(i, {"type", "passes", "time", "photons_per_pass", "alpha", "initial_radius",
                       "initial_radius_pixels", "max_depth", "seed", "hit_point_search",
                       "direct_lighting"}, "integrator")
        return {"type": "path", "max_depth": int(i.get("max_depth", 16)) + 1}

    def sensor(self, s):
        check_keys(s, {"type", "fov", "to_world", "near_clip", "aperture_radius", "focus_distance", "film",
                       "principal_point_offset_x", "principal_point_offset_y"},
                   "sensor")
        kind = s.get("type", "perspective")
        if kind not in ("perspective", "thinlens"):
            raise SceneError("sensor.type: expected \"perspective\" or \"thinlens\"")
        to_world = transform(s.get("to_world"), "sensor.to_world")
        self.camera_origin = to_world[:3, 3]
        film = s.get("film", {})
        check_keys(film, {"width", "height", "rfilter"}, "sensor.film")
        rfilter = dict(film.get("rfilter", {"type": "box"}))  # the same names in both formats
        width, height = int(film.get("width", 768)), int(film.get("height", 576))
        if self.film_scale:
            width, height = max(1, round(width * self.film_scale)), max(1, round(height * self.film_scale))
        width, height = self.width or width, self.height or height
        out = {"type": kind, "fov": number(s.get("fov", 39.5978), "sensor.fov"), "fov_axis": "x",
               "near_clip": number(s.get("near_clip", 0.01), "sensor.near_clip"), "far_clip": 1e8,
               "to_world": self.matrix(to_world),
               "sampler": {"type": "independent", "sample_count": self.spp},
               "film": {"type": "hdrfilm", "width": width, "height": height, "pixel_format": "rgb",
                        "rfilter": rfilter}}
        for key in ("principal_point_offset_x", "principal_point_offset_y"):
            if key in s:
                out[key] = number(s[key], f"sensor.{key}")
        if kind == "thinlens":
            for key in ("aperture_radius", "focus_distance"):
                if key not in s:
                    raise SceneError(f"sensor.{key}: required for thinlens")
                out[key] = number(s[key], f"sensor.{key}")
        return out

    def texture_or_colour(self, value, where):
        if isinstance(value, dict) and value.get("type") == "bitmap":
            check_keys(value, {"type", "filename", "scale", "offset"}, where)
            sc = value.get("scale", 1)
            su, sv = (number(sc[0], where), number(sc[1], where)) if isinstance(sc, list) else (number(sc, where),) * 2
            ou, ov = (number(v, where) for v in value.get("offset", [0, 0]))
            to_uv = translate([ou, ov, 0]) @ scale([su, sv, 1])
            filename = self.file(value["filename"])
            if not os.path.exists(filename):
                raise SceneError(f"{where}.filename: no such file: {filename}")
            return {"type": "bitmap", "filename": filename, "filter_type": "bilinear",
                    "wrap_mode": "repeat", "to_uv": self.matrix(to_uv)}
        return rgb(colour(value, where))

    def bsdf(self, b, where):
        if isinstance(b, str):
            if b not in self.bsdfs:
                raise SceneError(f"{where}: no bsdf named '{b}'")
            return self.bsdfs[b]
        check_keys(b, {"type", "reflectance", "specular_reflectance", "material", "int_ior", "ext_ior",
                       "diffuse_reflectance", "nonlinear", "eta", "k", "distribution", "alpha", "alpha_u",
                       "alpha_v", "sample_visible"}, where)
        kind = b.get("type")
        if kind == "null":
            check_keys(b, {"type"}, where)
            return {"type": "null"}
        if kind == "diffuse":
            check_keys(b, {"type", "reflectance"}, where)
            inner = {"type": "diffuse", "reflectance": self.texture_or_colour(b.get("reflectance", 0.5),
                                                                             f"{where}.reflectance")}
        elif kind in ("conductor", "roughconductor"):
            rough = kind == "roughconductor"
            check_keys(b, {"type", "specular_reflectance", "material", "eta", "k"} |
                       ({"distribution", "alpha", "alpha_u", "alpha_v", "sample_visible"} if rough else set()),
                       where)
            inner = {"type": kind,
                     "specular_reflectance": self.texture_or_colour(b.get("specular_reflectance", 1),
                                                                    f"{where}.specular_reflectance")}
            # Mitsuba's own keys: a named material, or eta and k (numbers or RGB).
            if "eta" in b or "k" in b:
                inner["eta"] = rgb(colour(b.get("eta", 0.0), f"{where}.eta"))
                inner["k"] = rgb(colour(b.get("k", 1.0), f"{where}.k"))
            else:
                inner["material"] = str(b.get("material", "none"))
            if rough:
                inner["distribution"] = str(b.get("distribution", "beckmann"))
                if "alpha_u" in b or "alpha_v" in b:
                    inner["alpha_u"] = number(b.get("alpha_u", 0.1), f"{where}.alpha_u")
                    inner["alpha_v"] = number(b.get("alpha_v", 0.1), f"{where}.alpha_v")
                else:
                    inner["alpha"] = number(b.get("alpha", 0.1), f"{where}.alpha")
                inner["sample_visible"] = bool(b.get("sample_visible", True))
        elif kind == "dielectric":
            check_keys(b, {"type", "int_ior", "ext_ior"}, where)
            return {"type": "dielectric", "int_ior": number(b.get("int_ior", 1.5046), f"{where}.int_ior"),
                    "ext_ior": number(b.get("ext_ior", 1.000277), f"{where}.ext_ior")}
        elif kind in ("thindielectric", "roughdielectric"):
            out = {"type": kind, "int_ior": number(b.get("int_ior", 1.5046), f"{where}.int_ior"),
                   "ext_ior": number(b.get("ext_ior", 1.000277), f"{where}.ext_ior")}
            if kind == "roughdielectric":
                for key in ("distribution", "alpha", "alpha_u", "alpha_v", "sample_visible"):
                    if key in b:
                        out[key] = b[key]
            return out
        elif kind == "roughplastic":
            inner = {"type": "roughplastic", "nonlinear": bool(b.get("nonlinear", False)),
                     "diffuse_reflectance": self.texture_or_colour(b.get("diffuse_reflectance", 0.5),
                                                                   f"{where}.diffuse_reflectance"),
                     "int_ior": number(b.get("int_ior", 1.49), f"{where}.int_ior"),
                     "ext_ior": number(b.get("ext_ior", 1.000277), f"{where}.ext_ior")}
            for key in ("distribution", "alpha", "sample_visible"):
                if key in b:
                    inner[key] = b[key]
        elif kind == "plastic":
            check_keys(b, {"type", "diffuse_reflectance", "int_ior", "ext_ior", "nonlinear"}, where)
            inner = {"type": "plastic", "nonlinear": bool(b.get("nonlinear", False)),
                     "diffuse_reflectance": self.texture_or_colour(b.get("diffuse_reflectance", 0.5),
                                                                   f"{where}.diffuse_reflectance"),
                     "int_ior": number(b.get("int_ior", 1.49), f"{where}.int_ior"),
                     "ext_ior": number(b.get("ext_ior", 1.000277), f"{where}.ext_ior")}
        else:
            raise SceneError(f"{where}.type: expected diffuse, conductor, roughconductor, dielectric or plastic")
        return {"type": "twosided", "bsdf": inner}

    def emitter(self, e, where):
        kind = e.get("type") if isinstance(e, dict) else None
        if kind == "point":
            check_keys(e, {"type", "position", "intensity"}, where)
            return {"type": "point", "position": vector3(e.get("position", [0, 0, 0]), f"{where}.position"),
                    "intensity": rgb(colour(e.get("intensity", 1), f"{where}.intensity"))}
        if kind == "spot":
            check_keys(e, {"type", "to_world", "intensity", "cutoff_angle", "beam_width"}, where)
            if "to_world" not in e:
                raise SceneError(f"{where}.to_world: required")
            cutoff = number(e.get("cutoff_angle", 20), f"{where}.cutoff_angle")
            return {"type": "spot", "to_world": self.matrix(transform(e["to_world"], f"{where}.to_world")),
                    "intensity": rgb(colour(e.get("intensity", 1), f"{where}.intensity")),
                    "cutoff_angle": cutoff,
                    "beam_width": number(e.get("beam_width", cutoff * 0.75), f"{where}.beam_width")}
        raise SceneError(f"{where}.type: expected \"point\" or \"spot\"")

    def shape(self, s, where):
        common = {"type", "bsdf", "emitter", "to_world"}
        kind = s.get("type") if isinstance(s, dict) else None
        m = transform(s.get("to_world"), f"{where}.to_world")
        if kind == "sphere":
            check_keys(s, common | {"center", "radius"}, where)
            c = vector3(s.get("center", [0, 0, 0]), f"{where}.center")
            r = number(s.get("radius", 1), f"{where}.radius")
            world = m @ translate(c) @ scale([r, r, r])
            radius = np.linalg.norm(world[:3, 0])
            if self.flatten and radius >= self.flatten:
                out = {"type": "rectangle", "to_world": self.matrix(self.tangent_plane(world[:3, 3], radius))}
            else:
                out = {"type": "sphere", "to_world": self.matrix(world)}
        elif kind == "rectangle":
            check_keys(s, common, where)
            out = {"type": "rectangle", "to_world": self.matrix(m)}
        elif kind == "quad":
            check_keys(s, common | {"origin", "edge_u", "edge_v"}, where)
            o, u, v = (np.array(vector3(s[k], f"{where}.{k}")) for k in ("origin", "edge_u", "edge_v"))
            n = np.cross(u, v)
            n /= np.linalg.norm(n)
            q = np.identity(4)
            q[:3, 0], q[:3, 1], q[:3, 2], q[:3, 3] = u / 2, v / 2, n, o + (u + v) / 2
            out = {"type": "rectangle", "to_world": self.matrix(m @ q)}
        elif kind == "obj":
            check_keys(s, common | {"filename"}, where)
            out = {"type": "obj", "filename": self.file(s["filename"]), "to_world": self.matrix(m)}
        elif kind == "bezier":
            check_keys(s, common | {"filename", "patches", "uv_rects"}, where)
            out = {"type": "obj", "filename": self.bezier_obj(s, where), "to_world": self.matrix(m)}
        else:
            raise SceneError(f"{where}.type: expected sphere, rectangle, quad, obj or bezier")
        if "bsdf" in s:
            out["bsdf"] = self.bsdf(s["bsdf"], f"{where}.bsdf")
        else:
            out["bsdf"] = {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb([0.5] * 3)}}
        if "emitter" in s:
            e = s["emitter"]
            check_keys(e, {"type", "radiance"}, f"{where}.emitter")
            if e.get("type") != "area":
                raise SceneError(f"{where}.emitter.type: expected \"area\"")
            out["emitter"] = {"type": "area", "radiance": rgb(colour(e.get("radiance", 1), f"{where}.emitter.radiance"))}
        return out

    # ---- Bezier patches through ppm-tess ----

    def bezier_obj(self, s, where):
        if ("filename" in s) == ("patches" in s):
            raise SceneError(f"{where}: give either filename or patches")
        if "filename" in s:
            patches = read_bpt(self.file(s["filename"]))
        else:
            patches = []
            for p, patch in enumerate(s["patches"]):
                if not isinstance(patch, list) or len(patch) != 16:
                    raise SceneError(f"{where}.patches[{p}]: expected 16 points")
                patches.append([vector3(q, f"{where}.patches[{p}][{k}]") for k, q in enumerate(patch)])
        rects = s.get("uv_rects")
        if rects is not None and (not isinstance(rects, list) or len(rects) != len(patches)):
            raise SceneError(f"{where}.uv_rects: expected one [u0, v0, u1, v1] per patch ({len(patches)})")
        points = np.array(patches, dtype=float).reshape(-1, 3)
        tolerance = 1e-4 * np.linalg.norm(points.max(axis=0) - points.min(axis=0))
        base = os.path.join(self.workdir, where.replace("[", "_").replace("]", ""))
        if rects is None:
            # ppm-tess writes vt = (u, 1 - v), which Mitsuba's OBJ loader reads as the patch's (u, v).
            return self.tessellate(patches, f"{base}.bpt", tolerance)
        # One patch at a time, so that each vertex's (u, v) can be mapped into its patch's
        # rectangle; the same absolute tolerance keeps shared edges' vertices identical.
        v_lines, vt_lines, vn_lines, f_lines = [], [], [], []
        for p, patch in enumerate(patches):
            u0, v0, u1, v1 = (number(x, f"{where}.uv_rects[{p}]") for x in rects[p])
            obj = self.tessellate([patch], f"{base}_patch{p}.bpt", tolerance)
            offset = (len(v_lines), len(vt_lines), len(vn_lines))
            for line in open(obj):
                w = line.split()
                if not w:
                    continue
                if w[0] == "v":
                    v_lines.append(line.strip())
                elif w[0] == "vn":
                    vn_lines.append(line.strip())
                elif w[0] == "vt":
                    u, v = float(w[1]), 1 - float(w[2])  # the patch's v (ppm-tess writes 1 - v)
                    vt_lines.append(f"vt {u0 + u * (u1 - u0):.9g} {1 - (v0 + v * (v1 - v0)):.9g}")
                elif w[0] == "f":
                    corners = []
                    for c in w[1:]:
                        idx = [int(i) + offset[k] for k, i in enumerate(c.split("/"))]
                        corners.append("/".join(map(str, idx)))
                    f_lines.append("f " + " ".join(corners))
        merged = f"{base}.obj"
        with open(merged, "w") as out:
            out.write("\n".join(v_lines + vt_lines + vn_lines + f_lines) + "\n")
        return merged

    def tessellate(self, patches, bpt_path, tolerance):
        with open(bpt_path, "w") as f:
            f.write(f"{len(patches)}\n")
            for patch in patches:
                f.write("3 3\n")
                for q in patch:
                    f.write(f"{q[0]!r} {q[1]!r} {q[2]!r}\n")
        obj_path = bpt_path[:-4] + ".obj"
        result = subprocess.run([self.tess, bpt_path, "-o", obj_path, "--tolerance", repr(float(tolerance))],
                                capture_output=True, text=True)
        if result.returncode != 0:
            raise RuntimeError(f"ppm-tess failed on {bpt_path}: {result.stderr.strip()}")
        return obj_path


def read_bpt(path):
    words = []
    with open(path) as f:
        for line in f:
            words += line.split("#")[0].split()
    count, k, patches = int(words[0]), 1, []
    for _ in range(count):
        if words[k:k + 2] != ["3", "3"]:
            raise SceneError(f"{path}: only bicubic patches ('3 3') are supported")
        k += 2
        patches.append([[float(words[k + 3 * i + j]) for j in range(3)] for i in range(16)])
        k += 48
    return patches


def find_tess(given):
    if given:
        return given
    candidates = [os.path.join(REPO, "build", "tools", "tess", "ppm-tess")]
    candidates += sorted(glob.glob(os.path.join(REPO, "build-*", "tools", "tess", "ppm-tess")))
    for c in candidates:
        if os.access(c, os.X_OK):
            return c
    return shutil.which("ppm-tess")


def set_variant(name):
    """scalar_rgb unless asked otherwise: llvm_ad_rgb JIT-compiles through the system's
    libLLVM, and a mismatched one aborts the process (LLVM ERROR: Cannot select ...)."""
    import mitsuba as mi
    mi.set_variant(name or "scalar_rgb")
    return name or "scalar_rgb"


def read_exr(path):
    import mitsuba as mi
    return np.array(mi.Bitmap(path), dtype=np.float32)[:, :, :3]


def compare(ours, ref):
    if ours.shape != ref.shape:
        raise RuntimeError(f"image sizes differ: ours {ours.shape[1]}x{ours.shape[0]}, "
                           f"Mitsuba {ref.shape[1]}x{ref.shape[0]}")
    mean_ours, mean_ref = ours.mean(axis=(0, 1)), ref.mean(axis=(0, 1))
    rel_mse = ((ours - ref) ** 2 / (ref ** 2 + 0.01)).mean(axis=(0, 1))
    fmt = lambda v: "[" + ", ".join(f"{x:.5g}" for x in v) + "]"
    print(f"image means (R, G, B): libppm {fmt(mean_ours)}, mitsuba {fmt(mean_ref)}")
    print(f"ratio of means per channel (libppm / mitsuba): {fmt(mean_ours / mean_ref)}, "
          f"overall {ours.mean() / ref.mean():.4f}")
    print(f"relative MSE per channel: {fmt(rel_mse)}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene", help="libppm JSON scene file")
    parser.add_argument("--print", action="store_true", help="print the Mitsuba dictionary")
    parser.add_argument("--render", metavar="OUT.exr", help="render with Mitsuba into this EXR")
    parser.add_argument("--png", action="store_true", help="with --render: also write OUT.png (sRGB)")
    parser.add_argument("--spp", type=int, default=64, help="samples per pixel (default 64)")
    parser.add_argument("--compare", metavar="OURS.exr", help="libppm's render of the same scene")
    parser.add_argument("--reference", metavar="MI.exr", help="compare with this Mitsuba EXR instead of rendering")
    parser.add_argument("--width", type=int)
    parser.add_argument("--height", type=int)
    parser.add_argument("--scale", type=float, help="scale the film size by this factor")
    parser.add_argument("--tess", help="ppm-tess executable")
    parser.add_argument("--flatten", type=float, default=1e4, metavar="R",
                        help="spheres of radius >= R become their tangent square nearest the camera "
                             "(default 1e4; 0: never): Mitsuba's single precision blotches them")
    parser.add_argument("--variant", help="Mitsuba variant (default scalar_rgb)")
    parser.add_argument("--keep", metavar="DIR", help="keep the tessellated meshes in DIR")
    args = parser.parse_args()
    if not (args.print or args.render or args.compare):
        parser.error("nothing to do: give --print, --render or --compare")

    try:
        import mitsuba as mi
    except ImportError:
        sys.exit("to_mitsuba.py: needs Mitsuba 3 (pip install mitsuba)")
    try:
        variant = set_variant(args.variant)
        if args.compare and args.reference and not args.render:
            compare(read_exr(args.compare), read_exr(args.reference))
            return 0
        workdir = args.keep or tempfile.mkdtemp(prefix="to_mitsuba_")
        os.makedirs(workdir, exist_ok=True)
        try:
            tess = find_tess(args.tess)
            translator = Translator(args.scene, tess, workdir, args.width, args.height, args.scale, args.spp,
                                    args.flatten)
            if tess is None:
                translator.tess = "ppm-tess"  # only needed for bezier shapes; fails there clearly
            scene_dict = translator.translate_scene()
            if args.print:
                print(scene_dict)
            if args.render or args.compare:
                print(f"to_mitsuba.py: rendering with Mitsuba {mi.__version__} ({variant}), {args.spp} spp",
                      file=sys.stderr)
                image = mi.render(mi.load_dict(scene_dict), spp=args.spp)
                bitmap = mi.Bitmap(image)
                if args.render:
                    bitmap.write(args.render)
                    if args.png:
                        png = os.path.splitext(args.render)[0] + ".png"
                        bitmap.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, srgb_gamma=True).write(png)
                if args.compare:
                    compare(read_exr(args.compare), np.array(bitmap, dtype=np.float32)[:, :, :3])
        finally:
            if not args.keep:
                shutil.rmtree(workdir, ignore_errors=True)
    except SceneError as e:
        print(f"to_mitsuba.py: {args.scene}: {e}", file=sys.stderr)
        return 1
    except (RuntimeError, OSError, subprocess.SubprocessError) as e:
        print(f"to_mitsuba.py: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
