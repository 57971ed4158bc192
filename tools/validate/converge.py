#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Equal-time convergence benchmark: libppm's modes against Mitsuba 3's path tracer, as error
against wall time on a handful of scenes, each measured against a long Mitsuba 3 reference.

Scenes (--scenes, comma separated; the first five by default):
  cornell-diffuse   diffuse Cornell box, square area light, a white diffuse ball
  cornell-glass     the same box with the ball in glass: a caustic under the area light
  cornell-caustic   the glass ball under a point light: the floor's caustic is made only of
                    light-specular-diffuse-camera paths, which a path tracer never samples
  teapot-glass      the Newell teapot (Bezier patches) in glass in teapot-cornell's box
  cornell-glossy    rough plastic walls and a rough gold ball (GGX, alpha 0.3)
  cornell-xml       examples/scenes/cornell-box.xml (mesh light, rough gold box, frosted
                    glass ball), read unchanged by both renderers (not in the default set)
The JSON scenes are in tools/validate/scenes/ and go to Mitsuba through
tools/validate/to_mitsuba.py (the same translation as its --render, Bezier patches
tessellated by ppm-tess); the XML scene is read by both as it is, as compare_xml.py does.

Method, per scene:
  1. Reference: Mitsuba's path tracer (the light tracer `ptracer` for cornell-caustic), with
     max_depth = libppm's max_depth + 1 (Mitsuba also counts the emitter vertex), rendered as
     two independent halves h1, h2 of --reference-spp samples per pixel each (other seeds),
     cached in DIR/reference/ under the scene's name, size, integrator, spp and a hash of the
     scene file, so that a rerun reuses them (a half interrupted goes on from its last save,
     DIR/reference/*.partial.npz, every minute). The reference is ref = (h1 + h2) / 2.
  2. For each time T in --times: libppm once per mode in --modes (`ppm-render SCENE --time T
     --set mode=M`), and Mitsuba's path tracer (and its light tracer on cornell-caustic) for
     the same wall time, each on all cores. Mitsuba's own `timeout` property cannot be used:
     it stops at the deadline between image blocks and leaves the rest of the image black. So
     Mitsuba renders successive batches of samples (other seeds, batch sizes doubling from 1
     spp up to about T/8), each batch sized from the time per sample measured so far, and stops
     when the next sample would end after T; the image is the mean over all samples, as one
     render of that many samples would be. Both report the time spent rendering (libppm's
     own figure from its summary line, which leaves out loading the scene and writing the
     image; Mitsuba's batches, scene loading left out), and the process's wall time.
  3. Errors over every pixel and channel, with x the image, d = x - ref and the noise of the
     reference taken out: h1 and h2 are independent with the same variance s^2 per pixel, so
     E[(h1 - h2)^2] = 2 s^2 and the variance of their mean ref is s^2 / 2 = E[(h1 - h2)^2] / 4.
     As x is independent of ref, E[d^2] = (bias of x)^2 + Var x + Var ref, so
        MSE    = mean(d^2 - (h1 - h2)^2 / 4)                      RMSE = sqrt(max(MSE, 0))
        relMSE = mean((d^2 - (h1 - h2)^2 / 4) / (ref^2 + 0.01))
     (relMSE as in compare_xml.py and to_mitsuba.py, with the noise term added) and
     mean_ratio = mean(x) / mean(ref). The noise terms are written too (ref_noise_mse,
     ref_noise_relmse): an error near them is not measured well, so the reference must have
     many more samples than the longest render. On cornell-caustic the light tracer cannot
     see specular surfaces from the camera, so the errors there are taken over the pixels in
     which no camera ray meets a specular surface first (glass, smooth metal, smooth plastic:
     a mask that Mitsuba renders, cached in DIR/mask/), for every renderer alike.

Writes DIR/converge.csv (scene, renderer, mode, seconds_requested, seconds_measured, rmse,
relmse, mean_ratio, then samples, seconds_wall, raw and noise figures, pixels), a log-log
chart of error against time per scene (DIR/converge-SCENE.png), every image
(DIR/renders/SCENE/), and prints a table with each result's ratio to Mitsuba's path tracer at
the same time (relMSE / relMSE of Mitsuba's path tracer: below 1 is better).

Run it with a Python that has Mitsuba 3 and numpy (and matplotlib for the charts), at the
lowest priority when the machine is shared:
  python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy matplotlib
  nice -n 19 /tmp/mi/bin/python tools/validate/converge.py --modes sppm --times 10,40,160
  nice -n 19 /tmp/mi/bin/python tools/validate/converge.py --quick      # a smoke test
--quick renders a quarter of each film size (32 x 32), reference halves of 128 spp, and 1 and 2 s.

Exit status: 0 ok, 1 usage error, 2 runtime error (Mitsuba or ppm-render missing or failing).
"""
import argparse
import csv
import hashlib
import math
import os
import re
import subprocess
import sys
import time

try:
    import numpy as np

    import to_mitsuba
except ImportError as e:
    print(f"converge.py: {e}: run this script with a Python that has Mitsuba 3 and numpy "
          "(python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy matplotlib)", file=sys.stderr)
    sys.exit(2)

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = to_mitsuba.REPO


class Scene:
    def __init__(self, name, path, about, reference="path", mitsuba=("path",), mask_specular=False,
                 xml_res=None):
        self.name, self.path, self.about = name, os.path.join(REPO, path), about
        self.reference = reference  # Mitsuba integrator of the reference
        self.mitsuba = mitsuba  # Mitsuba integrators rendered for each time, the first is the baseline
        self.mask_specular = mask_specular
        self.xml_res = xml_res  # an XML scene's film size parameter `$res` (square film)

    @property
    def is_xml(self):
        return self.path.endswith(".xml")


SCENES = [
    Scene("cornell-diffuse", "tools/validate/scenes/cornell-diffuse.json", "diffuse box, area light"),
    Scene("cornell-glass", "tools/validate/scenes/cornell-glass.json", "glass ball, area light"),
    Scene("cornell-caustic", "tools/validate/scenes/cornell-caustic.json", "glass ball, point light",
          reference="ptracer", mitsuba=("path", "ptracer"), mask_specular=True),
    Scene("teapot-glass", "tools/validate/scenes/teapot-glass.json", "glass teapot, area light"),
    Scene("cornell-glossy", "tools/validate/scenes/cornell-glossy.json", "rough plastic and gold"),
    Scene("cornell-xml", "examples/scenes/cornell-box.xml", "mesh light, rough gold, frosted glass",
          xml_res=128),
]
DEFAULT_SCENES = "cornell-diffuse,cornell-glass,cornell-caustic,teapot-glass,cornell-glossy"
SPECULAR_BSDFS = {"dielectric", "thindielectric", "conductor", "plastic"}
QUICK_SCALE = 0.25
# Seeds: the reference halves and the timed renders draw from disjoint ranges.
SEED_HALF = (1_000_000, 2_000_000)
SEED_TIMED = 10_000_000


def log(message):
    print(f"[{time.strftime('%H:%M:%S')}] {message}", file=sys.stderr, flush=True)


def mitsuba():
    try:
        import mitsuba as mi
    except ImportError:
        raise RuntimeError(f"Mitsuba 3 is not installed for {sys.executable}: run this script with a Python "
                           "that has it (python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy "
                           "matplotlib)") from None
    return mi


def quiet_mitsuba(mi):
    """Mitsuba's warnings and errors to stderr, without its progress bars (the light tracer
    draws one on stdout at any log level): this script reports its own progress."""
    class Appender(mi.Appender):
        def append(self, level, text):
            print(text, file=sys.stderr)

        def log_progress(self, progress, name, formatted, eta, ptr=None):
            pass

    mi.set_log_level(mi.LogLevel.Warn)
    mi.logger().clear_appenders()
    mi.logger().add_appender(Appender())


# ---- the scenes in Mitsuba ---------------------------------------------------------------------

class MitsubaScenes:
    """Translates and loads each scene once per integrator (and its specular mask)."""

    def __init__(self, out, tess, film_scale):
        self.out, self.tess, self.film_scale = out, tess, film_scale
        self.cache = {}

    def size(self, scene):
        """The film size: the scene's, times --scale."""
        if scene.is_xml:
            width = height = scene.xml_res
        else:
            film = to_mitsuba.read_scene(scene.path).get("sensor", {}).get("film", {})
            width, height = int(film.get("width", 768)), int(film.get("height", 576))
        return max(8, round(width * self.film_scale)), max(8, round(height * self.film_scale))

    def scene_dict(self, scene):
        width, height = self.size(scene)
        workdir = os.path.join(self.out, "meshes", scene.name)
        os.makedirs(workdir, exist_ok=True)
        return to_mitsuba.Translator(scene.path, self.tess, workdir, width, height).translate_scene()

    def load(self, scene, integrator):
        key = (scene.name, integrator)
        if key not in self.cache:
            mi = mitsuba()
            if scene.is_xml:
                if integrator != "path":
                    raise RuntimeError(f"{scene.name}: an XML scene renders with its own integrator only")
                loaded = mi.load_file(scene.path, res=str(self.size(scene)[0]))
            else:
                d = self.scene_dict(scene)
                d["integrator"]["type"] = integrator
                loaded = mi.load_dict(d)
            self.cache[key] = loaded
        return self.cache[key]

    def mask(self, scene):
        """1 where no camera ray of the pixel meets a specular surface first, else 0: every
        specular shape is made an emitter of radiance 1 in a black scene without lights and
        rendered with max_depth 1 (emitters seen directly)."""
        d = self.scene_dict(scene)
        d["integrator"] = {"type": "path", "max_depth": 1}
        black = {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0, 0, 0]}}
        for key in list(d):
            if key.startswith("emitter_"):
                del d[key]
            elif key.startswith("shape_"):
                bsdf = d[key]["bsdf"]
                inner = bsdf["bsdf"] if bsdf["type"] == "twosided" else bsdf
                d[key].pop("emitter", None)
                if inner["type"] in SPECULAR_BSDFS:
                    d[key]["emitter"] = {"type": "area", "radiance": {"type": "rgb", "value": [1, 1, 1]}}
                d[key]["bsdf"] = black
        mi = mitsuba()
        coverage = np.array(mi.render(mi.load_dict(d), spp=256, seed=7), dtype=np.float64)[..., :3].max(axis=2)
        return (coverage == 0).astype(np.float64)


def scene_hash(scene):
    with open(scene.path, "rb") as f:
        return hashlib.sha1(f.read()).hexdigest()[:8]


def render_mitsuba_spp(mi_scene, spp, seed, what, partial=None):
    """spp samples per pixel in batches of 256 (batch k with seed + k), progress every ~30 s.
    With `partial` (a .npz path), the sum so far is saved there after each ~60 s and an
    interrupted render goes on from it: the same batches, the same image."""
    mi = mitsuba()
    total, done, start, shown, saved = None, 0, time.perf_counter(), time.perf_counter(), time.perf_counter()
    if partial and os.path.exists(partial):
        with np.load(partial) as f:
            total, done = f["total"], int(f["done"])
        log(f"  {what}: going on from {done} spp ({partial})")
    first = done
    while done < spp:
        n = min(256, spp - done)
        image = np.array(mi.render(mi_scene, spp=n, seed=seed + done // 256), dtype=np.float64)[..., :3]
        total = image * n if total is None else total + image * n
        done += n
        now = time.perf_counter()
        if partial and now - saved > 60 and done < spp:
            np.savez(partial + ".tmp.npz", total=total, done=done)
            os.replace(partial + ".tmp.npz", partial)
            saved = now
        if now - shown > 30 and done < spp:
            rate = (now - start) / (done - first)
            log(f"  {what}: {done} of {spp} spp, {now - start:.0f} s, {rate * (spp - done):.0f} s to go")
            shown = now
    return total / spp, time.perf_counter() - start


def render_mitsuba_timed(mi_scene, seconds, seed):
    """As many samples per pixel as fit in `seconds` of rendering: batches doubling from 1 spp
    up to about seconds / 8 each, the last one sized to end by the deadline."""
    mi = mitsuba()
    total, done, batch, elapsed = None, 0, 0, 0.0
    start = time.perf_counter()
    while True:
        if done:
            per_sample = elapsed / done
            fits = int((seconds - elapsed) / per_sample)
            if fits < 1:
                break
            n = min(fits, max(1, min(2 * done, int(seconds / 8 / per_sample))))
        else:
            n = 1
        image = np.array(mi.render(mi_scene, spp=n, seed=seed + batch), dtype=np.float64)[..., :3]
        total = image * n if total is None else total + image * n
        done, batch = done + n, batch + 1
        elapsed = time.perf_counter() - start
    return total / done, done, elapsed


def reference_halves(scenes, scene, spp, out):
    """Both halves of the reference, rendered or read from the cache."""
    mi = mitsuba()
    width, height = scenes.size(scene)
    folder = os.path.join(out, "reference")
    os.makedirs(folder, exist_ok=True)
    halves = []
    for k, tag in enumerate("ab"):
        path = os.path.join(folder, f"{scene.name}-{width}x{height}-{scene.reference}-{spp}spp-"
                                    f"{scene_hash(scene)}-{tag}.exr")
        if os.path.exists(path):
            log(f"{scene.name}: reference half {tag} from {path}")
            halves.append(to_mitsuba.read_exr(path).astype(np.float64))
            continue
        log(f"{scene.name}: rendering reference half {tag}: Mitsuba {scene.reference}, {spp} spp, "
            f"{width} x {height}")
        partial = path[:-4] + ".partial.npz"
        image, seconds = render_mitsuba_spp(scenes.load(scene, scene.reference), spp, SEED_HALF[k],
                                            f"reference half {tag}", partial)
        log(f"{scene.name}: reference half {tag} took {seconds:.1f} s")
        mi.Bitmap(image.astype(np.float32)).write(path + ".tmp.exr")
        os.replace(path + ".tmp.exr", path)
        if os.path.exists(partial):
            os.remove(partial)
        halves.append(image)
    return halves


def specular_mask(scenes, scene, out):
    mi = mitsuba()
    width, height = scenes.size(scene)
    folder = os.path.join(out, "mask")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, f"{scene.name}-{width}x{height}-{scene_hash(scene)}.exr")
    if os.path.exists(path):
        return to_mitsuba.read_exr(path)[..., 0].astype(np.float64)
    mask = scenes.mask(scene)
    mi.Bitmap(np.repeat(mask[..., None], 3, axis=2).astype(np.float32)).write(path)
    return mask


# ---- libppm -------------------------------------------------------------------------------------

SUMMARY = re.compile(r"ppm-render: (\d+) passes \(.*\) in ([0-9.]+) s")


def render_libppm(binary, scene, size, mode, seconds, seed, settings, path):
    """One `ppm-render --time` run; its passes are unlimited so that only the time ends it."""
    command = [binary, scene.path, "-o", path, "--time", repr(float(seconds)), "--passes", "1000000000",
               "--seed", str(seed), "--size", f"{size[0]}x{size[1]}", "--set", f"mode={mode}"]
    if scene.is_xml:
        command += ["-D", f"res={size[0]}"]
    for item in settings:
        command += ["--set", item]
    start = time.perf_counter()
    result = subprocess.run(command, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if result.returncode != 0:
        raise RuntimeError(f"ppm-render failed ({result.returncode}): {' '.join(command)}\n{result.stderr.strip()}")
    match = SUMMARY.search(result.stderr)
    passes, render_seconds = (int(match.group(1)), float(match.group(2))) if match else (0, wall)
    return to_mitsuba.read_exr(path).astype(np.float64), passes, render_seconds, wall


def check_modes(binary, scene, modes, settings, out):
    """One tiny pass per mode before any reference is rendered: a misspelt mode or setting
    fails here, not after an hour of references."""
    for mode in modes:
        command = [binary, scene.path, "-o", os.path.join(out, "check-mode.exr"), "--passes", "1", "--photons",
                   "1000", "--size", "8x8", "--quiet", "--set", f"mode={mode}"]
        if scene.is_xml:
            command += ["-D", "res=8"]
        for item in settings:
            command += ["--set", item]
        result = subprocess.run(command, capture_output=True, text=True)
        if result.returncode != 0:
            raise RuntimeError(f"ppm-render cannot render mode '{mode}': {result.stderr.strip()}")
    if modes:
        os.remove(os.path.join(out, "check-mode.exr"))


# ---- errors ------------------------------------------------------------------------------------

def errors(image, halves, mask):
    """The figures of the docstring's step 3, over the pixels where mask is 1."""
    h1, h2 = halves
    ref = 0.5 * (h1 + h2)
    if image.shape != ref.shape:
        raise RuntimeError(f"image sizes differ: {image.shape[1]}x{image.shape[0]} against the reference's "
                           f"{ref.shape[1]}x{ref.shape[0]}")
    keep = np.broadcast_to(mask[..., None] > 0, ref.shape)
    d2 = ((image - ref) ** 2)[keep]
    noise = ((h1 - h2) ** 2 / 4)[keep]
    weight = 1.0 / (ref[keep] ** 2 + 0.01)
    mse = float(np.mean(d2 - noise))
    return {"rmse": math.sqrt(max(mse, 0.0)), "relmse": float(np.mean((d2 - noise) * weight)),
            "mean_ratio": float(image[keep].mean() / ref[keep].mean()),
            "rmse_raw": math.sqrt(float(np.mean(d2))), "relmse_raw": float(np.mean(d2 * weight)),
            "ref_noise_mse": float(np.mean(noise)), "ref_noise_relmse": float(np.mean(noise * weight)),
            "pixels": int(keep.sum() // 3)}


FIELDS = ["scene", "renderer", "mode", "seconds_requested", "seconds_measured", "rmse", "relmse", "mean_ratio",
          "samples", "seconds_wall", "rmse_raw", "relmse_raw", "ref_noise_mse", "ref_noise_relmse", "pixels"]


def write_csv(rows, path):
    with open(path + ".tmp", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    os.replace(path + ".tmp", path)


def chart(rows, scene, path):
    try:
        import matplotlib
    except ImportError:
        log(f"no chart: matplotlib is not installed for {sys.executable} ({sys.executable} -m pip install "
            "matplotlib)")
        return False
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    mine = [r for r in rows if r["scene"] == scene.name]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for label in dict.fromkeys(f"{r['renderer']} {r['mode']}" for r in mine):
        series = [r for r in mine if f"{r['renderer']} {r['mode']}" == label]
        for ax, key in zip(axes, ("relmse", "rmse")):
            points = [(r["seconds_measured"], r[key]) for r in series if r[key] > 0]
            if points:
                ax.loglog(*zip(*points), "o-", label=label)
    noise = mine[0]["ref_noise_relmse"], math.sqrt(mine[0]["ref_noise_mse"])
    for ax, key, level in zip(axes, ("relMSE", "RMSE"), noise):
        ax.axhline(level, color="grey", linestyle="--", linewidth=1, label="reference noise (subtracted)")
        ax.set_xlabel("seconds rendering (all cores)")
        ax.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_ylabel(f"{key} against the reference")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(f"{scene.name}: {scene.about}, {mine[0]['pixels']} pixels measured")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return True


def print_table(rows, scenes_run):
    print()
    for scene in scenes_run:
        mine = [r for r in rows if r["scene"] == scene.name]
        if not mine:
            continue
        print(f"{scene.name} ({scene.about}); reference noise relMSE {mine[0]['ref_noise_relmse']:.2e}, "
              f"{mine[0]['pixels']} pixels")
        print(f"  {'T (s)':>6} {'renderer':<17} {'measured':>8} {'samples':>8} {'relMSE':>9} {'x PT':>6} "
              f"{'RMSE':>9} {'x PT':>6} {'mean ratio':>10}")
        for t in dict.fromkeys(r["seconds_requested"] for r in mine):
            at = [r for r in mine if r["seconds_requested"] == t]
            base = next((r for r in at if r["renderer"] == "mitsuba" and r["mode"] == "path"), None)
            for r in at:
                rel = f"{r['relmse'] / base['relmse']:6.2f}" if base and base["relmse"] > 0 else f"{'-':>6}"
                rms = f"{r['rmse'] / base['rmse']:6.2f}" if base and base["rmse"] > 0 else f"{'-':>6}"
                print(f"  {t:>6g} {r['renderer'] + ' ' + r['mode']:<17} {r['seconds_measured']:8.2f} "
                      f"{r['samples']:>8} {r['relmse']:9.2e} {rel} {r['rmse']:9.2e} {rms} {r['mean_ratio']:10.4f}")
        print()
    print("x PT: the figure divided by Mitsuba's path tracer's at the same time (below 1: better); "
          "samples: libppm's passes, Mitsuba's samples per pixel")


class Parser(argparse.ArgumentParser):
    def error(self, message):
        self.print_usage(sys.stderr)
        self.exit(1, f"{self.prog}: error: {message}\n")


def main():
    parser = Parser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scenes", default=DEFAULT_SCENES,
                        help=f"comma-separated, of {', '.join(s.name for s in SCENES)} (default: {DEFAULT_SCENES})")
    parser.add_argument("--modes", default="sppm", help="libppm modes, comma separated (--set mode=NAME; default sppm)")
    parser.add_argument("--times", help="seconds per render, comma separated (default 10,40,160; --quick: 1,2)")
    parser.add_argument("--reference-spp", type=int,
                        help="samples per pixel of each of the reference's two halves (default 8192; --quick: 128)")
    parser.add_argument("--out", help="output folder (default build/converge; --quick: build/converge-quick)")
    parser.add_argument("--scale", type=float,
                        help="scale every film size by this factor (default 1, the scene's; --quick: 0.25)")
    parser.add_argument("--quick", action="store_true",
                        help="a smoke test: a quarter of each film size, 128-spp reference halves, 1 and 2 s")
    parser.add_argument("--ppm-render", default=os.path.join(REPO, "build", "tools", "render", "ppm-render"),
                        help="the ppm-render executable (default build/tools/render/ppm-render)")
    parser.add_argument("--tess", help="ppm-tess executable, for the teapot (default: found as to_mitsuba.py does)")
    parser.add_argument("--set", dest="settings", action="append", default=[], metavar="KEY=VALUE",
                        help="another libppm setting for every mode (ppm-render --set), repeatable")
    parser.add_argument("--no-mitsuba-timed", action="store_true",
                        help="leave out Mitsuba's timed renders (references only, then libppm)")
    parser.add_argument("--variant", default="scalar_rgb",
                        help="Mitsuba variant (default scalar_rgb; llvm_ad_rgb aborts with some libLLVM)")
    args = parser.parse_args()

    by_name = {s.name: s for s in SCENES}
    chosen = []
    for name in args.scenes.split(","):
        if name not in by_name:
            parser.error(f"--scenes: no scene '{name}' (there are {', '.join(by_name)})")
        chosen.append(by_name[name])
    modes = [m for m in args.modes.split(",") if m]
    try:
        times = [float(t) for t in (args.times or ("1,2" if args.quick else "10,40,160")).split(",")]
    except ValueError:
        parser.error(f"--times: expected seconds separated by commas, not '{args.times}'")
    if any(t <= 0 for t in times):
        parser.error("--times: every time must be > 0")
    film_scale = args.scale or (QUICK_SCALE if args.quick else 1.0)
    if film_scale <= 0:
        parser.error("--scale: must be > 0")
    spp = args.reference_spp or (128 if args.quick else 8192)
    if spp < 1:
        parser.error("--reference-spp: must be >= 1")
    out = os.path.abspath(args.out or os.path.join(REPO, "build", "converge-quick" if args.quick else "converge"))
    for item in args.settings:
        if "=" not in item:
            parser.error(f"--set {item}: expected KEY=VALUE")

    try:
        if modes and not os.access(args.ppm_render, os.X_OK):
            raise RuntimeError(f"no ppm-render executable at {args.ppm_render} (build libppm, or give --ppm-render PATH)")
        mi = mitsuba()
        to_mitsuba.set_variant(args.variant)
        quiet_mitsuba(mi)
        tess = to_mitsuba.find_tess(args.tess) or "ppm-tess"
        os.makedirs(out, exist_ok=True)
        log(f"Mitsuba {mi.__version__} ({args.variant}), libppm modes {', '.join(modes) or 'none'}, "
            f"times {', '.join(f'{t:g}' for t in times)} s, reference 2 x {spp} spp, output {out}")
        scenes = MitsubaScenes(out, tess, film_scale)
        check_modes(args.ppm_render, chosen[0], modes, args.settings, out)
        rows = []
        csv_path = os.path.join(out, "converge.csv")
        for scene in chosen:
            size = scenes.size(scene)
            halves = reference_halves(scenes, scene, spp, out)
            mask = specular_mask(scenes, scene, out) if scene.mask_specular else np.ones(halves[0].shape[:2])
            if scene.mask_specular:
                log(f"{scene.name}: errors over the {int(mask.sum())} of {mask.size} pixels that see no specular "
                    "surface first")
            folder = os.path.join(out, "renders", scene.name)
            os.makedirs(folder, exist_ok=True)
            for ti, seconds in enumerate(times):
                runs = [] if args.no_mitsuba_timed else [("mitsuba", i) for i in scene.mitsuba]
                runs += [("libppm", m) for m in modes]
                for renderer, mode in runs:
                    path = os.path.join(folder, f"{renderer}-{mode}-{seconds:g}s.exr")
                    seed = SEED_TIMED + 100_000 * ti
                    if renderer == "mitsuba":
                        image, samples, measured = render_mitsuba_timed(scenes.load(scene, mode), seconds, seed)
                        wall = measured
                        mi.Bitmap(image.astype(np.float32)).write(path)
                    else:
                        image, samples, measured, wall = render_libppm(args.ppm_render, scene, size, mode, seconds,
                                                                       ti + 1, args.settings, path)
                    e = errors(image, halves, mask)
                    rows.append(dict(scene=scene.name, renderer=renderer, mode=mode, seconds_requested=seconds,
                                     seconds_measured=measured, samples=samples, seconds_wall=wall, **e))
                    log(f"{scene.name}: {renderer} {mode} {seconds:g} s: {measured:.2f} s measured "
                        f"({wall:.2f} s wall), {samples} {'spp' if renderer == 'mitsuba' else 'passes'}, "
                        f"relMSE {e['relmse']:.3e}, RMSE {e['rmse']:.3e}, mean ratio {e['mean_ratio']:.4f}")
                    write_csv(rows, csv_path)
            if any(r["scene"] == scene.name for r in rows):
                png = os.path.join(out, f"converge-{scene.name}.png")
                if chart(rows, scene, png):
                    log(f"{scene.name}: chart {png}")
        if rows:
            print_table(rows, chosen)
            log(f"results in {csv_path}")
    except to_mitsuba.SceneError as e:
        print(f"converge.py: {e}", file=sys.stderr)
        return 1
    except (RuntimeError, OSError, subprocess.SubprocessError) as e:
        print(f"converge.py: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
