"""What chapter studies share (tools/meshes_study.py, tools/real_glass_study.py,
tools/antialias_study.py): their command line, their files, and reading
the chapters' PFM images. A study measures into OUT/NAME.json and
writes its tables to OUT/NAME.md; --tables-only rewrites the tables from
the JSON; --tag T names them NAME-T.json and NAME-T.md instead (the same
study in another configuration, kept beside it). Standard library only, so
the studies run on the GPU machine too.
"""
import argparse
import json
import math
import os
import struct
import subprocess
import sys


def run_study(name, doc, measure, tables, add_options=None, check=None):
    """measure(args) -> data; tables(data) -> markdown. add_options(parser)
    declares the study's own options; check(args) returns "" or what is wrong."""
    p = argparse.ArgumentParser(description=doc.splitlines()[0])
    p.add_argument("--bin")
    p.add_argument("--out", required=True)
    p.add_argument("--tables-only", action="store_true")
    p.add_argument("--tag", default="")
    p.add_argument("--width", type=int, default=640)
    p.add_argument("--height", type=int, default=360)
    p.add_argument("--frames", type=int, default=10)
    p.add_argument("--repeat", type=int, default=3)
    if add_options:
        add_options(p)
    args = p.parse_args()
    tool = f"{name}_study.py"
    os.makedirs(args.out, exist_ok=True)
    if args.tag:
        if not args.tag.replace("_", "").isalnum():
            sys.exit(f"{tool}: --tag takes letters, digits and _ only: {args.tag!r}")
        name = f"{name}-{args.tag}"
    path = os.path.join(args.out, f"{name}.json")
    if args.tables_only:
        with open(path) as f:
            data = json.load(f)
    else:
        if not args.bin:
            sys.exit(f"{tool}: --bin is needed to measure (or --tables-only)")
        if min(args.width, args.height, args.frames, args.repeat) < 1:
            sys.exit(f"{tool}: --width, --height, --frames and --repeat must be at least 1")
        problem = check(args) if check else ""
        if problem:
            sys.exit(f"{tool}: {problem}")
        data = measure(args)
        with open(path, "w") as f:
            json.dump(data, f, indent=2)
            f.write("\n")
    out = os.path.join(args.out, f"{name}.md")
    text = tables(data)  # before the file is opened: a failure leaves the old one
    with open(out, "w") as f:
        f.write(text)
    print(f"wrote {out}")


def run_chapter(tool, exe, size, extra, png):
    """Runs a chapter headless at size (w, h) with the extra options, its
    picture into png (and .pfm), and returns its report; a failed run ends
    the study with its output."""
    cmd = [exe, "--headless", "--width", str(size[0]), "--height", str(size[1]), "--output", png] + extra
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        sys.exit(f"{tool}: {' '.join(cmd)} failed:\n{done.stdout}")
    with open(os.path.splitext(png)[0] + ".json") as f:
        report = json.load(f)
    if report.get("non_finite_values", 0):
        sys.exit(f"{tool}: {' '.join(cmd)}: {report['non_finite_values']} NaN or infinite values in the picture")
    return report


def rmse(a, b, pixels):
    """Linear RMSE of two read_pfm images over the pixels listed, all three channels."""
    n = a[2]
    if not pixels:
        return 0.0
    return math.sqrt(sum((a[3][n * i + c] - b[3][n * i + c]) ** 2 for i in pixels for c in range(3)) /
                     (3 * len(pixels)))


def read_pfm(path):
    """(width, height, channels, values) of a PFM image, bottom row first."""
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        channels = 3 if kind == b"PF" else 1
        values = struct.unpack(("<" if scale < 0 else ">") + "f" * (width * height * channels),
                               f.read(4 * width * height * channels))
    return width, height, channels, values


def srgb(v):
    v = min(1.0, max(0.0, v))
    return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055
