#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Try Mitsuba 3 XML scenes as a new user would: which ones Mitsuba 3 loads, and of those,
which ones ppm-render loads and renders unchanged (one 16 x 16 pass), with the first line of
libppm's error for the others.

  survey_scenes.py FOLDER_OR_FILE ... [--lenient] [--ppm-render build/tools/render/ppm-render]
                   [--variant scalar_rgb] [--csv OUT.csv]

Folders are searched for *.xml, leaving out the fragments scenes include (files under a
folder named `fragments` or `include`). Not run by CI (Mitsuba is a large download); run it
with the Python that has Mitsuba: `python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba`.
"""
import argparse
import csv
import glob
import os
import subprocess
import sys
import tempfile


def repository_root():
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def scene_files(paths):
    files = []
    for path in paths:
        if os.path.isdir(path):
            for f in sorted(glob.glob(os.path.join(path, "**", "*.xml"), recursive=True)):
                parts = os.path.relpath(f, path).split(os.sep)
                if not any(p in ("fragments", "include") for p in parts[:-1]):
                    files.append(f)
        else:
            files.append(path)
    return files


def mitsuba_loads(path, variant):
    """None when Mitsuba 3 loads the file, else its error's first line (in a child process:
    a failed load can leave Mitsuba's state behind)."""
    code = ("import sys, mitsuba as mi; mi.set_variant(sys.argv[2]); mi.load_file(sys.argv[1])")
    r = subprocess.run([sys.executable, "-c", code, path, variant], capture_output=True, text=True,
                       timeout=600)
    if r.returncode == 0:
        return None
    lines = [l for l in r.stderr.strip().splitlines() if l.strip()]
    return lines[-1] if lines else f"exit status {r.returncode}"


def libppm_renders(path, ppm_render, lenient, out):
    command = [ppm_render, path, "-q", "--passes", "1", "--size", "16x16", "-o", out]
    if lenient:
        command.append("--lenient")
    r = subprocess.run(command, capture_output=True, text=True, timeout=900)
    if r.returncode == 0:
        return None
    lines = [l for l in r.stderr.splitlines() if l.startswith("ppm-render:")]
    return lines[0] if lines else (r.stderr.strip().splitlines() or [f"exit status {r.returncode}"])[-1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("paths", nargs="+")
    parser.add_argument("--lenient", action="store_true")
    parser.add_argument("--variant", default="scalar_rgb")
    parser.add_argument("--ppm-render", default=os.path.join(repository_root(), "build/tools/render/ppm-render"))
    parser.add_argument("--csv", help="write one row per scene")
    args = parser.parse_args()
    rows = []
    out = os.path.join(tempfile.mkdtemp(prefix="ppm-survey-"), "image.exr")
    for path in scene_files(args.paths):
        mitsuba = mitsuba_loads(path, args.variant)
        ours = libppm_renders(path, args.ppm_render, args.lenient, out) if mitsuba is None else None
        status = "mitsuba fails" if mitsuba else ("loads" if ours is None else "fails")
        rows.append((path, status, mitsuba or ours or ""))
        print(f"{status:14s} {path}" + (f"\n               {mitsuba or ours}" if (mitsuba or ours) else ""), flush=True)
    loaded_by_mitsuba = [r for r in rows if r[1] != "mitsuba fails"]
    ours = [r for r in loaded_by_mitsuba if r[1] == "loads"]
    print(f"\nMitsuba 3 ({args.variant}) loads {len(loaded_by_mitsuba)} of {len(rows)} files; "
          f"ppm-render{' --lenient' if args.lenient else ''} loads and renders {len(ours)} of those")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(["scene", "status", "message"])
            writer.writerows(rows)


if __name__ == "__main__":
    main()
