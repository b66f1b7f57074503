#!/usr/bin/python3
"""The ebook as a reader gets it: tools/ebook.py prints the built site, and
the PDF (read back with poppler's pdfinfo and pdftotext, and its outline
and links from the file itself) is a book:

- every page of mkdocs.yml's nav starts a sheet with its title, in the
  nav's order, and no formula is left as raw TeX;
- the outline (bookmarks) names every page of the nav;
- every sheet shows its number at its foot, and the contents page gives
  each page's first sheet;
- no link leaves the PDF except to the web (http, https), and the links
  between pages are links inside it;
- 120 to 280 sheets (261 with the contributors' page), at most 3 % of them near-empty
  (under 300 characters of text: a chapter's last lines) and none blank.

    tests/test_ebook.py SITE_DIR OUT_PDF
"""
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import ebook  # noqa: E402  (tools/ebook.py: its nav_pages, title_of)


def pdf_string(token):
    """A PDF string token, (literal) or <hex>, as text."""
    if token.startswith(b"<"):
        raw = bytes.fromhex(token[1:-1].decode())
        return raw[2:].decode("utf-16-be") if raw[:2] == b"\xfe\xff" else raw.decode("latin-1")
    text = re.sub(rb"\\(.)", rb"\1", token[1:-1])
    return text.decode("utf-16-be")[1:] if text[:2] == b"\xfe\xff" else text.decode("latin-1")


def main(site, pdf):
    failures = []
    r = subprocess.run([sys.executable, str(ROOT / "tools" / "ebook.py"), "--site", site, "--out", pdf],
                       capture_output=True, text=True)
    if r.returncode != 0:
        print(f"FAIL tools/ebook.py exited {r.returncode}: {r.stderr.strip()}")
        return 1
    info = subprocess.run(["pdfinfo", pdf], capture_output=True, text=True, check=True).stdout
    count = int(re.search(r"^Pages:\s+(\d+)", info, re.M).group(1))
    text = subprocess.run(["pdftotext", "-layout", pdf, "-"], capture_output=True, text=True, check=True).stdout
    sheets = [" ".join(sheet.split()) for sheet in text.split("\f")][:count]  # a long title wraps
    pages = ebook.nav_pages((ROOT / "mkdocs.yml").read_text())
    first = {}
    at = 0
    for page in pages:
        title = ebook.title_of(page)
        found = next((i for i in range(at, len(sheets)) if sheets[i].startswith(title)), None)
        if found is None:
            failures.append(f"no sheet starts with '{title}' ({page}.md) after sheet {at + 1}")
        else:
            first[page], at = found + 1, found + 1
    for raw in ("$$", "\\mathbf", "\\frac"):
        if raw in text:
            failures.append(f"raw TeX '{raw}' in the PDF's text")
    # The contents page: each title, then the sheet it starts on.
    for page, number in first.items():
        if not re.search(re.escape(ebook.title_of(page)) + r"\s+" + str(number) + r"\b", sheets[0]):
            failures.append(f"the contents page does not give '{ebook.title_of(page)}' as sheet {number}")
    # Every sheet's number at its foot.
    for k, sheet in enumerate(sheets, start=1):
        if not sheet.endswith(f" {k}") and sheet != str(k):
            failures.append(f"sheet {k} does not end with its number: ...{sheet[-40:]}")
            break
    # The outline and the links, from the file.
    data = pathlib.Path(pdf).read_bytes()
    titles = {pdf_string(t) for t in re.findall(rb"/Title\s*(<[0-9A-Fa-f]*>|\((?:[^()\\]|\\.)*\))", data)}
    bare = {re.sub(r"\s", "", t) for t in titles}  # a title's line break may lose its space
    for page in pages:
        if re.sub(r"\s", "", ebook.title_of(page)) not in bare:
            failures.append(f"the outline does not name '{ebook.title_of(page)}'")
    for uri in re.findall(rb"/URI\s*(\((?:[^()\\]|\\.)*\)|<[0-9A-Fa-f]*>)", data):
        target = pdf_string(uri)
        if not re.match(r"https?://", target):
            failures.append(f"a link leaves the PDF for {target}")
    internal = len(re.findall(rb"/Dest\b", data))
    if internal < 100:
        failures.append(f"only {internal} links inside the PDF")
    if not 120 <= count <= 280:
        failures.append(f"{count} sheets, not 120 to 280")
    short = [k for k, sheet in enumerate(sheets, start=1) if len(sheet) < 300]
    if len(short) > 0.03 * count:
        failures.append(f"{len(short)} near-empty sheets of {count}: {short}")
    blank = [k for k, sheet in enumerate(sheets, start=1) if len(sheet) <= len(str(k))]
    if blank:
        failures.append(f"blank sheets: {blank}")
    for f in failures:
        print("FAIL", f)
    print(f"test_ebook: {len(pages)} pages on {count} sheets ({len(short)} near-empty, {internal} internal "
          f"links, {len(titles)} outline entries) in {pdf}")
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(*sys.argv[1:]))
