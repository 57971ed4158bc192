#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Speed against accuracy chart of `ppm-bench intersect` results.

Reads the CSV the bench writes (one row per ray set and method) and draws, for the chosen
ray sets (default: random and camera rays, one column each), rays per second (x, log)
against the 99.9th percentile and the maximum of |dt| / bounding-box diagonal (y, log), and
against the failure rate (misses + false hits per ray) and against the memory taken: one
curve per method family (libppm's exact intersector over its tolerances and over its
patch_presplit setting, uniform meshes in Embree and CGAL over the grid size, adaptive meshes
over their tolerance) and the naive Newton variants as points, each labelled with its
parameter. Writes DIR/NAME.png and DIR/NAME.svg.

Usage: plot_bench.py --csv bench-results.csv --out DIR [--name intersect]
                     [--sets random,camera] [--threads 1|all]
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)

# Drawn in this order; label, colour, marker, whether the points form a curve.
FAMILIES = [
    ("exact", "libppm exact (tolerance)", "tab:red", "o", True),
    ("exact-presplit", "libppm exact 1e-9 (patch_presplit p)", "tab:orange", "P", True),
    ("embree-uniform", "Embree, uniform mesh (N)", "tab:blue", "s", True),
    ("embree-adaptive", "Embree, adaptive mesh (tol.)", "tab:cyan", "D", True),
    ("cgal-uniform", "CGAL AABB tree, uniform mesh (N)", "tab:green", "^", True),
    ("cgal-adaptive", "CGAL AABB tree, adaptive mesh (tol.)", "tab:olive", "v", True),
    ("newton", "naive Newton (starts)", "tab:purple", "X", False),
]
# Zero errors (exact to the last bit) sit on this floor of the log axis.
FLOOR = 1e-17


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def short_value(row):
    value = number(row["value"])
    family = row["family"]
    if family.endswith("uniform"):
        return "N%d" % int(value)
    if family == "newton":
        return row["method"].replace("newton-", "")
    if family == "exact-presplit":
        return "p%d" % int(value)
    exponent = math.log10(value) if value and value > 0 else 0
    if abs(exponent - round(exponent)) < 1e-9:
        return "1e%d" % round(exponent)
    return "%g" % value


def failure_rate(row):
    """Misses plus false hits per ray the reference decided; None if nothing was decided."""
    decided = (number(row["ray_count"]) or 0) - (number(row["undecided"]) or 0)
    if decided <= 0:
        return None
    return ((number(row["misses"]) or 0) + (number(row["false_hits"]) or 0)) / decided


def memory_mb(row):
    """Input arrays plus acceleration structure, in MB (2^20 bytes); None if not measured."""
    total = (number(row["array_bytes"]) or 0) + (number(row["structure_bytes"]) or 0)
    return total / 1048576.0 if total > 0 else None


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def draw(rows, sets, threads, out_dir, name):
    speed_key = "rays_per_s_1t" if threads == "1" else "rays_per_s_all"
    metrics = [("dt_p999_rel", "p99.9 |dt| / diagonal"), ("dt_max_rel", "max |dt| / diagonal"),
               ("failures", "(misses + false hits) / rays"), ("memory", "memory MB (input + structure)")]
    fig, axes = plt.subplots(len(metrics), len(sets), figsize=(6.5 * len(sets), 4.0 * len(metrics)),
                             squeeze=False)
    handles = {}
    for col, ray_set in enumerate(sets):
        set_rows = [r for r in rows if r["rays"] == ray_set]
        count = set_rows[0]["ray_count"] if set_rows else "0"
        # A rate of 0 cannot sit on a log axis: it is drawn at half a ray.
        zero_rate = 0.5 / max(1.0, number(count) or 1.0)
        for row_index, (key, label) in enumerate(metrics):
            ax = axes[row_index][col]
            for family, family_label, colour, marker, curve in FAMILIES:
                points = []
                for r in set_rows:
                    if r["family"] != family:
                        continue
                    x = number(r[speed_key])
                    if not x or x <= 0:
                        continue
                    if key == "failures":
                        y = failure_rate(r)
                        if y is not None:
                            y = max(y, zero_rate)
                    elif key == "memory":
                        y = memory_mb(r)
                    else:
                        y = number(r[key])  # None: no matched hit, nothing to plot
                        if y is not None:
                            y = max(y, FLOOR)
                    if y is None:
                        continue
                    points.append((x, y, r))
                if not points:
                    continue
                if curve:
                    points.sort(key=lambda p: number(p[2]["value"]))
                xs = [p[0] for p in points]
                ys = [p[1] for p in points]
                style = "-" if curve else "none"
                handle, = ax.plot(xs, ys, linestyle=style, marker=marker, color=colour, markersize=6,
                                  linewidth=1.2, label=family_label)
                handles[family_label] = handle
                for k, (x, y, r) in enumerate(points):
                    ax.annotate(short_value(r), (x, y), textcoords="offset points",
                                xytext=(4, 3 if k % 2 == 0 else -9), fontsize=6.5, color=colour)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.grid(True, which="major", linewidth=0.4, alpha=0.6)
            ax.set_xlabel("rays / s, %s" % ("one thread (CPU time)" if threads == "1" else
                                             "all threads (wall time)"))
            ax.set_ylabel(label)
            if key == "failures":
                ax.axhline(zero_rate, color="grey", linewidth=0.6, linestyle=":")
                ax.annotate("no failure", (0.01, zero_rate), xycoords=("axes fraction", "data"),
                            xytext=(0, 3), textcoords="offset points", fontsize=6.5, color="grey")
            ax.set_title("%s rays (%s): %s" % (ray_set, count, label), fontsize=10)
    fig.legend(list(handles.values()), list(handles.keys()), loc="lower center", ncol=3, fontsize=8,
               frameon=False)
    fig.suptitle("ppm-bench intersect: speed against accuracy (|dt| against the long-double reference; "
                 "errors of 0 drawn at %g)" % FLOOR, fontsize=10)
    fig.tight_layout(rect=(0, 0.05, 1, 0.97))
    os.makedirs(out_dir, exist_ok=True)
    written = []
    for extension in ("png", "svg"):
        path = os.path.join(out_dir, "%s.%s" % (name, extension))
        fig.savefig(path, dpi=80)
        written.append(path)
    plt.close(fig)
    return written


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--csv", required=True, help="CSV written by ppm-bench intersect")
    parser.add_argument("--out", required=True, help="directory for NAME.png and NAME.svg")
    parser.add_argument("--name", default="intersect", help="file name without extension")
    parser.add_argument("--sets", default="random,camera", help="ray sets, one column each")
    parser.add_argument("--threads", choices=("1", "all"), default="1", help="which rays/s to plot")
    args = parser.parse_args(argv)
    plt.rcParams["svg.fonttype"] = "none"  # text stays text: a small SVG
    rows = read_rows(args.csv)
    if not rows:
        print("plot_bench.py: %s has no rows" % args.csv, file=sys.stderr)
        return 1
    available = []
    for s in args.sets.split(","):
        if any(r["rays"] == s for r in rows):
            available.append(s)
        else:
            print("plot_bench.py: note: no '%s' rays in %s" % (s, args.csv), file=sys.stderr)
    if not available:
        print("plot_bench.py: none of the ray sets %s in %s" % (args.sets, args.csv), file=sys.stderr)
        return 1
    for path in draw(rows, available, args.threads, args.out, args.name):
        print("wrote %s" % path, file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
