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
})();
