#!/usr/bin/python3
"""The ebook: every page of the built docs site (tools/site.sh), in the
order of mkdocs.yml's nav, printed to PDF by headless Chromium (one browser
through selenium; it runs KaTeX, so formulas print as on screen) and joined
into one file with pdfunite (poppler-utils). The site's print style wraps
listings. Written atomically: a failed run leaves no half-written book.

    tools/ebook.py [--site DIR] [--out FILE]   (defaults: out/site, out/rayglass.pdf)

Runs on the system's Python 3 (Debian's python3-selenium, chromium-driver).
"""
import argparse
import base64
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent


def nav_pages(mkdocs_yml):
    """The nav's pages in order: its "- Name: page.md" lines."""
    return [m.group(1) for m in re.finditer(r"^\s*- (?:[^:\n]+: )?([\w-]+)\.md\s*$", mkdocs_yml, re.M)]


def fail(message):
    print(f"ebook: {message}", file=sys.stderr)
    sys.exit(1)


def main():
    parser = argparse.ArgumentParser(description="Prints the docs site as one PDF.")
    parser.add_argument("--site", default=str(ROOT / "out" / "site"))
    parser.add_argument("--out", default=str(ROOT / "out" / "rayglass.pdf"))
    args = parser.parse_args()
    site, book = pathlib.Path(args.site).resolve(), pathlib.Path(args.out)
    if not shutil.which("pdfunite"):
        fail("pdfunite is not installed (Debian: poppler-utils; tools/setup.sh installs it)")
    try:
        from selenium import webdriver
        from selenium.webdriver.chrome.options import Options
        from selenium.webdriver.chrome.service import Service
        from selenium.webdriver.support.ui import WebDriverWait
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
        parts = []
        browser = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
        try:
            for i, page in enumerate(pages):
                browser.get((site / f"{page}.html").as_uri())
                WebDriverWait(browser, 20).until(
                    lambda b: b.execute_script("return document.readyState") == "complete")
                # KaTeX renders on load (rayglass.js): wait until no formula is left as TeX.
                WebDriverWait(browser, 20).until(lambda b: b.execute_script(
                    "return [...document.querySelectorAll('.arithmatex')].every(e => e.querySelector('.katex'))"))
                pdf = browser.execute_cdp_cmd("Page.printToPDF", {"printBackground": True,
                                                                  "displayHeaderFooter": False})
                part = pathlib.Path(work) / f"{i:02d}_{page}.pdf"
                part.write_bytes(base64.b64decode(pdf["data"]))
                parts.append(str(part))
        finally:
            browser.quit()
        joined = pathlib.Path(work) / "book.pdf"
        subprocess.run(["pdfunite", *parts, str(joined)], check=True)
        book.parent.mkdir(parents=True, exist_ok=True)
        partial = book.with_name(book.name + ".partial")
        shutil.copyfile(joined, partial)
        os.replace(partial, book)
        # A copy inside the site, for the index's link to it.
        inside = site / "rayglass.pdf.partial"
        shutil.copyfile(joined, inside)
        os.replace(inside, site / "rayglass.pdf")
    print(f"ebook: {book.resolve()} ({len(pages)} pages of the site; a copy in {site})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
