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
import re
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


# Two wrong answers a learner might write per exercise, each one edit of the
# solution (text in the solution's region -> what the learner wrote), which
# `tools/exercise.py --check` must call wrong.
WRONG = {
    "05_ambient": [("m.ka.rgb * camera.ambient.rgb", "camera.ambient.rgb", "k_a left out"),
                   ("m.ka.rgb * camera.ambient.rgb", "m.ka.rgb", "I_a left out")],
    "06_diffuse": [("if (lightVisible(origin, lights[i].position.xyz))", "if (true)", "no shadow ray"),
                   ("safeNormalize(lights[i].position.xyz - p)", "safeNormalize(p - lights[i].position.xyz)",
                    "l pointing away from the light")],
    "07_specular": [("return pow(cosine, shininess);", "return pow(shininess, cosine);", "pow's arguments swapped"),
                    ("return pow(cosine, shininess);", "return cosine;", "the power left out")],
    "08_reflection": [("throughput *= mirror;", "", "the throughput not multiplied by the mirror's share"),
                      ("origin = secondaryOrigin(payload.position, payload.error, n);",
                       "origin = payload.position;", "the origin not moved off the surface")],
    "09_fresnel": [("dot(n, -direction), n1, n2)", "dot(n, direction), n1, n2)", "cos i of the wrong sign"),
                   ("float reflected = transmission * F + (1.0 - transmission) * m.params.y;",
                    "float reflected = F;", "F for the opaque part too")],
    "10_refraction": [("o = secondaryOrigin(p, e, -n);", "o = secondaryOrigin(p, e, n);",
                       "the origin moved to the near side"),
                      ("refractedDirection(b.direction, n, ns, s.eta)", "b.direction", "the ray not bent")],
    "11_rough": [("radiance += sum / float(count);", "radiance += sum;", "the sum, not the mean"),
                 ("lobeDirection(mirror, roughness,", "lobeDirection(mirror, 2.0 * roughness,",
                  "a lobe twice as wide")],
    "13_real_glass": [("return exp(-sigma * t);", "return exp(-sigma);", "the distance left out"),
                      ("return exp(-sigma * t);", "return exp(sigma * t);", "the exponent's sign")],
    "14_caustics": [("for (uint k = 0u; k < 8u; ++k) {", "for (uint k = 0u; k < 1u; ++k) {", "one cell read"),
                    ("return sum / (kPi * r * r);", "return sum / (4.0 * kPi * r * r);",
                     "over a sphere's area, not the disc's")],
    "15_frosted_glass": [("return normalize(vec3(h.x * alpha, h.y * alpha, max(h.z, 0.0f)));",
                          "return normalize(h);", "not stretched back"),
                         ("vec3 h = vec3(s * cos(phi), s * sin(phi), z) + stretched;",
                          "vec3 h = vec3(s * cos(phi), s * sin(phi), z);", "the cap not moved by wo")],
}


def run_check(chapter, tree, bin_dir):
    run = subprocess.run([sys.executable, str(ROOT / "tools" / "exercise.py"), chapter, "--out", str(tree),
                          "--check", "--bin", str(bin_dir)], capture_output=True, text=True, timeout=900)
    return run.returncode, (run.stdout + run.stderr).strip()


def check(chapter, bin_dir, work):
    tree = work / f"exercise-{chapter}"
    exercise(chapter, tree)
    text = (ROOT / "exercises" / f"{chapter}.glsl").read_text()
    file = re.search(r"^// replaces: (\S+)#", text, re.M).group(1)
    code, said = run_check(chapter, tree, bin_dir)
    print(f"{chapter}, the starter: {said}")
    if code != 1:
        return f"{chapter}: --check says of the starter: {said}"
    # the starter differs where the stage shows
    build = numpy.asarray(Image.open(bin_dir.parent / "exercise-check" / f"{chapter}.png").convert("RGB")).astype(int)
    starter = numpy.asarray(Image.open(tree / "check" / "yours.png").convert("RGB")).astype(int)
    differ = (numpy.abs(starter - build).max(axis=2) > 2).mean()
    if differ < 0.005:
        return f"{chapter}: the starter draws the chapter's picture (only {100 * differ:.2f} % of pixels differ)"
    exercise(chapter, tree, solution=True)
    code, said = run_check(chapter, tree, bin_dir)
    print(f"{chapter}, the solution: {said}")
    if code != 0:
        return f"{chapter}: --check says of the solution: {said}"
    solved = numpy.asarray(Image.open(tree / "check" / "yours.png").convert("RGB")).astype(int)
    tolerance = 1 if chapter in ("14_caustics", "15_frosted_glass") else 0  # photons
    if (numpy.abs(solved - build) > tolerance).any():
        return f"{chapter}: the solution in the copy draws another picture than the build"
    solution = (tree / "shaders" / file).read_text()
    for old, new, what in WRONG[chapter]:
        if solution.count(old) < 1:
            return f"{chapter}: the wrong answer '{what}' edits '{old}', which shaders/{file} no longer holds"
        (tree / "shaders" / file).write_text(solution.replace(old, new))
        code, said = run_check(chapter, tree, bin_dir)
        print(f"{chapter}, {what}: {said}")
        if code != 1:
            return f"{chapter}: --check does not call '{what}' wrong: {said}"
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
