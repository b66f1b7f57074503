#!/usr/bin/env python3
"""Keeps shared/ in its layers and docs/code-map.md true to it.

shared/ holds one folder per concern, in layers from the bottom up (LAYERS
below). A file may include the headers at the top of shared/ (host_device.h,
vk_check.h), its own folder's, and those of folders below its own: never one
above, so nothing climbs back up and no two folders include each other.

    tools/code_map.py --check   exit 1, naming each fault: an include that
                                climbs up, a file directly in shared/ other
                                than the few every layer includes, a folder
                                without its README.md or outside LAYERS, a
                                file over MAX_LINES (about 500) lines, or a module (a .h
                                or .cpp by its name) or folder that
                                docs/code-map.md does not name
    tools/code_map.py --uses FILE
                                the shared/ headers FILE includes, one a line
    --root DIR                  the repository to work on (default: this one)
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
# bottom first; a folder includes only folders before it
LAYERS = ["core", "vulkan", "scene", "raytracing", "reference", "app", "viewer", "chapter", "photons"]
# directly in shared/: what every layer may include, and the build file
TOP = {"CMakeLists.txt", "host_device.h", "vk_check.h"}
MAX_LINES = 520  # "about 500": a file past it gets split by concern
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def shared_includes(root, path):
    """The shared/ files `path` includes, as paths relative to shared/."""
    shared = root / "shared"
    found = []
    for name in INCLUDE.findall(path.read_text()):
        if (shared / name).is_file():
            found.append(name)
    return found


def modules(root):
    """{folder: sorted module names} of shared/'s folders (a module: a .h/.cpp name)."""
    out = {}
    for d in sorted(p for p in (root / "shared").iterdir() if p.is_dir()):
        out[d.name] = sorted({f.stem for f in d.iterdir() if f.suffix in (".h", ".cpp")})
    return out


def check(root):
    faults = []
    shared = root / "shared"
    for f in sorted(shared.iterdir()):
        if f.is_file() and f.name not in TOP:
            faults.append(f"shared/{f.name}: directly in shared/; it belongs in a folder")
    for d in sorted(p for p in shared.iterdir() if p.is_dir()):
        if d.name not in LAYERS:
            faults.append(f"shared/{d.name}/: not a layer of tools/code_map.py's LAYERS")
            continue
        if not (d / "README.md").is_file():
            faults.append(f"shared/{d.name}/: no README.md saying what it holds")
    for f in sorted(shared.rglob("*")):
        if f.suffix not in (".h", ".cpp"):
            continue
        rel = f.relative_to(shared)
        lines = len(f.read_text().splitlines())
        if lines > MAX_LINES:
            faults.append(f"shared/{rel}: {lines} lines, over {MAX_LINES}: split it by concern")
        here = rel.parts[0] if len(rel.parts) > 1 else None
        for inc in shared_includes(root, f):
            parts = pathlib.PurePosixPath(inc).parts
            if len(parts) == 1:
                continue  # the top's headers: every layer may include them
            there = parts[0]
            if here is None:
                faults.append(f"shared/{rel}: includes {inc}; the top of shared/ includes no folder")
            elif here in LAYERS and there in LAYERS and LAYERS.index(there) > LAYERS.index(here):
                faults.append(f"shared/{rel}: includes {inc}, which climbs from {here}/ up to "
                              f"{there}/")
    page = root / "docs" / "code-map.md"
    if not page.is_file():
        faults.append("docs/code-map.md: missing")
    else:
        text = page.read_text()
        for folder, names in modules(root).items():
            if f"`{folder}/`" not in text:
                faults.append(f"docs/code-map.md: does not name the folder `{folder}/`")
            for name in names:
                if f"`{folder}/{name}`" not in text:
                    faults.append(f"docs/code-map.md: does not name the module `{folder}/{name}`")
    return faults


def main(argv):
    root = ROOT
    if "--root" in argv:
        root = pathlib.Path(argv[argv.index("--root") + 1]).resolve()
    if "--uses" in argv:
        for inc in shared_includes(root, pathlib.Path(argv[argv.index("--uses") + 1])):
            print(inc)
        return 0
    if "--check" not in argv:
        print(__doc__, file=sys.stderr)
        return 2
    faults = check(root)
    for fault in faults:
        print(f"code_map.py: {fault}", file=sys.stderr)
    return 1 if faults else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
