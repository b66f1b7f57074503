#!/usr/bin/env python3
"""A chapter's exercise (docs: each shading chapter's "Write the stage
yourself"): a copy of the shader sources in which the chapter's new stage
is cut out, for the chapter to run with --shader-source.

exercises/NN_name.glsl is the starter: its comments are the task and a
hint, its code the stage with a TODO, and its line "replaces:
FILE#REGION" names the tagged region of shaders/FILE it stands in for.
The solution is the chapter's own code between the same tags.

    tools/exercise.py NN_name [--out DIR] [--solution] [--force]

writes DIR (default out/exercise-NN_name, below the current folder, as the
chapters' out/): shaders/ and shared/host_device.h
as in this tree, the region replaced by the starter (--solution: left as
it is), and prints the command that runs the chapter on it; an existing
DIR is left alone unless --force. Edit
DIR/shaders/FILE with the window open: each save recompiles, and the
picture changes once the stage is right. Exit 2 with one line for an
unknown chapter or a region that is not there.
"""
import pathlib
import re
import shutil
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
