#!/usr/bin/python3
"""Numbers the chapter pages state about what a command gives, produced
again and compared with the page: a page whose number drifts from what its
command gives fails, and so does a change that moves the result away from
what the page says.

Each claim names its page, a pattern that finds the stated number in the
page's text (so the test reads the page's number, not a copy of it; a
claim in words, "no pixel", gives the number it means), the
command (a chapter from BUILD_BIN_DIR, headless, with --validation), how to
read the same number off the run's report or image, and how far apart the
two may be (about one pixel or one unit of the last digit the page gives).
Claims the page makes about lavapipe are skipped on another device.

    tests/test_page_numbers.py BUILD_BIN_DIR
"""
import json
import math
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time

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


BIN = None  # BUILD_BIN_DIR, for measures that run more commands
WORK = None  # main()'s folder: every run writes under it, and it goes at the end
FAR_FLOOR = ["--scene", "assets/scenes/far_floor.json", "--width", "480", "--height", "270"]


def read_pfm(path):
    """A colour PFM as linear RGB floats (tools/montage.py's reader)."""
    sys.path.insert(0, str(ROOT / "tools"))
    import montage
    return montage.read_pfm(str(path))


def rmse_from_64_rays(report, png):
    """Page 12's far floor: the RMSE (linear, all pixels and channels) of this
    run's picture from the same view with 64 rays a pixel at level 0."""
    truth = run_once(["12_triangle_meshes", *FAR_FLOOR, "--mips", "off", "--antialias", "on", "--frames", "64"])
    image = read_pfm(png.with_suffix(".pfm"))
    return float(numpy.sqrt(((image - read_pfm(truth.with_suffix(".pfm"))) ** 2).mean()))


FURNACE = ["--width", "64", "--height", "64", "--caustics", "off"]
# single scattering (16 frames) and compensated (256: its rough balls are grainier)
FURNACE_OFF = [*FURNACE, "--frames", "16", "--multiple-scattering", "off"]
FURNACE_ON = [*FURNACE, "--frames", "256", "--multiple-scattering", "on"]


def furnace_loss(roughness, args):
    """Page 15's white furnace: the per cent of the sky's light a rough glass
    ball (furnace.json at `roughness`) loses, from the mean over its inner
    disc at 64x64 (tests/test_15_frosted_glass.cpp's measure), run with
    `args` (FURNACE_OFF or FURNACE_ON)."""
    def measure(report, png):
        scene = json.loads((ROOT / "assets" / "scenes" / "furnace.json").read_text())
        out = png  # the claim's own run: furnace.json as it is
        if scene["materials"]["rough_glass"]["roughness"] != roughness:
            scene["materials"]["rough_glass"]["roughness"] = roughness
            path = WORK / f"furnace_scene_{roughness}.json"
            path.write_text(json.dumps(scene))
            out = run_once(["15_frosted_glass", "--scene", str(path), *args])
        image = read_pfm(out.with_suffix(".pfm"))
        h, w = image.shape[:2]
        ys, xs = numpy.mgrid[0:h, 0:w]
        disc = numpy.hypot(xs + 0.5 - w / 2, ys + 0.5 - h / 2) <= 0.25 * w
        return 100 * (1 - float(image[disc].mean()))
    return measure


# Page 11's progressive table: rough.json at 160x90, one sample per hit and
# frame, against one CPU reference of 16,384 samples per rough hit (made
# once, by the command the page prints).
ROUGH = ["--scene", "assets/scenes/rough.json", "--width", "160", "--height", "90", "--samples", "1"]
ROUGH_REFERENCE = ["--frames", "256", "--pattern", "sobol", "--reference", "--reference-samples", "16384"]
_rough = {}


def run_once(command, timeout=600):
    """The PNG that `command` (chapter, then its arguments) wrote, run
    headless with validation under main()'s folder, once for all the
    claims and measures that name it."""
    key = tuple(command)
    if key not in _runs:
        png = WORK / f"run{len(_runs)}" / f"{command[0]}.png"
        png.parent.mkdir()
        args = [str(BIN / command[0]), "--headless", "--validation", *command[1:], "--output", str(png)]
        start = time.monotonic()
        run = subprocess.run(args, cwd=ROOT, capture_output=True, text=True, timeout=timeout)
        took = time.monotonic() - start
        if took > 5:  # where the test's time goes
            print(f"  ran {' '.join(command)} in {took:.1f} s", flush=True)
        if run.returncode != 0:
            raise RuntimeError(f"{' '.join(command)}: exit {run.returncode}: {run.stdout[-300:]}{run.stderr[-300:]}")
        _runs[key] = png
    return _runs[key]


def reference_image(command):
    """The CPU reference that `command` (which asks for --reference) wrote."""
    png = run_once(command, timeout=900)
    return read_pfm(png.with_name(png.stem + "_reference.pfm"))


def rough_rmse(pattern, frames, png=None):
    """The RMSE (linear, as the chapter's report) of `pattern` after
    `frames` (the run that wrote `png`, or the table's own run) against the
    shared reference."""
    reference = reference_image(["11_rough", *ROUGH, *ROUGH_REFERENCE])
    if png is None:
        png = run_once(["11_rough", *ROUGH, "--pattern", pattern, "--frames", str(frames)])
    return float(numpy.sqrt(((read_pfm(png.with_suffix(".pfm")) - reference) ** 2).mean()))


def rough_table(row, column):
    """A cell of page 11's table: the RMSE after 1, 16, 64 or 256 frames,
    or the slope of log RMSE over log frames from 16 to 256."""
    pattern = {"uniform": "uniform", "Hammersley": "hammersley", "Sobol (default)": "sobol"}[row]
    frames = [1, 16, 64, 256, 256][column]
    cells = r"[-0-9.e]+ \| " * column

    def measure(report, png):
        if column < 4:
            return rough_rmse(pattern, frames, png)
        return math.log(rough_rmse(pattern, 256, png) / rough_rmse(pattern, 16)) / math.log(256 / 16)
    return {"page": "11_rough.md", "pattern": r"\| " + re.escape(row) + r" \| " + cells + r"([-0-9.e]+) \|",
            "command": ["11_rough", *ROUGH, "--pattern", pattern, "--frames", str(frames)], "measure": measure,
            "lavapipe": True, "tolerance": "last digit"}


# Page 13's prism: its spectrum after N frames against a reference of 4,096
# (as tools/real_glass_study.py's convergence study, at 80x45), made once.
PRISM = ["--scene", "assets/scenes/prism.json", "--width", "80", "--height", "45"]


def prism_error(frames, png=None):
    """(RMSE, fraction of pixels off by more than 1/255 in sRGB) of the
    prism after `frames` against the 4,096-frame reference."""
    reference = reference_image(["13_real_glass", *PRISM, "--frames", "4096", "--reference"])
    if png is None:
        png = run_once(["13_real_glass", *PRISM, "--frames", str(frames)])
    image = read_pfm(png.with_suffix(".pfm"))
    srgb = lambda x: numpy.where(x <= 0.0031308, 12.92 * x, 1.055 * numpy.power(numpy.maximum(x, 0), 1 / 2.4) - 0.055)
    off = (numpy.abs(srgb(numpy.clip(image, 0, 1)) - srgb(numpy.clip(reference, 0, 1))).max(axis=-1) > 1 / 255).mean()
    return float(numpy.sqrt(((image - reference) ** 2).mean())), float(off)


def prism_slope(report, png):
    """The log-log slope of the prism's RMSE against frames, fitted from 4
    to 256 frames (the study's fit)."""
    points = [(math.log(f), math.log(prism_error(f, png if f == 256 else None)[0])) for f in (4, 8, 16, 32, 64, 128, 256)]
    n, sx, sy = len(points), sum(p[0] for p in points), sum(p[1] for p in points)
    sxx, sxy = sum(p[0] ** 2 for p in points), sum(p[0] * p[1] for p in points)
    return (n * sxy - sx * sy) / (n * sxx - sx * sx)


def rmse(page, pattern, command, tolerance, lavapipe=True):
    """A claim of the reference error's RMSE (linear)."""
    return {"page": page, "pattern": pattern, "command": command, "tolerance": tolerance,
            "measure": lambda report, png: report["error"]["rmse"], "lavapipe": lavapipe}


def rays(page, pattern, command, tolerance, scale=1, lavapipe=False):
    """A claim of rays a frame (in units of `scale`: 1e6 for "million")."""
    return {"page": page, "pattern": pattern, "command": command, "tolerance": tolerance,
            "measure": lambda report, png: report["rays_per_frame"] / scale, "lavapipe": lavapipe}


def pixels_off(page, pattern, command, tolerance, lavapipe=True):
    """A claim of the % of pixels off the reference by more than 1/255."""
    return {"page": page, "pattern": pattern, "command": command, "tolerance": tolerance,
            "measure": lambda report, png: 100 * report["error"]["frac_over_1_255"], "lavapipe": lavapipe}


def wrong_lobe(work):
    """Page 11's Try-it "The wrong lobe": the shaders with lobeDirection's
    cosTheta line replaced as the page says, run by --shader-source."""
    tree = work / "wrong_lobe"
    if not tree.exists():
        shutil.copytree(ROOT / "shaders", tree / "shaders")
        (tree / "shared").mkdir()
        shutil.copy(ROOT / "shared" / "host_device.h", tree / "shared")
        glsl = tree / "shaders" / "common" / "sampling.glsl"
        right = "    float cosTheta = 1.0 - u.x * (1.0 - cosMax);\n"
        text = glsl.read_text()
        if right not in text:
            raise AssertionError("sampling.glsl no longer has the line page 11 replaces")
        glsl.write_text(text.replace(right, "    float cosTheta = cos(u.x * roughness * 0.5 * kPi);\n"))
    return ["--shader-source", str(tree)]


CLAIM_BALL_LENS = {
    "page": "10_refraction.md",
    "pattern": r"markers appear inverted, ([0-9.]+)\s+pixels from the centre",
    "command": ["10_refraction", "--scene", "tests/optics/ball_lens.json", "--width", "500", "--height", "500"],
    "measure": marker_distance,
    "tolerance": 0.25,  # a quarter of a pixel
}

def acceleration_bytes(structure, key):
    """Page 03's sample output (lavapipe): a structure's bytes from the report."""
    def measure(report, png):
        if structure == "tlas":
            return report["tlas"][key]
        return next(b[key] for b in report["blas"] if b["name"] == structure)
    return measure


CLAIMS = [
    CLAIM_BALL_LENS,
    # page 03's "What it prints" on lavapipe: the structures' sizes (the times vary)
    *[{"page": "03_acceleration_structures.md", "pattern": pattern, "command": ["03_acceleration_structures"],
       "measure": acceleration_bytes(structure, key), "tolerance": 0, "lavapipe": True}
      for pattern, structure, key in (
          (r"unit_quad    triangles +([0-9]+) ", "unit_quad", "size_bytes"),
          (r"unit_quad    triangles +[0-9]+ +([0-9]+) ", "unit_quad", "compacted_bytes"),
          (r"unit_sphere  aabbs +([0-9]+) ", "unit_sphere", "size_bytes"),
          (r"unit_sphere  aabbs +[0-9]+ +([0-9]+) ", "unit_sphere", "compacted_bytes"),
          (r"tlas         instances +([0-9]+) ", "tlas", "size_bytes"),
          (r"\(5 instances, update scratch ([0-9]+) bytes\)", "tlas", "update_scratch_bytes"))],
    {**CLAIM_BALL_LENS, "pattern": r"and chapter 10 puts them at ([0-9.]+) \(",
     "command": ["10_refraction", "--scene", "tests/optics/ball_lens.json", "--width", "1000", "--height", "1000"],
     "tolerance": 0.5},  # the page's last digit
    pixels_off("12_triangle_meshes.md",
               r"reference:\s+([0-9.]+) % of pixels off by more than 1/255 on lavapipe",
               ["12_triangle_meshes", "--reference", "--width", "320", "--height", "180"],
               0.002),  # about one pixel of 57,600
    rays("12_triangle_meshes.md", r"at 800x450:\s+([0-9.]+) million rays a frame instead of",
         ["12_triangle_meshes", "--depth", "2"], 0.01, scale=1e6, lavapipe=True),
    rays("12_triangle_meshes.md", r"rays a frame instead of\s+([0-9.]+)\s+million",
         ["12_triangle_meshes"], 0.01, scale=1e6, lavapipe=True),
    rays("04_raygen_miss.md", r"`GPU median \.\.\. ms over 10 frames, ([0-9]+) rays per\s+frame`",
         ["04_raygen_miss", "--reference"], 0),  # one ray per pixel
    pixels_off("04_raygen_miss.md", r"rmse [0-9.e-]+, \.\.\. ([0-9.]+)% of pixels off by > 1/255`",
               ["04_raygen_miss", "--reference"], 0.00005),  # the page's last digit
    rays("05_ambient.md", r"`([0-9]+) rays per frame` and a reference error", ["05_ambient", "--reference"], 0),
    pixels_off("05_ambient.md", r"RMSE, ([0-9.]+) % of pixels off", ["05_ambient", "--reference"], 0.005),
    rmse("05_ambient.md", r"reference error of\s+about ([0-9.e-]+) RMSE", ["05_ambient", "--reference"], 1e-7),
    rays("06_diffuse.md", r"about ([0-9 ]+) rays per frame \(the camera rays plus",
         ["06_diffuse", "--reference"], 5000),  # "about 730 000": the page's last digit
    rmse("06_diffuse.md", r"reference RMSE of about ([0-9.e-]+)\.", ["06_diffuse", "--reference"], 1e-7),
    # page 06's fixed epsilons: the scaled scenes of its figures, and its Try-it
    *[pixels_off("06_diffuse.md", pattern, ["06_diffuse", "--reference", "--scene", f"tests/scenes/scaled_{scale}.json",
                                            "--fixed-epsilon", "1e-3", "--width", "480", "--height", "270"], 0.1)
      for pattern, scale in ((r"under the spheres \(([0-9.]+) % of pixels wrong\)", "1e-3"),
                             (r"acne all over the spheres \(([0-9.]+) % wrong\)", "1e5"))],
    *[pixels_off("06_diffuse.md", pattern, ["06_diffuse", "--reference", "--fixed-epsilon", epsilon], 0.1)
      for pattern, epsilon in ((r"start on \(([0-9.]+) % of pixels off the", "1e-9"),
                               (r"detach from the spheres \(([0-9.]+) % off\)", "0.05"))],
    # ... and what --numerics fast does to the scenes that need care (test_metamorphic's runs)
    *[pixels_off("06_diffuse.md", pattern, [chapter, "--reference", "--frames", "1", "--width", "160", "--height", "90",
                                            "--scene", f"tests/scenes/{scene}.json", "--numerics", "fast"],
                 tolerance)  # the page's last digit
      for pattern, chapter, scene, tolerance in (
          (r"\(([0-9.]+) and [0-9.]+ % of pixels off at\s+160x90\)", "06_diffuse", "ground_sphere_1e5", 1.0),
          (r"\([0-9.]+ and ([0-9.]+) % of pixels off at\s+160x90\)", "06_diffuse", "sky_dome_1e20", 1.0),
          (r"`shininess_1e6` \(([0-9.]+) %\)", "07_specular", "shininess_1e6", 0.1))],
    rays("07_specular.md", r"chapter 06, about ([0-9 ]+)\s", ["07_specular", "--reference"], 1000),
    rmse("07_specular.md", r"reference RMSE of\s+about ([0-9.e-]+)\.", ["07_specular", "--reference"], 1e-7),
    rays("08_reflection.md", r"\(about ([0-9 ]+):\s+the reflected rays\)", ["08_reflection", "--reference"], 1000),
    rmse("08_reflection.md", r"reference RMSE of about ([0-9.e-]+) \(no pixel", ["08_reflection", "--reference"],
         5e-7),
    {**pixels_off("08_reflection.md", r"\(no pixel off by more\s+than 1/255\)", ["08_reflection", "--reference"], 0),
     "value": 0.0},  # "no pixel": 0 %
    rays("09_fresnel.md", r"then about ([0-9 ]+)\s+rays per frame",
         ["09_fresnel", "--scene", "assets/scenes/glass_sphere.json", "--fresnel", "exact"], 1000),
    rays("10_refraction.md", r"the first command prints about ([0-9.]+) million rays",
         ["10_refraction", "--scene", "assets/scenes/glass_sphere.json"], 0.05, scale=1e6),
    rays("10_refraction.md", r"default scene eight bounces deep, about ([0-9.]+) million",
         ["10_refraction", "--fresnel", "exact", "--depth", "8"], 0.005, scale=1e6),
    pixels_off("13_real_glass.md", r"reference of ([0-9.]+) % of pixels off by more\s+than 1/255",
               ["13_real_glass", "--reference", "--width", "320", "--height", "180"],
               0.002),  # about one pixel of 57,600
    {"page": "12_triangle_meshes.md", "pattern": r"64-ray picture is\s+([0-9.]+) at full size",
     "command": ["12_triangle_meshes", *FAR_FLOOR, "--mips", "off"], "measure": rmse_from_64_rays,
     "tolerance": 0.0005, "lavapipe": True},
    {"page": "12_triangle_meshes.md", "pattern": r"at full size and\s+([0-9.]+) with ray cones",
     "command": ["12_triangle_meshes", *FAR_FLOOR], "measure": rmse_from_64_rays,
     "tolerance": 0.0005, "lavapipe": True},
    pixels_off("14_caustics.md", r"prints an error of ([0-9.]+) % of pixels off by more\s+than 1/255",
               ["14_caustics", "--reference", "--width", "160", "--height", "90", "--frames", "32",
                "--photons", "400000", "--radius", "0.05", "--alpha", "1"],
               0.007),  # one pixel of 14,400
    # page 15's one branch against both: rays a frame ("about": the nearest thousand)
    *[rays("15_frosted_glass.md", pattern, ["15_frosted_glass", "--width", "640", "--height", "360", "--frames", "8",
                                            *more], 1000, lavapipe=True)
      for pattern, more in ((r"The first run prints about ([0-9,]+)\s+rays a frame", []),
                            (r"the second about ([0-9,]+):", ["--rough-branches", "both"]))],
    pixels_off("15_frosted_glass.md", r"\n  ([0-9.]+) % of pixels by more than 1/255 on lavapipe",
               ["15_frosted_glass", "--reference", "--width", "160", "--height", "90", "--frames", "4",
                "--caustics", "off", "--max-bounces", "64"], 0.007),  # one pixel of 14,400
    # page 15's white furnace: the loss at each roughness the page gives
    *[{"page": "15_frosted_glass.md", "pattern": pattern,
       "command": ["15_frosted_glass", "--scene", "assets/scenes/furnace.json", *args],
       "measure": furnace_loss(roughness, args), "lavapipe": True,
       # 1 % of the light lost without compensation; with it, the last digit
       "tolerance": 1.0 if args is FURNACE_OFF else 0.15}
      for roughness, args, pattern in (
          (0.1, FURNACE_OFF, r"a loss of ([0-9.]+) % at roughness 0.1"),
          (0.3, FURNACE_OFF, r"([0-9.]+) % at 0.3"), (0.6, FURNACE_OFF, r"([0-9.]+) % at 0.6"),
          (1.0, FURNACE_OFF, r"([0-9.]+) % at 1.0 for the glass ball"),
          # ... and compensated (the page's section on multiple scattering)
          (0.3, FURNACE_ON, r"measures a loss of ([0-9.]+) % at roughness 0.3"),
          (0.6, FURNACE_ON, r"([0-9.]+) %\s+at 0.6 and [0-9.]+ % at 1.0 for the compensated"),
          (1.0, FURNACE_ON, r"([0-9.]+) % at 1.0 for the compensated"))],
    # page 11's progressive table (every cell) and its Try-it
    *[rough_table(row, column) for row in ("uniform", "Hammersley", "Sobol (default)") for column in range(5)],
    *[rmse("11_rough.md", pattern, ["11_rough", "--reference", "--samples", samples, "--frames", frames],
           "last digit") for pattern, samples, frames in (
        (r"\(RMSE ([0-9.e-]+) both on lavapipe", "1", "64"), (r"\(RMSE ([0-9.e-]+) both on lavapipe", "64", "1"))],
    {"page": "11_rough.md", "pattern": r"of which ([0-9.e-]+) is\s+the reference's own",
     "command": ["11_rough", "--reference", "--samples", "64", "--frames", "1"], "tolerance": "last digit",
     "measure": lambda report, png: report["error"]["reference_std_error_rms"], "lavapipe": True},
    *[rmse("11_rough.md", pattern, ["11_rough", "--reference", "--samples", samples, "--frames", frames,
                                    "--pattern", "stratified", "--width", "160", "--height", "90"], "last digit")
      for pattern, samples, frames in ((r"64\s+frames of one sample give ([0-9.e-]+)", "1", "64"),
                                       (r"one frame of 64 stratified samples\s+([0-9.e-]+)", "64", "1"))],
    *[rmse("11_rough.md", r"\(at 160x90: " + r"[0-9.e-]+, " * k + r"([0-9.e-]+)",
           ["11_rough", "--samples", "4", "--frames", "1", "--reference", "--pattern", pattern, "--width", "160",
            "--height", "90"], "last digit") for k, pattern in enumerate(("uniform", "stratified", "hammersley"))],
    *[rmse("11_rough.md", pattern, ["11_rough", "--width", "160", "--height", "90", "--frames", "1",
                                    "--no-accumulate", "--samples", "4", "--reference", "--reference-samples", "4096",
                                    "--scene", f"assets/scenes/{scene}.json", "--pattern", sampling], "last digit")
      for pattern, scene, sampling in (
          (r"Hammersley's RMSE\s+is ([0-9.e-]+) against", "rough_sky", "hammersley"),
          (r"against uniform's ([0-9.e-]+) \(", "rough_sky", "uniform"),
          (r"on the scene with edges\s+([0-9.e-]+) against", "rough", "hammersley"),
          (r"on the scene with edges\s+[0-9.e-]+ against ([0-9.e-]+) \(", "rough", "uniform"))],
    # the wrong lobe (the Try-it's edit of sampling.glsl) and the right one
    *[{**rmse("11_rough.md", pattern, ["11_rough", "--reference", "--width", "160", "--height", "90", "--samples",
                                       "16", "--frames", frames], "last digit"), "prepare": wrong_lobe}
      for pattern, frames in ((r"RMSE ([0-9.e-]+) after one frame and", "1"),
                              (r"after one frame and ([0-9.e-]+) after 16", "16"))],
    *[rmse("11_rough.md", pattern, ["11_rough", "--reference", "--width", "160", "--height", "90", "--samples",
                                    "16", "--frames", frames], "last digit")
      for pattern, frames in ((r"\(the right\s+lobe: ([0-9.e-]+) and", "1"),
                              (r"lobe: [0-9.e-]+ and ([0-9.e-]+)\)", "16"))],
    rays("13_real_glass.md", r"against ([0-9.]+) million for\s+chapter 10's rule",
         ["12_triangle_meshes", "--scene", "assets/scenes/real_glass.json", "--width", "400", "--height", "225",
          "--depth", "8", "--fresnel", "exact"], 0.01, scale=1e6, lavapipe=True),
    # page 13's prism, converging
    *[{"page": "13_real_glass.md", "pattern": pattern, "command": ["13_real_glass", *PRISM, "--frames", frames],
       "measure": measure, "tolerance": "last digit", "lavapipe": True}
      for pattern, frames, measure in (
          (r"RMSE falls from ([0-9.e-]+)\s+after one frame", "1", lambda r, png: prism_error(1, png)[0]),
          (r"after one frame to ([0-9.e-]+)\s+after 16", "16", lambda r, png: prism_error(16, png)[0]),
          (r"after 16 and ([0-9.e-]+) after 256", "256", lambda r, png: prism_error(256, png)[0]),
          (r"\(a log-log slope of ([-0-9.]+)\s+from 4", "256", prism_slope),
          (r"after 256 frames ([0-9.]+) % of the pixels", "256", lambda r, png: 100 * prism_error(256, png)[1]))],
    rays("13_real_glass.md", r"this chapter traces ([0-9.]+) million\s+rays a frame",
         ["13_real_glass", "--width", "400", "--height", "225"], 0.01, scale=1e6,
         lavapipe=True),  # the page's last digit
]


def last_digit(stated_text):
    """One unit of the last digit a page gives: "1.05e-3" -> 1e-5."""
    mantissa, _, exponent = stated_text.partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 10.0 ** (-decimals + (int(exponent) if exponent else 0))


_runs = {}  # command -> the PNG its run wrote


def check(claim, work):
    text = (ROOT / "docs" / claim["page"]).read_text()
    found = re.search(claim["pattern"], text)
    if not found:
        return f"{claim['page']}: no longer says /{claim['pattern']}/"
    # "730 000", "598,000"; a claim in words ("no pixel") gives its value
    stated = claim["value"] if "value" in claim else float(found.group(1).replace(" ", "").replace(",", ""))
    name = claim["command"][0]
    extra = claim["prepare"](work) if "prepare" in claim else []
    # claims that name the same command read the same run
    try:
        png = run_once([*claim["command"], *extra])
    except RuntimeError as error:
        return f"{claim['page']}: {error}"
    report = json.loads(png.with_suffix(".json").read_text())
    if report["validation_messages"] != 0:
        return f"{claim['page']}: {name}: {report['validation_messages']} validation messages"
    if claim.get("lavapipe") and "llvmpipe" not in report["device"]:
        print(f"skipped {claim['page']}: it states a lavapipe number, this is {report['device']}")
        return None
    try:
        measured = claim["measure"](report, png)
    except RuntimeError as error:  # a run the measure needs
        return f"{claim['page']}: {error}"
    tolerance = claim["tolerance"]
    if tolerance == "last digit":
        tolerance = last_digit(found.group(1))
    print(f"{claim['page']}: states {stated}, the run gives {measured:.4g} (tolerance {tolerance:g})")
    if abs(measured - stated) > tolerance:
        return f"{claim['page']}: states {stated}, but {' '.join(claim['command'])} gives {measured:.4g}"
    return None


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    global BIN, WORK
    BIN = pathlib.Path(argv[1]).resolve()
    failures = []
    with tempfile.TemporaryDirectory(prefix="rayglass-numbers-") as work:
        WORK = pathlib.Path(work)
        for claim in CLAIMS:
            problem = check(claim, WORK)
            if problem:
                failures.append(problem)
                print("FAIL " + problem)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
