#!/usr/bin/env python3
"""Keeps the code in docs/*.md true to the code.

In a page, a block between
    <!-- snippet: PATH#REGION -->  ...  <!-- end -->
holds the region `// [region REGION]` ... `// [end]` of PATH (a file of the
repository), dedented, in a fenced block under a line naming PATH; and a
block between
    <!-- diff: OLD NEW -->  ...  <!-- end -->
holds the unified diff from file or folder OLD to NEW; and a block between
    <!-- footer: NN_name -->  ...  <!-- end -->
holds a chapter page's links: its sources (the chapter's main.cpp, its
shader folder, its tests) and the previous and next chapters.

Regions nest: each `// [end]` closes the innermost open region, and the
markers of inner regions are left out of listings and diffs. A file whose
markers do not balance is an error.

The tutorial's sources (chapters/, shared/, shaders/), which the pages
quote, keep their lines to 90 characters: a listing then fits the page's
column at 1280 px without scrolling (tests/test_site.py checks that too).

    tools/docs.py --write   rewrite those blocks from the code
    tools/docs.py --check   exit 1 (naming the page and block) if any is stale,
                            or (naming file and line) if a source line is too long
    --root DIR              the repository to work on (default: this one)
"""
import difflib
import pathlib
import re
import sys
import textwrap

from code_map import LAYERS, shared_includes

ROOT = pathlib.Path(__file__).resolve().parent.parent
BLOCK = re.compile(r"(<!-- (snippet|diff|footer): ([^>]*?) -->\n)(.*?)(<!-- end -->)", re.S)
MARKER = re.compile(r"<!-- (snippet|diff|footer): ")  # inside a block: the block before lacks its end
CHAPTER = re.compile(r"^(\d\d)_\w+$")
OPEN = re.compile(r"^\s*(?://|#)\s*\[region ([\w.-]+)\]\s*$")
CLOSE = re.compile(r"^\s*(?://|#)\s*\[end\]\s*$")
LANG = {".cpp": "cpp", ".h": "cpp", ".glsl": "glsl", ".comp": "glsl", ".rgen": "glsl", ".rchit": "glsl",
        ".rmiss": "glsl", ".rint": "glsl", ".rahit": "glsl", ".json": "json", ".sh": "bash", ".txt": "cmake",
        ".py": "python", ".gp": "gnuplot", ".md": "markdown"}


class DocsError(Exception):
    pass


def is_marker(line):
    return bool(OPEN.match(line) or CLOSE.match(line))


def regions(path, lines):
    """{name: (first line, end line)} of every region, nested ones included."""
    found, stack = {}, []
    for i, line in enumerate(lines):
        if m := OPEN.match(line):
            stack.append((m.group(1), i))
        elif CLOSE.match(line):
            if not stack:
                raise DocsError(f"{path}:{i + 1}: '[end]' closes no region")
            name, start = stack.pop()
            if name in found:
                raise DocsError(f"{path}: region '{name}' defined twice")
            found[name] = (start + 1, i)
    if stack:
        name, start = stack[-1]
        raise DocsError(f"{path}:{start + 1}: region '{name}' is never closed")
    return found


def region(root, path, name):
    lines = (root / path).read_text().splitlines()
    spans = regions(path, lines)
    if name not in spans:
        raise DocsError(f"{path}: no region '{name}'")
    first, end = spans[name]
    body = textwrap.dedent("\n".join(l for l in lines[first:end] if not is_marker(l)))
    return f"```{LANG.get(pathlib.Path(path).suffix, '')}\n{body}\n```\n"


def files_of(root, path):
    p = root / path
    if p.is_dir():
        return {f.relative_to(p).as_posix(): f for f in sorted(p.rglob("*")) if f.is_file()}
    if not p.is_file():
        raise DocsError(f"{path}: no such file or folder")
    return {"": p}  # two single files are compared whatever their names


def code_lines(path):
    return [l for l in path.read_text().splitlines() if not is_marker(l)]


def diff(root, old, new):
    a, b = files_of(root, old), files_of(root, new)
    out = []
    for name in sorted(set(a) | set(b)):
        la = code_lines(a[name]) if name in a else []
        lb = code_lines(b[name]) if name in b else []
        oldname = f"{old}/{name}" if name else old
        newname = f"{new}/{name}" if name else new
        out += difflib.unified_diff(la, lb, oldname if name in a else "/dev/null",
                                    newname if name in b else "/dev/null", n=2, lineterm="")
    return "```diff\n" + "\n".join(out) + "\n```\n"


def title(page):
    first = page.read_text().splitlines()[0]
    return first.lstrip("# ").strip()


def what_is_new(root, nn):
    """The "new in it" column of the chapter table in docs/index.md, or None."""
    index = root / "docs" / "index.md"
    if not index.exists():
        return None
    for line in index.read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 4 and cells[0] == nn:
            return cells[3]
    return None


def footer(root, chapter):
    """Sources and previous/next links of a chapter page (docs/NN_name.md)."""
    if not CHAPTER.match(chapter):
        raise DocsError(f"footer: '{chapter}' is not a chapter name (NN_name)")
    pages = sorted(p for p in (root / "docs").glob("[0-9][0-9]_*.md"))
    names = [p.stem for p in pages]
    if chapter not in names:
        raise DocsError(f"footer: no page docs/{chapter}.md")
    sources = [f"chapters/{chapter}/main.cpp"]
    shader_dir = root / "shaders" / chapter
    if shader_dir.is_dir():
        sources += [f.relative_to(root).as_posix() for f in sorted(shader_dir.iterdir()) if f.is_file()]
    nn = chapter[:2]
    if int(nn) >= 4:
        sources.append("shaders/common")  # the payload, hit, miss and shading code chapters share
    if int(nn) >= 5:
        sources.append("shared/chapter/rt_chapter.cpp")  # chapter 04's main() for the shading chapters
    sources += [f.relative_to(root).as_posix() for f in sorted((root / "tests").glob(f"test_{nn}_*.cpp"))]
    if 5 <= int(nn) <= 13:  # tests/CMakeLists.txt's RG_REFERENCE_CHAPTERS
        sources.append("tests/test_reference.cpp")
    missing = [s for s in sources if not (root / s).exists()]
    if missing:
        raise DocsError(f"footer {chapter}: missing {', '.join(missing)}")
    links = " · ".join(f"[`{s}`](../{s})" for s in sources)
    used = modules_used(root, chapter)
    modules = ""
    if used:
        modules = ("**Shared modules it includes:** " +
                   " · ".join(f"[`{m}`](../shared/{m})" for m in used) +
                   " ([code map](code-map.md))\n\n")
    i = names.index(chapter)
    if i + 1 < len(pages):
        after = names[i + 1]
        teaser = what_is_new(root, after[:2])
        upcoming = f"[{title(pages[i + 1])}]({pages[i + 1].name})" + (f": {teaser}." if teaser else ".")
    else:
        upcoming = ("This is the last chapter. \"Where next\" above lists what could follow; the "
                    "[performance page](performance.md) compares every chapter's speed and error.")
    nav = []
    if i > 0:
        nav.append(f"Previous: [{title(pages[i - 1])}]({pages[i - 1].name})")
    nav.append("[Contents](index.md)")
    if i + 1 < len(pages):
        nav.append(f"Next: [{title(pages[i + 1])}]({pages[i + 1].name})")
    commands = [(f"cmake --build build --target {chapter}", "this chapter alone"),
                (f"build/bin/{chapter}", "a window, where a display exists"),
                (f"build/bin/{chapter} --headless", "PNG and JSON report into out/"),
                (f"ctest --test-dir build -L {nn}", "its tests")]
    width = max(len(c) for c, _ in commands) + 2
    block = "".join(f"{c.ljust(width)}# {why}\n" for c, why in commands)
    run = ("\n## Build and run this chapter\n\nFrom the repository's root, after the README's set-up:\n\n"
           f"```sh\n{block}```\n")
    return (run + f"\n## Next\n\n{upcoming}\n\n---\n\n**Sources:** {links}\n\n" + modules +
            " · ".join(nav) + "\n")


def modules_used(root, chapter):
    """The shared/ headers a chapter's main.cpp includes, and, where it
    includes chapter/rt_chapter.h, those that chapter 04's main() there
    includes: bottom layer first (tools/code_map.py)."""
    main = root / "chapters" / chapter / "main.cpp"
    used = set(shared_includes(root, main)) if main.is_file() else set()
    rt_chapter = root / "shared" / "chapter" / "rt_chapter.cpp"
    if "chapter/rt_chapter.h" in used and rt_chapter.is_file():
        used |= set(shared_includes(root, rt_chapter))

    def order(m):
        folder = m.split("/")[0]
        return (LAYERS.index(folder) + 1 if folder in LAYERS else 0, m)
    return sorted(used, key=order)


def render(root, kind, arg):
    if kind == "footer":
        return footer(root, arg)
    if kind == "snippet":  # the listing, captioned with the file it comes from
        path, name = arg.split("#")
        return f"[`{path}`](../{path})\n\n" + region(root, path, name)
    old, new = arg.split()
    return diff(root, old, new)


def run(root, mode):
    stale = []
    for page in sorted((root / "docs").rglob("*.md")):
        text = page.read_text()
        def fill(m):
            if MARKER.search(m.group(4)):  # --write would replace the page up to the next block's end
                raise DocsError(f"{page.relative_to(root)}: {m.group(2)} {m.group(3).strip()} has no "
                                "<!-- end --> before the next block")
            want = render(root, m.group(2), m.group(3).strip())
            if m.group(4) != want:
                stale.append(f"{page.relative_to(root)}: {m.group(2)} {m.group(3).strip()}")
            return m.group(1) + want + m.group(5)
        new = BLOCK.sub(fill, text)
        if mode == "--write" and new != text:
            page.write_text(new)
    if mode == "--check" and stale:
        print("docs.py: these blocks differ from the code (run tools/docs.py --write):")
        print("\n".join("  " + s for s in stale))
        return 1
    if mode == "--check":
        long = long_lines(root)
        if long:
            print(f"docs.py: lines longer than {MAX_COLUMNS} characters in the tutorial's sources:")
            print("\n".join("  " + s for s in long))
            return 1
    return 0


MAX_COLUMNS = 90
SOURCES = ("chapters", "shared", "shaders")


def long_lines(root):
    """`path:line (N characters)` for each line of the tutorial's sources over MAX_COLUMNS."""
    found = []
    for folder in SOURCES:
        for path in sorted((root / folder).rglob("*")):
            if not path.is_file() or LANG.get(path.suffix) not in ("cpp", "glsl"):
                continue
            for number, line in enumerate(path.read_text(errors="replace").split("\n"), 1):
                if len(line) > MAX_COLUMNS:
                    found.append(f"{path.relative_to(root)}:{number} ({len(line)} characters)")
    return found


def main(argv):
    mode, root = "--check", ROOT
    args = list(argv)
    while args:
        a = args.pop(0)
        if a in ("--check", "--write"):
            mode = a
        elif a == "--root" and args:
            root = pathlib.Path(args.pop(0)).resolve()
        else:
            print(f"docs.py: unknown argument {a} (use --check, --write, --root DIR)", file=sys.stderr)
            return 2
    try:
        return run(root, mode)
    except DocsError as e:
        print(f"docs.py: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
