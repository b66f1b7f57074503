#!/usr/bin/python3
"""The ebook as a reader gets it: tools/ebook.py prints the built site, and
the PDF (read back with poppler's pdfinfo and pdftotext) has every page of
mkdocs.yml's nav, each starting on a new sheet with its title, in the nav's
order, and no formula left as raw TeX.

    tests/test_ebook.py SITE_DIR OUT_PDF
"""
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import ebook  # noqa: E402  (tools/ebook.py: its nav_pages)


def main(site, pdf):
    failures = []
    r = subprocess.run([sys.executable, str(ROOT / "tools" / "ebook.py"), "--site", site, "--out", pdf],
                       capture_output=True, text=True)
    if r.returncode != 0:
        print(f"FAIL tools/ebook.py exited {r.returncode}: {r.stderr.strip()}")
        return 1
    info = subprocess.run(["pdfinfo", pdf], capture_output=True, text=True, check=True).stdout
    sheets = int(re.search(r"^Pages:\s+(\d+)", info, re.M).group(1))
    text = subprocess.run(["pdftotext", "-layout", pdf, "-"], capture_output=True, text=True, check=True).stdout
    sheets_text = [" ".join(sheet.split()) for sheet in text.split("\f")]  # a long title wraps
    pages = ebook.nav_pages((ROOT / "mkdocs.yml").read_text())
    at = 0
    for page in pages:
        title = (ROOT / "docs" / f"{page}.md").read_text().splitlines()[0].lstrip("# ").strip()
        found = next((i for i in range(at, len(sheets_text)) if sheets_text[i].startswith(title)), None)
        if found is None:
            failures.append(f"no sheet starts with '{title}' ({page}.md) after sheet {at + 1}")
        else:
            at = found + 1
    for raw in ("$$", "\\mathbf", "\\frac"):
        if raw in text:
            failures.append(f"raw TeX '{raw}' in the PDF's text")
    if sheets < len(pages):
        failures.append(f"{sheets} sheets for {len(pages)} pages")
    for f in failures:
        print("FAIL", f)
    print(f"test_ebook: {len(pages)} pages on {sheets} sheets in {pdf}")
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(*sys.argv[1:]))
