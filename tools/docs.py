#!/usr/bin/env python3
"""Keeps the code in docs/*.md true to the code.

In a page, a block between
    <!-- snippet: PATH#REGION -->  ...  <!-- end -->
holds the region `// [region REGION]` ... `// [end]` of PATH (a file of the
repository), dedented, in a fenced block; and a block between
    <!-- diff: OLD NEW -->  ...  <!-- end -->
holds the unified diff from file or folder OLD to NEW.

    tools/docs.py --write   rewrite those blocks from the code
    tools/docs.py --check   exit 1 (naming the page and block) if any is stale
"""
import difflib
import pathlib
import re
import sys
import textwrap

ROOT = pathlib.Path(__file__).resolve().parent.parent
BLOCK = re.compile(r"(<!-- (snippet|diff): ([^>]*?) -->\n)(.*?)(<!-- end -->)", re.S)
LANG = {".cpp": "cpp", ".h": "cpp", ".glsl": "glsl", ".comp": "glsl", ".rgen": "glsl", ".rchit": "glsl",
        ".rmiss": "glsl", ".rint": "glsl", ".rahit": "glsl", ".json": "json", ".sh": "bash", ".txt": "cmake"}


def region(path, name):
    lines = (ROOT / path).read_text().splitlines()
    start = [i for i, l in enumerate(lines) if l.strip() == f"// [region {name}]"]
    if len(start) != 1:
        raise SystemExit(f"docs.py: region '{name}' found {len(start)} times in {path}")
    end = next(i for i in range(start[0] + 1, len(lines)) if lines[i].strip() == "// [end]")
    body = textwrap.dedent("\n".join(lines[start[0] + 1:end]))
    return f"```{LANG.get(pathlib.Path(path).suffix, '')}\n{body}\n```\n"


def files_of(path):
    p = ROOT / path
    if p.is_dir():
        return {f.relative_to(p).as_posix(): f for f in sorted(p.rglob("*")) if f.is_file()}
    return {p.name: p}


def diff(old, new):
    a, b = files_of(old), files_of(new)
    out = []
    for name in sorted(set(a) | set(b)):
        la = a[name].read_text().splitlines() if name in a else []
        lb = b[name].read_text().splitlines() if name in b else []
        oldname = f"{old}/{name}" if (ROOT / old).is_dir() else old
        newname = f"{new}/{name}" if (ROOT / new).is_dir() else new
        out += difflib.unified_diff(la, lb, oldname if name in a else "/dev/null",
                                    newname if name in b else "/dev/null", n=2, lineterm="")
    return "```diff\n" + "\n".join(out) + "\n```\n"


def render(kind, arg):
    if kind == "snippet":
        path, name = arg.split("#")
        return region(path, name)
    old, new = arg.split()
    return diff(old, new)


def main():
    mode = sys.argv[1] if len(sys.argv) > 1 else "--check"
    stale = []
    for page in sorted((ROOT / "docs").glob("*.md")):
        text = page.read_text()
        def fill(m):
            want = render(m.group(2), m.group(3).strip())
            if m.group(4) != want:
                stale.append(f"{page.relative_to(ROOT)}: {m.group(2)} {m.group(3).strip()}")
            return m.group(1) + want + m.group(5)
        new = BLOCK.sub(fill, text)
        if mode == "--write" and new != text:
            page.write_text(new)
    if mode == "--check" and stale:
        print("docs.py: these blocks differ from the code (run tools/docs.py --write):")
        print("\n".join("  " + s for s in stale))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
