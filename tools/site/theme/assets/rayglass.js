// Renders the formulas pymdownx.arithmatex marked (\(...\) inline, \[...\]
// display) with KaTeX, which the site carries (no network).
(function () {
  for (const el of document.querySelectorAll(".arithmatex")) {
    const tex = el.textContent.trim().replace(/^\\[(\[]/, "").replace(/\\[)\]]$/, "");
    try {
      katex.render(tex, el, {displayMode: el.tagName === "DIV", throwOnError: true});
    } catch (e) {
      console.error("KaTeX: " + e.message + " in: " + tex);
    }
  }
  // On a narrow screen (a phone's 390 px) a display formula wider than its
  // column is scaled down to fit, instead of hiding its end behind a
  // sideways scroll; the widest are written on two lines in the pages, so
  // that none is scaled below about two thirds (tests/test_site.py).
  // Widths are measured again after each step (not all of a formula
  // scales with its font size), and again once KaTeX's fonts have loaded.
  function fit() {
    for (const el of document.querySelectorAll("div.arithmatex")) {
      let percent = 100;
      el.style.fontSize = "";
      for (let i = 0; i < 4 && el.scrollWidth > el.clientWidth + 1; ++i) {
        percent *= 0.99 * el.clientWidth / el.scrollWidth;
        el.style.fontSize = percent.toFixed(1) + "%";
      }
    }
  }
  fit();
  if (document.fonts) document.fonts.ready.then(fit);
  // A figure is a link to itself: a click shows it at its full size (the
  // column is narrower than most of the chapters' pictures).
  for (const img of document.querySelectorAll("article img")) {
    if (img.closest("a")) continue;
    const a = document.createElement("a");
    a.href = img.getAttribute("src");
    a.className = "rg-enlarge";
    a.title = "full size";
    img.replaceWith(a);
    a.appendChild(img);
  }
  window.addEventListener("load", fit);
  window.addEventListener("resize", fit);
})();
