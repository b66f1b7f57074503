#!/usr/bin/env python3
"""Tests of tools/docs.py, the check that keeps quoted code true to the code:
on a small repository made in a temporary folder, a nested region is quoted
whole and without inner markers, and a page holding a truncated listing (what
the old parser produced) fails the check. Also tools/site.sh's repository
link: a clone's public origin as its web address, and none for any other."""
import pathlib
import shutil
import subprocess
import sys
import tempfile
import unittest

DOCS_PY = pathlib.Path(__file__).resolve().parent.parent / "tools" / "docs.py"
CODE_MAP_PY = DOCS_PY.parent / "code_map.py"
SITE_SH = DOCS_PY.parent / "site.sh"

SOURCE = """\
void f() {
    // [region outer]
    int a = 1;
    // [region inner]
    int b = 2;
    // [end]
    int c = 3;
    // [end]
}
"""

WHOLE = "```glsl\nint a = 1;\nint b = 2;\nint c = 3;\n```\n"
TRUNCATED = "```glsl\nint a = 1;\n// [region inner]\nint b = 2;\n```\n"


def docs(root, *args):
    return subprocess.run([sys.executable, str(DOCS_PY), "--root", str(root), *args],
                          capture_output=True, text=True)


class DocsCheck(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = pathlib.Path(self.tmp.name)
        (self.root / "docs").mkdir()
        (self.root / "a.rgen").write_text(SOURCE)

    def tearDown(self):
        self.tmp.cleanup()

    def page(self, body, name="p.md"):
        (self.root / "docs" / name).write_text(body)

    def test_nested_region_quoted_whole_without_markers(self):
        self.page("<!-- snippet: a.rgen#outer -->\n<!-- end -->\n")
        self.assertEqual(docs(self.root, "--write").returncode, 0)
        text = (self.root / "docs" / "p.md").read_text()
        self.assertIn(WHOLE, text)
        self.assertNotIn("[region", text.replace("<!-- snippet", ""))
        self.assertEqual(docs(self.root, "--check").returncode, 0)

    def test_listing_names_its_file(self):
        # The caption links the file: on the site, its code page (hooks.py).
        self.page("<!-- snippet: a.rgen#inner -->\n<!-- end -->\n")
        docs(self.root, "--write")
        self.assertIn("<!-- snippet: a.rgen#inner -->\n[`a.rgen`](../a.rgen)\n\n```glsl\n",
                      (self.root / "docs" / "p.md").read_text())

    def test_inner_region_alone(self):
        self.page("<!-- snippet: a.rgen#inner -->\n<!-- end -->\n")
        docs(self.root, "--write")
        self.assertIn("```glsl\nint b = 2;\n```\n", (self.root / "docs" / "p.md").read_text())

    def test_a_source_line_over_90_characters_fails_the_check(self):
        (self.root / "shaders").mkdir()
        (self.root / "shaders" / "ok.rgen").write_text("x" * 90 + "\n")
        self.assertEqual(docs(self.root, "--check").returncode, 0)
        (self.root / "shaders" / "long.glsl").write_text("int a;\n" + "y" * 91 + "\n")
        r = docs(self.root, "--check")
        self.assertEqual(r.returncode, 1)
        self.assertIn("shaders/long.glsl:2 (91 characters)", r.stdout)

    def test_truncated_listing_fails_the_check(self):
        self.page("<!-- snippet: a.rgen#outer -->\n" + TRUNCATED + "<!-- end -->\n")
        r = docs(self.root, "--check")
        self.assertEqual(r.returncode, 1)
        self.assertIn("p.md: snippet a.rgen#outer", r.stdout)

    def test_diff_leaves_markers_out(self):
        (self.root / "b.rgen").write_text(SOURCE.replace("int c = 3;", "int c = 4;"))
        self.page("<!-- diff: a.rgen b.rgen -->\n<!-- end -->\n")
        self.assertEqual(docs(self.root, "--write").returncode, 0)
        text = (self.root / "docs" / "p.md").read_text()
        self.assertIn("-    int c = 3;\n+    int c = 4;", text)
        self.assertNotIn("// [", text)

    def test_unbalanced_markers_are_an_error(self):
        (self.root / "a.rgen").write_text(SOURCE.replace("    // [end]\n}", "}"))
        self.page("<!-- snippet: a.rgen#inner -->\n<!-- end -->\n")
        r = docs(self.root, "--check")
        self.assertEqual(r.returncode, 1)
        self.assertIn("never closed", r.stderr)

    def test_footer_links_sources_and_neighbours(self):
        for n, name in ((1, "01_a"), (2, "02_b"), (3, "03_c")):
            (self.root / "chapters" / name).mkdir(parents=True)
            (self.root / "chapters" / name / "main.cpp").write_text("int main() {}\n")
            (self.root / "docs" / f"{name}.md").write_text(f"# {n:02d} · Title {n}\n")
        self.page("# 02 · Title 2\n<!-- footer: 02_b -->\n<!-- end -->\n", "02_b.md")
        self.assertEqual(docs(self.root, "--write").returncode, 0)
        text = (self.root / "docs" / "02_b.md").read_text()
        self.assertIn("[`chapters/02_b/main.cpp`](../chapters/02_b/main.cpp)", text)
        self.assertIn("Previous: [01 · Title 1](01_a.md)", text)
        self.assertIn("Next: [03 · Title 3](03_c.md)", text)
        self.assertIn("## Next\n\n[03 · Title 3](03_c.md).", text)  # no index.md: no teaser
        self.assertIn("cmake --build build --target 02_b  # this chapter alone", text)
        self.assertIn("ctest --test-dir build -L 02", text)
        (self.root / "docs" / "index.md").write_text("| # | chapter | thesis | new in it |\n| 03 | [c](03_c.md) | 1 | rays |\n")
        self.assertEqual(docs(self.root, "--check").returncode, 1)  # the teaser comes from the index
        self.assertEqual(docs(self.root, "--write").returncode, 0)
        self.assertIn("[03 · Title 3](03_c.md): rays.", (self.root / "docs" / "02_b.md").read_text())
        (self.root / "docs" / "03_c.md").write_text("# 03 · Renamed\n")
        self.assertEqual(docs(self.root, "--check").returncode, 1)  # the next page's title changed

    def test_footer_links_the_shared_modules_a_chapter_includes(self):
        for n, name in ((1, "01_a"), (2, "02_b")):
            (self.root / "chapters" / name).mkdir(parents=True)
            (self.root / "docs" / f"{name}.md").write_text(f"# {n:02d} · Title {n}\n")
        (self.root / "shared" / "vulkan").mkdir(parents=True)
        (self.root / "shared" / "core").mkdir(parents=True)
        (self.root / "shared" / "vulkan" / "context.h").write_text("")
        (self.root / "shared" / "core" / "cli.h").write_text("")
        (self.root / "chapters" / "02_b" / "main.cpp").write_text(
            '#include "vulkan/context.h"\n#include "core/cli.h"\n#include <vector>\n')
        (self.root / "chapters" / "01_a" / "main.cpp").write_text("int main() {}\n")
        self.page("# 02 · Title 2\n<!-- footer: 02_b -->\n<!-- end -->\n", "02_b.md")
        self.assertEqual(docs(self.root, "--write").returncode, 0)
        text = (self.root / "docs" / "02_b.md").read_text()
        # bottom layer first, each a link to its file, and the map
        self.assertIn("**Shared modules it includes:** [`core/cli.h`](../shared/core/cli.h) · "
                      "[`vulkan/context.h`](../shared/vulkan/context.h) ([code map](code-map.md))",
                      text)

    def test_a_block_without_its_end_is_an_error_and_writes_nothing(self):
        body = ("<!-- snippet: a.rgen#inner -->\n\nProse that --write must not swallow.\n\n"
                "<!-- snippet: a.rgen#outer -->\n<!-- end -->\n")
        self.page(body)
        for mode in ("--write", "--check"):
            r = docs(self.root, mode)
            self.assertEqual(r.returncode, 1)
            self.assertIn("a.rgen#inner has no <!-- end --> before the next block", r.stderr)
        self.assertEqual((self.root / "docs" / "p.md").read_text(), body)

    def test_missing_region_is_an_error(self):
        self.page("<!-- snippet: a.rgen#nothere -->\n<!-- end -->\n")
        r = docs(self.root, "--check")
        self.assertEqual(r.returncode, 1)
        self.assertIn("no region 'nothere'", r.stderr)


def code_map(root):
    return subprocess.run([sys.executable, str(CODE_MAP_PY), "--root", str(root), "--check"],
                          capture_output=True, text=True)


class CodeMapCheck(unittest.TestCase):
    """tools/code_map.py on a small shared/ made in a temporary folder: it
    passes as made, and each fault it exists for makes it fail."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = pathlib.Path(self.tmp.name)
        for folder in ("core", "vulkan"):
            (self.root / "shared" / folder).mkdir(parents=True)
            (self.root / "shared" / folder / "README.md").write_text(f"# {folder}/\n")
        (self.root / "shared" / "vk_check.h").write_text("")
        (self.root / "shared" / "core" / "files.h").write_text('#include "vk_check.h"\n')
        (self.root / "shared" / "vulkan" / "context.h").write_text('#include "core/files.h"\n')
        (self.root / "shared" / "vulkan" / "context.cpp").write_text('#include "vulkan/context.h"\n')
        (self.root / "docs").mkdir()
        (self.root / "docs" / "code-map.md").write_text(
            "`core/` `core/files` `vulkan/` `vulkan/context`\n")

    def tearDown(self):
        self.tmp.cleanup()

    def fails_with(self, words):
        r = code_map(self.root)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn(words, r.stderr)

    def test_a_clean_tree_passes(self):
        r = code_map(self.root)
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_an_include_that_climbs_up_fails(self):
        (self.root / "shared" / "core" / "files.h").write_text('#include "vulkan/context.h"\n')
        self.fails_with("shared/core/files.h: includes vulkan/context.h, which climbs from core/ "
                        "up to vulkan/")

    def test_a_module_missing_from_the_map_fails(self):
        (self.root / "shared" / "vulkan" / "window.h").write_text("")
        self.fails_with("does not name the module `vulkan/window`")

    def test_a_file_directly_in_shared_fails(self):
        (self.root / "shared" / "helpers.h").write_text("")
        self.fails_with("shared/helpers.h: directly in shared/")

    def test_a_long_file_fails(self):
        (self.root / "shared" / "core" / "files.h").write_text("int a;\n" * 600)
        self.fails_with("shared/core/files.h: 600 lines")

    def test_a_folder_without_readme_or_layer_fails(self):
        (self.root / "shared" / "vulkan" / "README.md").unlink()
        self.fails_with("shared/vulkan/: no README.md")
        (self.root / "shared" / "misc").mkdir()
        self.fails_with("shared/misc/: not a layer")


# A fresh Debian has no git (the CI's Debian 13 system): with no clone there
# is no origin to read, and site.sh then links nothing.
@unittest.skipUnless(shutil.which("git"), "git is not installed")
class SiteRepoLink(unittest.TestCase):
    """The site links the repository only where the clone says where it is
    public; the addresses here are made up for the test and never built."""

    def link(self, origin):
        with tempfile.TemporaryDirectory() as tmp:
            root = pathlib.Path(tmp)
            (root / "tools").mkdir()
            (root / "tools" / "site.sh").write_bytes(SITE_SH.read_bytes())
            subprocess.run(["git", "init", "-q", str(root)], check=True)
            if origin:
                subprocess.run(["git", "-C", str(root), "remote", "add", "origin", origin],
                               check=True)
            r = subprocess.run(["bash", str(root / "tools" / "site.sh"), "--repo-url"],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            return r.stdout.strip()

    def test_public_origins_become_web_addresses(self):
        self.assertEqual(self.link("git@github.com:someone/rayglass.git"),
                         "https://github.com/someone/rayglass")
        self.assertEqual(self.link("ssh://git@github.com/someone/rayglass.git"),
                         "https://github.com/someone/rayglass")
        # a token in the origin never reaches a page
        self.assertEqual(self.link("https://user:token@gitlab.com/a/b.git"),
                         "https://gitlab.com/a/b")

    def test_no_public_origin_no_link(self):
        self.assertEqual(self.link(""), "")
        self.assertEqual(self.link("/srv/git/rayglass"), "")
        self.assertEqual(self.link("file:///srv/git/rayglass"), "")


if __name__ == "__main__":
    unittest.main()
