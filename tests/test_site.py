#!/usr/bin/env python3
"""Opens every page of the built site from disk (file://) in headless Chromium
and checks what a reader would see:

- every <img> loaded (natural width > 0);
- every internal link resolves to a file of the site, and its #fragment to an
  element of that page (the code pages, one template for 170 files: a tenth
  of them in the browser, the links of all from their HTML);
- formulas rendered: a page whose Markdown has math shows KaTeX elements, one
  per formula, and no raw `$$`, `\\(` or `\\[` in its text;
- no message in the browser console (JavaScript errors, failed loads);
- every figure is a link to itself, to see it at full size;
- search works from disk: typing a word lists results;
- at 1280 px no display formula and no listing of a chapter page scrolls
  sideways; at 390 px no page is wider than the screen, and every display
  formula fits its column, scaled to no less than 65 %.
Saves screenshots of the front page and chapter 10 into OUT.

    test_site.py SITE_DIR DOCS_DIR OUT_DIR
"""
import functools
import html.parser
import json
import pathlib
import re
import sys
import time
import urllib.parse

from selenium import webdriver
from selenium.webdriver.chrome.options import Options
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import WebDriverWait

MATH = re.compile(r"\$\$.+?\$\$|(?<![\\$])\$[^$\s][^$\n]*?(?<!\s)\$", re.S)
FENCE = re.compile(r"^```.*?^```|^    .*?$|`[^`\n]+`", re.S | re.M)


class Ids(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids, self.links = set(), []

    def handle_starttag(self, tag, attrs):
        for k, v in attrs:
            if k in ("id", "name") and v:
                self.ids.add(v)
            if tag == "a" and k == "href" and v is not None:
                self.links.append(v)


@functools.lru_cache(maxsize=None)
def parsed(path):
    p = Ids()
    p.feed(path.read_text(errors="replace"))
    return p


def ids_of(path):
    return parsed(path).ids


def formulas_in(markdown):
    return len(MATH.findall(FENCE.sub("", markdown)))


def browser():
    o = Options()
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1280,900",
                "--disable-dev-shm-usage"):
        o.add_argument(arg)
    o.binary_location = "/usr/bin/chromium"
    o.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=o)


def check_links(site, page, hrefs, fail):
    """Every internal link of `page` resolves to a file of the site, and its
    #fragment to an element of that page."""
    for href in hrefs:
        url = urllib.parse.urlsplit(href)
        if url.scheme or href.startswith("//"):
            continue  # external: not followed (the site must work offline)
        target = (page.parent / urllib.parse.unquote(url.path)).resolve() if url.path else page
        if target.is_dir():
            target = target / "index.html"
        if href == "rayglass.pdf" and not target.is_file():
            continue  # printed from the built site into it afterwards (tools/ebook.py; test_ebook.py)
        if not target.is_file() or site.resolve() not in target.parents:
            fail(f"link to a missing file: {href}")
        elif url.fragment and target.suffix == ".html" and urllib.parse.unquote(url.fragment) not in ids_of(target):
            fail(f"link to a missing anchor: {href}")


def check_page(d, site, page, docs, failures):
    rel = page.relative_to(site).as_posix()
    d.get(page.as_uri())
    WebDriverWait(d, 10).until(lambda d: d.execute_script("return document.readyState") == "complete")
    fail = lambda msg: failures.append(f"{rel}: {msg}")
    for src, ok in d.execute_script(
            "return [...document.images].map(i => [i.getAttribute('src'), i.complete && i.naturalWidth > 0])"):
        if not ok:
            fail(f"image not loaded: {src}")
    check_links(site, page, d.execute_script(
        "return [...document.querySelectorAll('a[href]')].map(a => a.getAttribute('href'))"), fail)
    source = docs / (rel[:-5] + ".md")
    want = formulas_in(source.read_text()) if source.is_file() else 0
    if source.is_file():
        got = d.execute_script("return document.querySelectorAll('.arithmatex .katex').length")
        if got != want:
            fail(f"{want} formula(s) in the Markdown, {got} rendered by KaTeX")
        # At 1280 px every display formula fits its column (a narrow phone's
        # screen may scroll one sideways).
        for width, label in d.execute_script(
                "return [...document.querySelectorAll('div.arithmatex')].filter(e => e.scrollWidth > e.clientWidth + 1)"
                ".map(e => [e.scrollWidth + ' px of ' + e.clientWidth, e.innerText.replace(/\\s+/g, ' ').slice(0, 40)])"):
            fail(f"a formula overflows its column at 1280 px ({width}): {label}")
        # A chapter's listings and diffs fit too: its sources keep to 90
        # characters (tools/docs.py --check). Code pages show whole files.
        if not rel.startswith("code/"):
            for width, label in d.execute_script(
                    "return [...document.querySelectorAll('article pre > code')]"
                    ".filter(e => e.scrollWidth > e.clientWidth + 1)"
                    ".map(e => [e.scrollWidth + ' px of ' + e.clientWidth,"
                    " e.innerText.split('\\n').reduce((a, b) => b.length > a.length ? b : a, '').slice(0, 50)])"):
                fail(f"a listing scrolls sideways at 1280 px ({width}): {label}")
        text = d.execute_script("return document.querySelector('article').innerText")
        for raw in ("$$", "\\(", "\\["):
            if raw in text:
                fail(f"raw math '{raw}' left in the text")
    # Every figure of the article opens at full size on a click (rayglass.js).
    for src in d.execute_script("return [...document.querySelectorAll('article img')]"
                                ".filter(i => !i.closest('a')).map(i => i.getAttribute('src'))"):
        fail(f"a figure is not a link to its full size: {src}")
    for entry in d.get_log("browser"):
        fail(f"console: {entry['level']} {entry['message']}")
    return want > 0


def check_phone(d, site, pages, failures, out):
    """At a phone's 390 px nothing makes the page itself scroll sideways: a
    wide listing or table scrolls inside its own box. Every display formula
    fits its column whole (rayglass.js scales a wide one down), at no less
    than 65 % of its size. Screenshots of the front page and chapter 10 as a
    phone shows them."""
    d.set_window_size(390, 844)
    width = d.execute_script("return window.innerWidth")
    formulas = 0
    for page in pages:
        d.get(page.as_uri())
        WebDriverWait(d, 10).until(lambda d: d.execute_script("return document.readyState") == "complete")
        # the formulas are fitted again once KaTeX's fonts are in
        WebDriverWait(d, 10).until(lambda d: d.execute_script(
            "return !document.fonts || document.fonts.status === 'loaded'"))
        rel = page.relative_to(site).as_posix()
        wide = d.execute_script("return document.documentElement.scrollWidth")
        if wide > width + 1:
            failures.append(f"{rel}: at {width} px the page is {wide} px wide")
        rows = json.loads(d.execute_script(
            "return JSON.stringify([...document.querySelectorAll('div.arithmatex')].map(e => [e.scrollWidth,"
            " e.clientWidth, parseFloat(e.style.fontSize || '100'), e.textContent.slice(0, 40)]))"))
        formulas += len(rows)
        for scroll, client, percent, label in rows:
            if scroll > client + 1:
                failures.append(f"{rel}: at {width} px a formula scrolls sideways ({scroll} px of {client}): {label}")
            if percent < 65:
                failures.append(f"{rel}: at {width} px a formula is scaled to {percent} %: {label}")
    if formulas == 0:
        failures.append(f"at {width} px: no display formula found to check")
        if page.name in ("index.html", "10_refraction.html"):
            d.save_screenshot(str(out / f"site_phone_{page.stem}.png"))
    d.set_window_size(1280, 900)


def check_search(d, site, failures):
    d.get((site / "index.html").as_uri())
    box = d.find_element(By.CSS_SELECTOR, "input.md-search__input")
    if not box.is_displayed():  # Material 9 (Debian 13) folds search into the header's button
        for toggle in d.find_elements(By.CSS_SELECTOR, 'label[for="__search"]'):
            if toggle.is_displayed():
                toggle.click()
                break
        WebDriverWait(d, 5).until(lambda d: box.is_displayed())
    box.click()
    box.send_keys("Schlick")
    try:
        WebDriverWait(d, 10).until(lambda d: d.find_elements(By.CSS_SELECTOR, ".md-search-result__item"))
    except Exception:
        failures.append("search from disk: no results for 'Schlick'")
    # A code page's hit shows code, not its line-number gutter (hooks.py).
    texts = d.execute_script("return [...document.querySelectorAll('.md-search-result__item')]"
                             ".map(e => e.textContent)")
    if any("1 2 3 4 5" in t for t in texts):
        failures.append("search: a hit's excerpt is a code page's line numbers")
    if not any("code/" in (h or "") for h in d.execute_script(
            "return [...document.querySelectorAll('.md-search-result__link')].map(a => a.getAttribute('href'))")):
        failures.append("search: no code page among the hits for 'Schlick'")
    for entry in d.get_log("browser"):
        failures.append(f"search: console: {entry['level']} {entry['message']}")


def main(site, docs, out):
    site, docs, out = pathlib.Path(site).resolve(), pathlib.Path(docs).resolve(), pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    pages = sorted(p for p in site.rglob("*.html") if p.name != "404.html")
    if not (site / "index.html").is_file():
        print(f"test_site: no site in {site}")
        return 1
    failures, with_math = [], 0
    d = browser()
    try:
        start = time.time()
        # The code pages (one per source file) come from one template: a
        # tenth of them open in the browser, and every one's links are
        # checked from its HTML (a page in Chromium takes 0.6 s).
        code = [p for p in pages if p.relative_to(site).parts[0] == "code"]
        browsed = [p for p in pages if p not in code] + code[::10]
        for page in browsed:
            with_math += check_page(d, site, page, docs, failures)
        for page in code:
            if page not in browsed:
                rel = page.relative_to(site).as_posix()
                check_links(site, page, parsed(page).links, lambda msg, rel=rel: failures.append(f"{rel}: {msg}"))
        check_search(d, site, failures)
        check_phone(d, site, [p for p in pages if p.relative_to(site).parts[0] != "code"], failures, out)
        for name, shot in (("index.html", "site_index.png"), ("10_refraction.html", "site_10_refraction.png")):
            d.get((site / name).as_uri())
            time.sleep(0.3)
            d.save_screenshot(str(out / shot))
        print(f"test_site: {len(pages)} pages ({len(browsed)} in the browser, {with_math} with math) checked in {time.time() - start:.1f} s; "
              f"screenshots in {out}")
    finally:
        d.quit()
    if with_math == 0:
        failures.append("no page has math: the formula check checked nothing")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(*sys.argv[1:]))
