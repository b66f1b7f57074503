#!/usr/bin/python3
"""A chapter's exercise (docs: each shading chapter's "Write the stage
yourself"): a copy of the shader sources in which the chapter's new stage
is cut out, for the chapter to run with --shader-source.

exercises/NN_name.glsl is the starter: its comments are the task and a
hint, its code the stage with a TODO, and its line "replaces:
FILE#REGION" names the tagged region of shaders/FILE it stands in for.
The solution is the chapter's own code between the same tags.

    tools/exercise.py NN_name [--out DIR] [--solution] [--force]
    tools/exercise.py NN_name --check [--out DIR] [--bin DIR]

writes DIR (default out/exercise-NN_name, below the current folder, as the
chapters' out/): shaders/ and shared/host_device.h
as in this tree, the region replaced by the starter (--solution: left as
it is), and prints the command that runs the chapter on it; an existing
DIR is left alone unless --force. Edit
DIR/shaders/FILE with the window open: each save recompiles, and the
picture changes once the stage is right. Exit 2 with one line for an
unknown chapter or a region that is not there.

--check renders the chapter on DIR (headless, 160x90, one frame, validation on) and
compares the picture with the chapter's own (the build's, DIR of --bin,
default build/bin; kept in its build folder's exercise-check/ until the
build changes): right (exit 0) where at most 0.1 % of the pixels differ by
more than 2 of 255 in a channel (the photons of chapters 14 and 15 differ
by one from run to run), else not yet (exit 1), saying how much differs and
where, with DIR/check/difference.png (the differing pixels red over the
chapter's picture, greyed). A shader that does not compile: the chapter's
one line, exit 2.
"""
import json
import pathlib
import re
import shutil
import subprocess
import sys

import docs  # tools/docs.py: the tagged regions, read one way

ROOT = pathlib.Path(__file__).resolve().parent.parent


def fail(message):
    print(f"exercise.py: {message}", file=sys.stderr)
    sys.exit(2)


def starter(chapter):
    path = ROOT / "exercises" / f"{chapter}.glsl"
    if not path.is_file():
        known = sorted(p.stem for p in (ROOT / "exercises").glob("*.glsl"))
        fail(f"no exercise {path.relative_to(ROOT)} (there are: {', '.join(known)})")
    text = path.read_text()
    found = re.search(r"^// replaces: (\S+)#(\S+)$", text, re.M)
    if not found:
        fail(f"{path.relative_to(ROOT)}: no line '// replaces: FILE#REGION'")
    return text, found.group(1), found.group(2)


def replace_region(source, region, body, name):
    """The lines between '// [region NAME]' and its '// [end]' (regions
    nest, as tools/docs.py reads them), replaced by `body` indented as the
    tag is."""
    lines = source.split("\n")
    try:
        spans = docs.regions(name, lines)
    except docs.DocsError as error:
        fail(str(error))
    if region not in spans:
        fail(f"{name}: no region {region}")
    first, end = spans[region]
    tag = lines[first - 1]
    indent = tag[: len(tag) - len(tag.lstrip())]
    new = [indent + l if l else l for l in body.rstrip("\n").split("\n")]
    return "\n".join(lines[:first] + new + lines[end:])


CHECK_SIZE = ["--width", "160", "--height", "90", "--frames", "1"]
CHECK_CODES = 2  # a pixel differs where a channel is off by more than this (of 255)
CHECK_SHARE = 0.001  # right: at most this share of the pixels differ


def render(exe, png, extra):
    """Runs the chapter headless into png and returns the picture (RGB);
    where the chapter refuses the shaders, its one line and exit 2 (exit 1
    where it fails otherwise or the validation layer speaks)."""
    run = subprocess.run([str(exe), "--headless", "--validation", *CHECK_SIZE, *extra, "--output", str(png)],
                         capture_output=True, text=True, timeout=900)
    if run.returncode != 0:
        lines = [l for l in run.stderr.splitlines() if l.strip()] or run.stdout.splitlines()[-1:]
        print(f"exercise.py: {lines[-1] if lines else exe.name + ' failed'}", file=sys.stderr)
        sys.exit(2 if run.returncode == 2 else 1)
    report = json.loads(png.with_suffix(".json").read_text())
    if report["validation_messages"]:
        print(f"not yet: {report['validation_messages']} validation messages (see {png.parent})")
        sys.exit(1)
    from PIL import Image  # only --check needs it (Debian's python3-pil)
    return Image.open(png).convert("RGB")


def built_picture(chapter, exe):
    """The chapter's own picture at the check's size, rendered once per build."""
    shaders = exe.parent / "shaders"
    stamp = " ".join([str(max([exe.stat().st_mtime_ns] + [p.stat().st_mtime_ns for p in shaders.rglob("*.spv")])),
                      *CHECK_SIZE])
    folder = exe.parent.parent / "exercise-check"
    folder.mkdir(exist_ok=True)
    png, kept = folder / f"{chapter}.png", folder / f"{chapter}.stamp"
    if png.is_file() and kept.is_file() and kept.read_text() == stamp:
        from PIL import Image
        return Image.open(png).convert("RGB")
    picture = render(exe, png, [])
    kept.write_text(stamp)
    return picture


def where(mask):
    """Where most of the True pixels are, in words, and their box."""
    h, w = len(mask), len(mask[0])
    counts = {}
    for y in range(h):
        for x in range(w):
            if mask[y][x]:
                cell = (min(3 * y // h, 2), min(3 * x // w, 2))
                counts[cell] = counts.get(cell, 0) + 1
    row, col = max(counts, key=counts.get)
    name = {(1, 1): "middle"}.get((row, col), f"{['upper', '', 'lower'][row]} {['left', 'middle', 'right'][col]}")
    ys = [y for y in range(h) if any(mask[y])]
    xs = [x for x in range(w) if any(mask[y][x] for y in range(h))]
    name = " ".join(name.split())
    return f"most in the {name} of the picture (x {xs[0]}-{xs[-1]}, y {ys[0]}-{ys[-1]} of {w}x{h})"


def check(chapter, out, bin_dir):
    exe = bin_dir / chapter
    if not exe.is_file():
        fail(f"{exe} does not exist: build the chapters first (cmake --build build)")
    if not (out / "shaders").is_dir():
        fail(f"{out} holds no exercise: make it with tools/exercise.py {chapter}")
    pictures = out / "check"
    pictures.mkdir(exist_ok=True)
    theirs = built_picture(chapter, exe)
    yours = render(exe, pictures / "yours.png", ["--shader-source", str(out)])
    w, h = theirs.size
    a, b = theirs.load(), yours.load()
    mask = [[max(abs(p - q) for p, q in zip(a[x, y], b[x, y])) > CHECK_CODES for x in range(w)] for y in range(h)]
    off = sum(map(sum, mask))
    if off <= CHECK_SHARE * w * h:
        print(f"right: your picture is the chapter's ({off} of {w * h} pixels differ by more than "
              f"{CHECK_CODES}/255; {100 * CHECK_SHARE:g} % may)")
        return 0
    difference = theirs.convert("L").convert("RGB")
    d = difference.load()
    for y in range(h):
        for x in range(w):
            d[x, y] = (255, 0, 0) if mask[y][x] else tuple(v // 2 for v in d[x, y])
    difference.save(pictures / "difference.png")
    here = pathlib.Path.cwd()
    shown = pictures.relative_to(here) if pictures.is_relative_to(here) else pictures
    print(f"not yet: {100 * off / (w * h):.1f} % of the pixels differ from the chapter's by more than "
          f"{CHECK_CODES}/255, {where(mask)}; see {shown}/difference.png")
    return 1


def main(argv):
    args = argv[1:]
    if not args or args[0].startswith("-"):
        print(__doc__, file=sys.stderr)
        return 2
    chapter, solution = args[0], "--solution" in args
    out = pathlib.Path("out").resolve() / f"exercise-{chapter}"  # beside the chapters' out/
    if "--out" in args:
        i = args.index("--out")
        if i + 1 >= len(args):
            fail("--out needs a folder")
        out = pathlib.Path(args[i + 1]).resolve()
    text, file, region = starter(chapter)
    if "--check" in args:
        bin_dir = pathlib.Path("build/bin")
        if "--bin" in args:
            i = args.index("--bin")
            if i + 1 >= len(args):
                fail("--bin needs a folder")
            bin_dir = pathlib.Path(args[i + 1])
        return check(chapter, out, bin_dir.resolve())
    if out.exists():
        if "--force" not in args:
            fail(f"{out} exists (your work?): remove it, or --force to start again")
        shutil.rmtree(out)
    shutil.copytree(ROOT / "shaders", out / "shaders")
    (out / "shared").mkdir(parents=True)
    shutil.copy(ROOT / "shared" / "host_device.h", out / "shared")
    target = out / "shaders" / file
    if not target.is_file():
        fail(f"exercises/{chapter}.glsl: shaders/{file} does not exist")
    source = target.read_text()
    changed = replace_region(source, region, text, f"shaders/{file}")
    if not solution:
        target.write_text(changed)
    here = pathlib.Path.cwd()
    shown = out.relative_to(here) if out.is_relative_to(here) else out
    print(f"{'solution' if solution else 'starter'} in {shown}/shaders/{file} (region {region})")
    print(f"run: build/bin/{chapter} --shader-source {shown}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
