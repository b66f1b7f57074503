#!/usr/bin/python3
"""Numbers the chapter pages state about what a command gives, produced
again and compared with the page: a page whose number drifts from what its
command gives fails, and so does a change that moves the result away from
what the page says.

Each claim names its page, a pattern that finds the stated number in the
page's text (so the test reads the page's number, not a copy of it), the
command (a chapter from BUILD_BIN_DIR, headless, with --validation), how to
read the same number off the run's report or image, and how far apart the
two may be (about one pixel or one unit of the last digit the page gives).
Claims the page makes about lavapipe are skipped on another device.

    tests/test_page_numbers.py BUILD_BIN_DIR
"""
import json
import pathlib
import re
import subprocess
import sys
import tempfile

import numpy
from PIL import Image

ROOT = pathlib.Path(__file__).resolve().parent.parent


def marker_distance(report, png):
    """Page 10's ball lens: the mean distance of the red, blue and green
    markers' centroids from the image's centre, in pixels."""
    rgb = numpy.asarray(Image.open(png).convert("RGB")).astype(int)
    h, w, _ = rgb.shape
    hi, lo = rgb > 150, rgb < 80
    distances = []
    for c in range(3):
        mask = hi[..., c] & lo[..., (c + 1) % 3] & lo[..., (c + 2) % 3]
        ys, xs = numpy.nonzero(mask)
        near = numpy.hypot(xs + 0.5 - w / 2, ys + 0.5 - h / 2) < w / 8
        if not near.any():
            raise AssertionError(f"no marker of colour {c} near the centre")
        distances.append(numpy.hypot(xs[near].mean() + 0.5 - w / 2, ys[near].mean() + 0.5 - h / 2))
    return float(numpy.mean(distances))


CLAIMS = [
    {
        "page": "10_refraction.md",
        "pattern": r"markers appear inverted, ([0-9.]+)\s+pixels from the centre",
        "command": ["10_refraction", "--scene", "tests/optics/ball_lens.json", "--width", "500", "--height", "500"],
        "measure": marker_distance,
        "tolerance": 0.25,  # a quarter of a pixel
    },
    {
        "page": "12_triangle_meshes.md",
        "pattern": r"reference:\s+([0-9.]+) % of pixels off by more than 1/255 on lavapipe",
        "command": ["12_triangle_meshes", "--reference", "--width", "320", "--height", "180"],
        "measure": lambda report, png: 100 * report["error"]["frac_over_1_255"],
        "tolerance": 0.002,  # about one pixel of 57,600
        "lavapipe": True,
    },
    {
        "page": "12_triangle_meshes.md",
        "pattern": r"at 800x450:\s+([0-9.]+) million rays a frame instead of",
        "command": ["12_triangle_meshes", "--depth", "2"],
        "measure": lambda report, png: report["rays_per_frame"] / 1e6,
        "tolerance": 0.01,
        "lavapipe": True,
    },
    {
        "page": "12_triangle_meshes.md",
        "pattern": r"rays a frame instead of\s+([0-9.]+)\s+million",
        "command": ["12_triangle_meshes"],
        "measure": lambda report, png: report["rays_per_frame"] / 1e6,
        "tolerance": 0.01,
        "lavapipe": True,
    },
    {
        "page": "04_raygen_miss.md",
        "pattern": r"`GPU median \.\.\. ms over 10 frames, ([0-9]+) rays per\s+frame`",
        "command": ["04_raygen_miss", "--reference"],
        "measure": lambda report, png: report["rays_per_frame"],
        "tolerance": 0,  # one ray per pixel
    },
    {
        "page": "04_raygen_miss.md",
        "pattern": r"rmse [0-9.e-]+, \.\.\. ([0-9.]+)% of pixels off by > 1/255`",
        "command": ["04_raygen_miss", "--reference"],
        "measure": lambda report, png: 100 * report["error"]["frac_over_1_255"],
        "tolerance": 0.00005,  # the page's last digit
        "lavapipe": True,
    },
    {
        "page": "05_ambient.md",
        "pattern": r"`([0-9]+) rays per frame` and a reference error",
        "command": ["05_ambient", "--reference"],
        "measure": lambda report, png: report["rays_per_frame"],
        "tolerance": 0,
    },
    {
        "page": "05_ambient.md",
        "pattern": r"RMSE, ([0-9.]+) % of pixels off",
        "command": ["05_ambient", "--reference"],
        "measure": lambda report, png: 100 * report["error"]["frac_over_1_255"],
        "tolerance": 0.005,
        "lavapipe": True,
    },
    {
        "page": "06_diffuse.md",
        "pattern": r"about ([0-9 ]+) rays per frame \(the camera rays plus",
        "command": ["06_diffuse", "--reference"],
        "measure": lambda report, png: report["rays_per_frame"],
        "tolerance": 5000,  # "about 730 000": the page's last digit
    },
    {
        "page": "09_fresnel.md",
        "pattern": r"then about ([0-9 ]+)\s+rays per frame",
        "command": ["09_fresnel", "--scene", "assets/scenes/glass_sphere.json", "--fresnel", "exact"],
        "measure": lambda report, png: report["rays_per_frame"],
        "tolerance": 1000,
    },
    {
        "page": "10_refraction.md",
        "pattern": r"the first command prints about ([0-9.]+) million rays",
        "command": ["10_refraction", "--scene", "assets/scenes/glass_sphere.json"],
        "measure": lambda report, png: report["rays_per_frame"] / 1e6,
        "tolerance": 0.05,
    },
    {
        "page": "10_refraction.md",
        "pattern": r"default scene eight bounces deep, about ([0-9.]+) million",
        "command": ["10_refraction", "--fresnel", "exact", "--depth", "8"],
        "measure": lambda report, png: report["rays_per_frame"] / 1e6,
        "tolerance": 0.005,
    },
    {
        "page": "13_real_glass.md",
        "pattern": r"reference of ([0-9.]+) % of pixels off by more\s+than 1/255",
        "command": ["13_real_glass", "--reference", "--width", "320", "--height", "180"],
        "measure": lambda report, png: 100 * report["error"]["frac_over_1_255"],
        "tolerance": 0.002,  # about one pixel of 57,600
        "lavapipe": True,
    },
    {
        "page": "13_real_glass.md",
        "pattern": r"this chapter traces ([0-9.]+) million\s+rays a frame",
        "command": ["13_real_glass", "--width", "800", "--height", "450"],
        "measure": lambda report, png: report["rays_per_frame"] / 1e6,
        "tolerance": 0.01,  # the page's last digit
        "lavapipe": True,
    },
]


def check(claim, bin_dir, work):
    text = (ROOT / "docs" / claim["page"]).read_text()
    found = re.search(claim["pattern"], text)
    if not found:
        return f"{claim['page']}: no longer says /{claim['pattern']}/"
    stated = float(found.group(1).replace(" ", ""))  # "730 000"
    name = claim["command"][0]
    png = work / f"{name}.png"
    args = [str(bin_dir / name), "--headless", "--validation", *claim["command"][1:], "--output", str(png)]
    run = subprocess.run(args, cwd=ROOT, capture_output=True, text=True, timeout=600)
    if run.returncode != 0:
        return f"{claim['page']}: {' '.join(claim['command'])}: exit {run.returncode}: {run.stdout[-300:]}{run.stderr[-300:]}"
    report = json.loads(png.with_suffix(".json").read_text())
    if report["validation_messages"] != 0:
        return f"{claim['page']}: {name}: {report['validation_messages']} validation messages"
    if claim.get("lavapipe") and "llvmpipe" not in report["device"]:
        print(f"skipped {claim['page']}: it states a lavapipe number, this is {report['device']}")
        return None
    measured = claim["measure"](report, png)
    print(f"{claim['page']}: states {stated}, the run gives {measured:.4g} (tolerance {claim['tolerance']})")
    if abs(measured - stated) > claim["tolerance"]:
        return f"{claim['page']}: states {stated}, but {' '.join(claim['command'])} gives {measured:.4g}"
    return None


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    bin_dir = pathlib.Path(argv[1]).resolve()
    failures = []
    with tempfile.TemporaryDirectory(prefix="rayglass-numbers-") as work:
        for claim in CLAIMS:
            problem = check(claim, bin_dir, pathlib.Path(work))
            if problem:
                failures.append(problem)
                print("FAIL " + problem)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
