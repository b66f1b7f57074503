#!/usr/bin/python3
"""Every exercise (exercises/NN_name.glsl, tools/exercise.py) as a reader
meets it: the starter compiles and the chapter renders it (--shader-source,
headless, validation on), and its picture differs from the chapter's where
the stage shows (at least 0.5 % of pixels by more than 2 codes: the rough
lobe of chapter 11 is one small sphere's reflection, 1.2 % on lavapipe); the solution,
written into the same copy, draws the build's picture to the bit, so the
copy and --shader-source change nothing else (chapter 14 within one code:
its photons are stored in the order their atomics happen to run, so its
float sums may round differently from run to run). A starter broken by a typo
is refused with one line naming its file and line, exit 2, and so is a typo
in the copy's photon shader (chapter 15's photons are compiled from it).

    tests/test_exercises.py BUILD_BIN_DIR
"""
import json
import pathlib
import subprocess
import sys
import tempfile

import numpy
from PIL import Image

ROOT = pathlib.Path(__file__).resolve().parent.parent
SIZE = ["--width", "160", "--height", "90"]


def render(bin_dir, chapter, png, extra):
    run = subprocess.run([str(bin_dir / chapter), "--headless", "--validation", *SIZE, "--output", str(png),
                          *extra], cwd=ROOT, capture_output=True, text=True, timeout=600)
    if run.returncode != 0:
        raise AssertionError(f"{chapter} {' '.join(extra)}: exit {run.returncode}: {run.stdout[-400:]}{run.stderr[-400:]}")
    report = json.loads(png.with_suffix(".json").read_text())
    if report["validation_messages"] != 0:
        raise AssertionError(f"{chapter} {' '.join(extra)}: {report['validation_messages']} validation messages")
    return numpy.asarray(Image.open(png).convert("RGB")).astype(int)


def exercise(chapter, out, solution=False):
    args = [sys.executable, str(ROOT / "tools" / "exercise.py"), chapter, "--out", str(out), "--force"]
    subprocess.run(args + (["--solution"] if solution else []), check=True, capture_output=True)


def check(chapter, bin_dir, work):
    build = render(bin_dir, chapter, work / f"{chapter}_build.png", [])
    tree = work / f"exercise-{chapter}"
    exercise(chapter, tree)
    starter = render(bin_dir, chapter, work / f"{chapter}_starter.png", ["--shader-source", str(tree)])
    differ = (numpy.abs(starter - build).max(axis=2) > 2).mean()
    print(f"{chapter}: the starter differs from the chapter in {100 * differ:.1f} % of pixels")
    if differ < 0.005:
        return f"{chapter}: the starter draws the chapter's picture (only {100 * differ:.2f} % of pixels differ)"
    exercise(chapter, tree, solution=True)
    solved = render(bin_dir, chapter, work / f"{chapter}_solution.png", ["--shader-source", str(tree)])
    tolerance = 1 if chapter in ("14_caustics", "15_frosted_glass") else 0  # photons
    if (numpy.abs(solved - build) > tolerance).any():
        return f"{chapter}: the solution in the copy draws another picture than the build"
    return None


def broken(bin_dir, work):
    """A typo in a starter: one line with the file and line, exit 2."""
    tree = work / "exercise-broken"
    exercise("06_diffuse", tree)
    shading = tree / "shaders" / "common" / "shading.glsl"
    shading.write_text(shading.read_text().replace("vec3 sum = vec3(0.0);", "vec3 sum = vec3(0.0)", 1))
    run = subprocess.run([str(bin_dir / "06_diffuse"), "--headless", *SIZE, "--shader-source", str(tree),
                          "--output", str(work / "broken.png")], cwd=ROOT, capture_output=True, text=True, timeout=600)
    lines = [l for l in run.stderr.splitlines() if l.strip()]
    if run.returncode != 2 or len(lines) != 1 or "shaders/common/shading.glsl:100:" not in lines[0]:
        return f"a broken starter: exit {run.returncode}, {lines}"
    print(f"a broken starter: {lines[0]}")
    # a photon pass compiles from the copy too (chapter 15's caustics follow
    # the reader's facets): a typo there is refused the same way
    tree = work / "exercise-broken-photons"
    exercise("15_frosted_glass", tree)
    photons = tree / "shaders" / "15_frosted_glass" / "photon.rgen"
    photons.write_text(photons.read_text() + "a typo\n")
    run = subprocess.run([str(bin_dir / "15_frosted_glass"), "--headless", *SIZE, "--shader-source", str(tree),
                          "--output", str(work / "broken_photons.png")], cwd=ROOT, capture_output=True, text=True,
                         timeout=600)
    lines = [l for l in run.stderr.splitlines() if l.strip()]
    if run.returncode != 2 or len(lines) != 1 or "shaders/15_frosted_glass/photon.rgen:" not in lines[0]:
        return f"a broken photon shader: exit {run.returncode}, {lines}"
    print(f"a broken photon shader: {lines[0]}")
    return None


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    bin_dir = pathlib.Path(argv[1]).resolve()
    chapters = sorted(p.stem for p in (ROOT / "exercises").glob("*.glsl"))
    with tempfile.TemporaryDirectory(prefix="rayglass-exercises-") as folder:
        work = pathlib.Path(folder)
        problems = [check(c, bin_dir, work) for c in chapters] + [broken(bin_dir, work)]
    failures = [p for p in problems if p]
    print("".join(f"FAIL {p}\n" for p in failures), end="")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
