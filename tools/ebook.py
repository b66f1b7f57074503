#!/usr/bin/python3
"""The ebook: every page of the built docs site (tools/site.sh), in the
order of mkdocs.yml's nav, as one book printed to PDF by headless Chromium
(through selenium; it runs KaTeX, so formulas print as on screen).

The pages' articles are joined into one document (book.html, in a
temporary folder, its images and styles the site's by file URL), after a
contents page: each chapter starts on a new sheet, and every link between pages
becomes a link inside the PDF; links to the web stay, links to anything
else (the code pages, files) become plain text. Chromium prints it with
page numbers in the footer and an outline (bookmarks) of the chapters and
their sections; the contents page's numbers are where the first print put
each chapter (its text read back with pdftotext), filled in for the second
print. Long listings may break across sheets; diffs print open. Written
atomically: a failed run leaves no half-written book.

    tools/ebook.py [--site DIR] [--out FILE]   (defaults: out/site, out/rayglass.pdf)

Runs on the system's Python 3 (Debian's python3-selenium, chromium-driver,
poppler-utils).
"""
import argparse
import base64
import html
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
ARTICLE = re.compile(r'<article class="md-content__inner md-typeset">(.*?)</article>', re.S)
LINK = re.compile(r'<a\b([^>]*?)\bhref="([^"]*)"([^>]*)>(.*?)</a>', re.S)


def nav_pages(mkdocs_yml):
    """The nav's pages in order: its "- Name: page.md" lines."""
    return [m.group(1) for m in re.finditer(r"^\s*- (?:[^:\n]+: )?([\w-]+)\.md\s*$", mkdocs_yml, re.M)]


def title_of(page):
    """A page's title: its Markdown's first line."""
    return (ROOT / "docs" / f"{page}.md").read_text().splitlines()[0].lstrip("# ").strip()


def fail(message):
    print(f"ebook: {message}", file=sys.stderr)
    sys.exit(1)


def chapter(page, text, pages):
    """One page's article, its ids and links made the book's: an id x becomes
    page--x, a link to a page of the book (or an anchor in it) an internal
    link, a link to the web stays, any other link becomes its text."""
    text = re.sub(r'<a class="headerlink"[^>]*>.*?</a>', "", text, flags=re.S)
    text = re.sub(r'\bid="([^"]+)"', lambda m: f'id="{page}--{m.group(1)}"', text)

    def link(m):
        before, href, after, inner = m.groups()
        if re.match(r"https?://", href):
            return m.group(0)
        target, _, anchor = href.partition("#")
        target = target or f"{page}.html"
        name = target[:-5] if target.endswith(".html") else None
        if name in pages:
            dest = f"{name}--{anchor}" if anchor else f"page--{name}"
            return f'<a{before}href="#{dest}"{after}>{inner}</a>'
        return f"<span>{inner}</span>"

    text = LINK.sub(link, text)
    text = text.replace("<details", "<details open")  # diffs print open
    return f'<section class="rg-book-chapter" id="page--{page}">{text}</section>'


def book_html(site, pages, numbers):
    """The whole book as one HTML document; `numbers`: each page's first
    sheet for the contents page (None: a placeholder of the same width)."""
    first = (site / f"{pages[0]}.html").read_text()
    styles = "\n".join(re.findall(r'<link rel="stylesheet" href="[^"]*">', first))
    rows = []
    for page in pages:
        number = numbers.get(page) if numbers else None
        rows.append(f'<li><a href="#page--{page}">{html.escape(title_of(page))}</a>'
                    f'<span class="rg-toc-page">{number if number else "000"}</span></li>')
    chapters = []
    for page in pages:
        m = ARTICLE.search((site / f"{page}.html").read_text())
        if not m:
            fail(f"{page}.html: no article found")
        chapters.append(chapter(page, m.group(1), set(pages)))
    body = f"""<!doctype html>
<html><head><meta charset="utf-8"><title>RayGlass</title>
{styles}
<style>
  body {{ margin: 0; }}
  .md-typeset {{ font-size: 0.8rem; }}
  .rg-book-chapter {{ break-before: page; }}
  .rg-toc ol {{ list-style: none; padding: 0; margin: 0; }}
  .rg-toc li {{ display: flex; margin: 0.2em 0; }}
  .rg-toc li a {{ flex: 1; }}
  .rg-toc-page {{ min-width: 3em; text-align: right; }}
  @media print {{
    /* a listing or table longer than a sheet's third may break across sheets */
    .md-typeset pre.rg-long, .md-typeset table.rg-long {{ break-inside: auto; }}
  }}
</style></head>
<body data-md-color-scheme="default"><div class="md-typeset">
<section class="rg-toc"><h1 id="contents">RayGlass</h1><h2>Contents</h2><ol>
{''.join(rows)}
</ol></section>
{''.join(chapters)}
</div>
<script src="assets/katex/katex.min.js"></script>
<script src="assets/rayglass.js"></script>
<script>
  for (const pre of document.querySelectorAll(".md-typeset pre"))
    if (pre.textContent.split("\\n").length > 40) pre.classList.add("rg-long");
  for (const table of document.querySelectorAll(".md-typeset table"))
    if (table.rows.length > 12) table.classList.add("rg-long");
  // a book is read in order: a page's "Previous: ... Next: ..." line goes
  for (const p of document.querySelectorAll(".rg-book-chapter p"))
    if (p.textContent.startsWith("Previous:") || p.textContent.startsWith("Next:")) p.remove();
</script>
</body></html>
"""
    # The book is written outside the site (a test that opens the site's
    # pages must not meet it): its images, styles and scripts by file URL.
    base = site.as_uri() + "/"
    return re.sub(r'\b(src|href)="(?!https?:|data:|file:|#)([^"]+)"',
                  lambda m: f'{m.group(1)}="{base}{m.group(2)}"', body)


def print_pdf(browser, url, out):
    from selenium.webdriver.support.ui import WebDriverWait
    browser.get(url)
    WebDriverWait(browser, 60).until(lambda b: b.execute_script("return document.readyState") == "complete")
    # KaTeX renders on load (rayglass.js): wait until no formula is left as TeX.
    WebDriverWait(browser, 60).until(lambda b: b.execute_script(
        "return [...document.querySelectorAll('.arithmatex')].every(e => e.querySelector('.katex'))"))
    footer = ('<div style="font-size: 8px; width: 100%; text-align: center; color: #555;">'
              '<span class="pageNumber"></span></div>')
    pdf = browser.execute_cdp_cmd("Page.printToPDF", {
        "printBackground": True, "displayHeaderFooter": True, "headerTemplate": "<div></div>",
        "footerTemplate": footer, "marginTop": 0.5, "marginBottom": 0.6, "marginLeft": 0.6,
        "marginRight": 0.6, "generateDocumentOutline": True, "generateTaggedPDF": True})
    out.write_bytes(base64.b64decode(pdf["data"]))


def first_sheets(pdf, pages):
    """Each page's first sheet (1-based) in a printed book: the first sheet
    after the previous chapter's whose text starts with the page's title."""
    text = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True,
                          check=True).stdout
    sheets = [" ".join(s.split()) for s in text.split("\f")]
    numbers, at = {}, 1  # sheet 1: the contents
    for page in pages:
        title = title_of(page)
        found = next((i for i in range(at, len(sheets)) if sheets[i].startswith(title)), None)
        if found is None:
            fail(f"the printed book has no sheet that starts with '{title}' ({page}.md)")
        numbers[page] = found + 1
        at = found + 1
    return numbers


def main():
    parser = argparse.ArgumentParser(description="Prints the docs site as one PDF.")
    parser.add_argument("--site", default=str(ROOT / "out" / "site"))
    parser.add_argument("--out", default=str(ROOT / "out" / "rayglass.pdf"))
    args = parser.parse_args()
    site, book = pathlib.Path(args.site).resolve(), pathlib.Path(args.out)
    if not shutil.which("pdftotext"):
        fail("pdftotext is not installed (Debian: poppler-utils; tools/setup.sh installs it)")
    try:
        from selenium import webdriver
        from selenium.webdriver.chrome.options import Options
        from selenium.webdriver.chrome.service import Service
    except ImportError:
        fail("selenium is not installed (Debian: python3-selenium chromium-driver; tools/setup.sh installs them)")
    if not (site / "index.html").is_file():
        fail(f"no site in {site} (build it with tools/site.sh --out {site})")
    pages = nav_pages((ROOT / "mkdocs.yml").read_text())
    if not pages:
        fail("no pages found in mkdocs.yml's nav")
    missing = [p for p in pages if not (site / f"{p}.html").is_file()]
    if missing:
        fail(f"pages missing from {site}: {', '.join(missing)}")

    options = Options()
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"):
        options.add_argument(arg)
    options.binary_location = "/usr/bin/chromium"
    with tempfile.TemporaryDirectory() as work:
        source = pathlib.Path(work) / "book.html"
        printed = pathlib.Path(work) / "book.pdf"
        browser = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
        try:
            source.write_text(book_html(site, pages, None))
            print_pdf(browser, source.as_uri(), printed)
            numbers = first_sheets(printed, pages)
            source.write_text(book_html(site, pages, numbers))
            print_pdf(browser, source.as_uri(), printed)
            if first_sheets(printed, pages) != numbers:
                fail("the contents page's numbers moved between the two prints")
        finally:
            browser.quit()
        book.parent.mkdir(parents=True, exist_ok=True)
        partial = book.with_name(book.name + ".partial")
        shutil.copyfile(printed, partial)
        os.replace(partial, book)
        # A copy inside the site, for the index's link to it.
        inside = site / "rayglass.pdf.partial"
        shutil.copyfile(printed, inside)
        os.replace(inside, site / "rayglass.pdf")
    print(f"ebook: {book.resolve()} ({len(pages)} pages of the site; a copy in {site})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
