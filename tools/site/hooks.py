"""mkdocs hooks for the RayGlass site (mkdocs.yml names this file).

- Source links: a page links its sources as `../chapters/...` (right on GitHub
  and in a checkout); on the site each such link goes to a generated page
  `code/<path>.md` that shows the file highlighted (a folder: a list of its files).
- Every page of docs/ must be in the navigation (mkdocs 1.4 only logs it).
- KaTeX is copied from Debian's libjs-katex into the site: no CDN.
- Search from disk: browsers refuse fetch() and workers on file:// URLs, so the
  search index and Material's search worker are also written as scripts that
  tools/site/theme/main.html loads and hands to Material (8 and 9 differ there).
"""
import atexit
import json
import logging
import pathlib
import re
import shutil
import sys
import tempfile

from mkdocs.exceptions import PluginError
from mkdocs.structure.files import File

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from docs import LANG  # noqa: E402  the languages the docs' listings use, per file suffix
KATEX = pathlib.Path("/usr/share/javascript/katex")
LINK = re.compile(r"\]\(\.\./([^)#\s]+)\)")


class _QuietCodePages(logging.Filter):
    """on_nav below is the check; mkdocs's own note would list every code page."""
    def filter(self, record):
        return not record.getMessage().startswith("The following pages exist in the docs directory")


logging.getLogger("mkdocs.structure.nav").addFilter(_QuietCodePages())


def _code_page(rel):
    path = ROOT / rel
    up = "../" * rel.count("/")  # from code/<rel>.md back to the docs root
    head = f"# `{rel}`\n\n"
    if path.is_dir():
        items = sorted(p for p in path.iterdir() if p.is_file())
        body = "Files in this folder:\n\n" + "".join(
            f"- [`{p.name}`]({path.name}/{p.name}.md)\n" for p in items)
        return head + body, [p.relative_to(ROOT).as_posix() for p in items]
    lang = LANG.get(path.suffix, "text")
    text = path.read_text()
    fence = "````" if "```" in text else "```"
    body = (f"[Contents]({up}../index.md) · this file in the repository: `{rel}`\n\n"
            f"{fence}{lang} linenums=\"1\"\n{text}{'' if text.endswith(chr(10)) else chr(10)}{fence}\n")
    return head + body, []


def on_files(files, config):
    docs = pathlib.Path(config["docs_dir"])
    # docs/perf/<device>/perf.md are inputs of performance.md, not pages
    for f in [f for f in files if f.src_path.startswith("perf/") and f.src_path.endswith(".md")]:
        files.remove(f)
    wanted = []
    for page in sorted(docs.glob("*.md")):
        for rel in LINK.findall(page.read_text()):
            if (ROOT / rel).exists():
                wanted.append(rel)
    generated = pathlib.Path(tempfile.mkdtemp(prefix="rayglass-code-"))
    atexit.register(shutil.rmtree, generated, True)
    done = set()
    while wanted:
        rel = wanted.pop(0)
        if rel in done:
            continue
        done.add(rel)
        text, more = _code_page(rel)
        out = generated / "code" / f"{rel}.md"
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(text)
        files.append(File(f"code/{rel}.md", str(generated), config["site_dir"], config["use_directory_urls"]))
        wanted += more
    return files


def on_nav(nav, config, files):
    in_nav = {p.file.src_path for p in nav.pages}
    left_out = [f.src_path for f in files.documentation_pages()
                if not f.src_path.startswith("code/") and f.src_path not in in_nav]
    if left_out:
        raise PluginError(f"pages not in mkdocs.yml's nav: {', '.join(sorted(left_out))}")
    return nav


def on_page_markdown(markdown, page, config, files):
    if page.file.src_path.startswith("code/"):
        return markdown
    depth = page.file.src_path.count("/")
    return LINK.sub(lambda m: f"]({'../' * depth}code/{m.group(1)}.md)"
                    if (ROOT / m.group(1)).exists() else m.group(0), markdown)


GUTTER = re.compile(r"(?<!\S)1(?: \d+)+")


def _without_gutters(index_json):
    """A code page's search text starts with its line-number gutter ("1 2 3
    ... N"), which would be every hit's excerpt: drop such runs."""
    def counts_up(m):
        numbers = m.group(0).split()
        return len(numbers) > 2 and numbers == [str(i) for i in range(1, len(numbers) + 1)]
    index = json.loads(index_json)
    for doc in index["docs"]:
        if doc["location"].startswith("code/"):
            doc["text"] = GUTTER.sub(lambda m: "" if counts_up(m) else m.group(0), doc["text"])
    return json.dumps(index)


def on_post_build(config):
    site = pathlib.Path(config["site_dir"])
    if not (KATEX / "katex.min.js").exists():
        raise PluginError(f"KaTeX not found in {KATEX}: install Debian's libjs-katex")
    dest = site / "assets" / "katex"
    dest.mkdir(parents=True, exist_ok=True)
    for name in ("katex.min.js", "katex.min.css"):
        shutil.copy(KATEX / name, dest / name)
    shutil.copytree(KATEX / "fonts", dest / "fonts", dirs_exist_ok=True)
    index = _without_gutters((site / "search" / "search_index.json").read_text())
    (site / "search" / "search_index.json").write_text(index)
    (site / "search" / "search_index.js").write_text(f"var __index = {index};\n")  # the name Material 9 reads
    workers = sorted((site / "assets" / "javascripts" / "workers").glob("search.*.min.js"))
    if len(workers) != 1:
        raise PluginError("expected one Material search worker, found " + str(len(workers)))
    source = workers[0].read_text()
    (site / "assets" / "rayglass-search-worker.js").write_text(f"var __rgSearchWorker = {json.dumps(source)};\n")
