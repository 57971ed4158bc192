#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Compare libppm's thindielectric, roughdielectric and roughplastic with Mitsuba 3's plugins
of the same names, BSDF against BSDF (no scene): f and pdf at fixed direction pairs, the
thin sheet's reflectance, and the albedo (mean sample weight) at a few incident directions,
in both transport modes. Prints per-case, per-channel ratios libppm / Mitsuba:
  f ratio   = mean of libppm's f over the pairs / mean of Mitsuba's (pairs where both > 0)
  max |rel| = the largest relative difference of f (and pdf) at one pair
  albedo    = per-wo ratios of the sampled albedos.

libppm's side is the internal program tools/validate/bsdf_values (built with the tools:
cmake --build build --target bsdf_values). Mitsuba: /tmp/mitsuba-venv/bin/python (variant scalar_rgb).
  compare_dielectric_bsdfs.py [--bsdf-values PATH] [--samples 40000] [--only NAME ...]
Not run by CI (Mitsuba is a big download); the figures are quoted in the report.

Conventions: libppm's wo is Mitsuba's si.wi and its wi Mitsuba's wo; Mitsuba's eval() includes
|cos wo| (its wo), divided out here. Mitsuba's roughplastic is one-sided: compared on the front.
"""
import argparse
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))

CASES = {
    "thindielectric": dict(type="thindielectric"),
    "thindielectric-water": dict(type="thindielectric", int_ior=1.333, ext_ior=1.0),
    "roughdielectric-beckmann-0.1": dict(type="roughdielectric"),
    "roughdielectric-ggx-0.3": dict(type="roughdielectric", distribution="ggx", alpha=0.3),
    "roughdielectric-ggx-aniso": dict(type="roughdielectric", distribution="ggx", alpha_u=0.15, alpha_v=0.4),
    "roughdielectric-beckmann-0.3-all-normals": dict(type="roughdielectric", alpha=0.3, sample_visible=False),
    "roughplastic-beckmann-0.1": dict(type="roughplastic", diffuse_reflectance=0.5),
    "roughplastic-ggx-0.3": dict(type="roughplastic", distribution="ggx", alpha=0.3, diffuse_reflectance=0.8),
    "roughplastic-beckmann-0.6": dict(type="roughplastic", alpha=0.6, diffuse_reflectance=0.3, int_ior=1.6),
    "roughplastic-nonlinear": dict(type="roughplastic", alpha=0.2, diffuse_reflectance=0.7, nonlinear=True),
    "roughplastic-specular-0.4": dict(type="roughplastic", distribution="ggx", alpha=0.3, diffuse_reflectance=0.6,
                                      specular_reflectance=0.4),
}
DEFAULT_IOR = {"thindielectric": 1.5046, "roughdielectric": 1.5046, "roughplastic": 1.49}


def params(c):
    alpha = c.get("alpha", 0.1)
    return dict(type=c["type"], distribution=c.get("distribution", "beckmann"),
                alpha_u=c.get("alpha_u", alpha), alpha_v=c.get("alpha_v", alpha),
                int_ior=c.get("int_ior", DEFAULT_IOR[c["type"]]), ext_ior=c.get("ext_ior", 1.000277),
                reflectance=c.get("diffuse_reflectance", 0.5), sample_visible=c.get("sample_visible", True),
                nonlinear=c.get("nonlinear", False), specular=c.get("specular_reflectance", 1.0))


def material_words(p, mode):
    return (f"{p['type']} {p['distribution']} {p['alpha_u']!r} {p['alpha_v']!r} {p['int_ior']!r} "
            f"{p['ext_ior']!r} {p['reflectance']!r} {int(p['sample_visible'])} {int(p['nonlinear'])} "
            f"{p['specular']!r} {mode}")


def mitsuba_bsdf(mi, p):
    d = {"type": p["type"], "int_ior": p["int_ior"], "ext_ior": p["ext_ior"]}
    if p["type"] != "thindielectric":
        d.update(distribution=p["distribution"], sample_visible=p["sample_visible"])
        if p["type"] == "roughplastic":
            d.update(alpha=p["alpha_u"], nonlinear=p["nonlinear"],
                     diffuse_reflectance={"type": "rgb", "value": [p["reflectance"]] * 3},
                     specular_reflectance={"type": "rgb", "value": [p["specular"]] * 3})
        else:
            d.update(alpha_u=p["alpha_u"], alpha_v=p["alpha_v"])
    return mi.load_dict(d)


def direction(theta, phi):
    return (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bsdf-values", default=os.path.join(REPO, "build", "tools", "validate", "bsdf_values"))
    parser.add_argument("--samples", type=int, default=40000, help="samples per albedo estimate (each side)")
    parser.add_argument("--only", nargs="*")
    args = parser.parse_args()

    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    ours = subprocess.Popen([args.bsdf_values], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)

    def ask(line):
        ours.stdin.write(line + "\n")
        ours.stdin.flush()
        return [float(x) for x in ours.stdout.readline().split()]

    print(f"Mitsuba {mi.__version__} (scalar_rgb) against libppm tools/validate/bsdf_values")
    modes = {"radiance": mi.TransportMode.Radiance, "importance": mi.TransportMode.Importance}
    worst = 0.0
    for name in args.only or list(CASES):
        p = params(CASES[name])
        bsdf = mitsuba_bsdf(mi, p)
        sides = [1.0] if p["type"] == "roughplastic" else [1.0, -1.0]
        for mode_name, mode in modes.items():
            ctx = mi.BSDFContext(mode)
            words = material_words(p, mode_name)
            si = mi.SurfaceInteraction3f()
            si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
            if p["type"] == "thindielectric":
                rel = []
                for theta in (0.0, 0.4, 0.8, 1.2, 1.5):
                    for side in sides:
                        wo = direction(theta, 0.3)
                        wo = (wo[0], wo[1], wo[2] * side)
                        si.wi = mi.Vector3f(*wo)
                        bs, w = bsdf.sample(ctx, si, 0.0, mi.Point2f(0.5, 0.5))
                        r_m = bs.pdf
                        r_p = ask(f"S {words} {wo[0]!r} {wo[1]!r} {wo[2]!r} 0")[3]
                        rel.append(r_p / r_m - 1)
                worst = max(worst, max(abs(x) for x in rel))
                print(f"{name} [{mode_name}]: reflectance R' ratio max |rel| {max(abs(x) for x in rel):.2e} "
                      f"(transmission 1 - R' in both)")
                continue
            # f and pdf at fixed pairs: wo on a grid, wi on a grid over the sphere.
            sum_p, sum_m, max_f, max_pdf, count = [0.0] * 3, [0.0] * 3, 0.0, 0.0, 0
            for side in sides:
                for theta_o in (0.2, 0.7, 1.2):
                    wo = direction(theta_o, 0.4)
                    wo = (wo[0], wo[1], wo[2] * side)
                    si.wi = mi.Vector3f(*wo)
                    for i in range(12):
                        for j in range(8):
                            wi = direction((i + 0.5) * math.pi / 12, (j + 0.25) * 2 * math.pi / 8)
                            if abs(wi[2]) < 1e-3:
                                continue
                            f_m = bsdf.eval(ctx, si, mi.Vector3f(*wi))
                            pdf_m = bsdf.pdf(ctx, si, mi.Vector3f(*wi))
                            f_m = [f_m[k] / abs(wi[2]) for k in range(3)]
                            got = ask(f"E {words} {wo[0]!r} {wo[1]!r} {wo[2]!r} {wi[0]!r} {wi[1]!r} {wi[2]!r}")
                            f_p, pdf_p = got[:3], got[3]
                            if f_m[0] > 1e-6 and f_p[0] > 1e-6:
                                count += 1
                                for k in range(3):
                                    sum_p[k] += f_p[k]
                                    sum_m[k] += f_m[k]
                                max_f = max(max_f, abs(f_p[0] / f_m[0] - 1))
                            if pdf_m > 1e-6 and pdf_p > 1e-6:
                                max_pdf = max(max_pdf, abs(pdf_p / pdf_m - 1))
            ratio = [sum_p[k] / sum_m[k] for k in range(3)]
            worst = max(worst, max(abs(r - 1) for r in ratio))
            # Albedo at a few wo, by each renderer's own sampler.
            alb = []
            rng = mi.PCG32(initstate=7)
            for side in sides:
                for theta_o in (0.3, 1.0):
                    wo = direction(theta_o, 0.4)
                    wo = (wo[0], wo[1], wo[2] * side)
                    si.wi = mi.Vector3f(*wo)
                    acc = [0.0] * 3
                    for _ in range(args.samples):
                        bs, w = bsdf.sample(ctx, si, rng.next_float32(),
                                            mi.Point2f(rng.next_float32(), rng.next_float32()))
                        for k in range(3):
                            acc[k] += w[k]
                    a_m = [x / args.samples for x in acc]
                    a_p = ask(f"A {words} {wo[0]!r} {wo[1]!r} {wo[2]!r} {10 * args.samples}")
                    alb.append((side * theta_o, a_p[0], a_m[0]))
            alb_text = ", ".join(f"theta {t:+.1f}: {a:.4f}/{b:.4f}={a / b:.4f}" for t, a, b in alb)
            print(f"{name} [{mode_name}]: f ratio [{', '.join(f'{r:.4f}' for r in ratio)}] over {count} pairs, "
                  f"max |rel| f {max_f:.2e} pdf {max_pdf:.2e}; albedo libppm/Mitsuba {alb_text}", flush=True)
    ours.stdin.close()
    ours.wait()
    print(f"largest mean-ratio deviation: {100 * worst:.3f} %")


if __name__ == "__main__":
    main()
