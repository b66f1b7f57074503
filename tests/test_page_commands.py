#!/usr/bin/python3
"""Every command a chapter page (or the README) prints in a ```sh block is
run as printed, so that a page cannot show a command that fails.

Each block runs as one bash script (set -e) in a fresh folder that looks
like the repository's root: assets/, tests/, tools/ and docs/ are the
sources', and build/bin/ holds one small script per chapter (and per tool
a page runs) that runs the real executable with --validation added. An
exercise's `tools/exercise.py NN --check`, run on the starter the block has
just made, must say "not yet". No display is set, so commands
printed for a window run headless. The lines that build or test the tree
itself (cmake --build, ctest) are left out, and so is a command the page
has already printed. A block passes when it exits 0,
prints no validation message and every chapter report it wrote says 0
validation messages.

    tests/test_page_commands.py PAGE.md BUILD_BIN_DIR
"""
import json
import os
import pathlib
import re
import signal
import subprocess
import sys
import tempfile
import time

from timescale import seconds as scaled  # a block's limit on a busy machine

ROOT = pathlib.Path(__file__).resolve().parent.parent
# they install, build and test the tree this test runs in
SKIPPED = ("cmake ", "ctest ", "tools/setup.sh", "tools/test.sh")


def blocks(markdown):
    # Not the footer's "Build and run this chapter" box: tools/docs.py writes
    # it alike for every page, and test_cli.cpp's OutputsGoToOutByDefault
    # runs its commands for every chapter.
    markdown = re.sub(r"<!-- footer: .*?<!-- end -->", "", markdown, flags=re.S)
    # a block inside a list item is indented: its lines lose the fence's indent
    found = re.findall(r"^( *)```sh\n(.*?)^\1```", markdown, re.S | re.M)
    return ["".join(l[len(indent):] if l.startswith(indent) else l for l in body.splitlines(True))
            for indent, body in found]


def make_root(folder, bin_dir):
    for name in ("assets", "tests", "tools", "docs"):
        (folder / name).symlink_to(ROOT / name)
    bin_copy = folder / "build" / "bin"
    bin_copy.mkdir(parents=True)
    (bin_copy / "assets").symlink_to(bin_dir / "assets")
    # the chapters, and the tools a page runs (chapter 12's leak_probe)
    for exe in sorted(bin_dir.glob("[0-9][0-9]_*")) + [bin_dir / "leak_probe"]:
        if exe.is_file() and os.access(exe, os.X_OK):
            wrapper = bin_copy / exe.name
            wrapper.write_text(f'#!/bin/sh\nexec "{exe}" "$@" --validation\n')
            wrapper.chmod(0o755)


def run_block(block, bin_dir, seen):
    """Runs a block; `seen` holds the one-line commands already run from this
    page, which are not run again (without a display, a window's command is
    its --headless one)."""
    lines = []
    for line in block.splitlines():
        command = line.split("  #")[0].strip()
        if command.startswith(SKIPPED):
            continue
        if command.startswith("build/bin/") and not command.endswith("\\"):
            key = " ".join(a for a in command.split() if a != "--headless")
            if key in seen:
                continue
            seen.add(key)
        if command.startswith("tools/exercise.py") and "--check" in command:
            # right after the starter is made, the check must say "not yet"
            # (exit 1); exit 2 (its input refused) fails the block
            lines += [f"{command} > exercise-check.txt || test $? -eq 1", "cat exercise-check.txt",
                      "grep -q '^not yet: ' exercise-check.txt"]
            continue
        lines.append(line)
    script = "\n".join(lines)
    if not script.strip():
        return None
    print(f"run: {script.strip().splitlines()[0]}", flush=True)
    with tempfile.TemporaryDirectory(prefix="rayglass-page-") as work:
        folder = pathlib.Path(work)
        make_root(folder, bin_dir)
        env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
        # bash traces each command it starts into a file: a block that runs
        # past its limit is reported with the command that was running.
        trace = folder / "trace.txt"
        prologue = f"exec 9>'{trace}'; BASH_XTRACEFD=9; set -x -euo pipefail\n"
        limit = scaled(240)
        start = time.monotonic()
        with subprocess.Popen(["bash", "-c", prologue + script], cwd=folder, env=env, text=True,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True) as p:
            try:
                stdout, stderr = p.communicate(timeout=limit)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)  # bash and the chapter it runs
                p.communicate()
                started = [l for l in trace.read_text().splitlines() if l.startswith("+ ")]
                return [f"timed out after {limit:.0f} s in `{started[-1][2:] if started else script}`"]
        r = subprocess.CompletedProcess(p.args, p.returncode, stdout, stderr)
        print(f"  took {time.monotonic() - start:.1f} s", flush=True)
        problems = []
        if r.returncode != 0:
            tail = (r.stdout + r.stderr).strip().splitlines()[-3:]
            problems.append(f"exit {r.returncode}: " + " | ".join(tail))
        if re.search(r"validation message|VUID-|SYNC-HAZARD", r.stdout + r.stderr):
            problems.append("a validation message")
        reports = 0
        for path in folder.rglob("*.json"):
            if any(p.is_symlink() for p in [path, *path.parents] if folder in p.parents):
                continue  # the sources' own scene files
            try:
                report = json.loads(path.read_text())
            except ValueError:
                continue
            if isinstance(report, dict) and "validation_messages" in report:
                reports += 1
                if report["validation_messages"] != 0:
                    problems.append(f"{path.name}: {report['validation_messages']} validation messages")
        # A tool writes no chapter report; with --validation, a message
        # makes it exit 1 (runChapter), which the exit code above catches.
        if r.returncode == 0 and reports == 0 and re.search(r"build/bin/[0-9][0-9]_", script):
            problems.append("no chapter report written")
        return problems


def main(page, bin_dir):
    page, bin_dir = pathlib.Path(page), pathlib.Path(bin_dir).resolve()
    failures, ran, seen = [], 0, set()
    for block in blocks(page.read_text()):
        problems = run_block(block, bin_dir, seen)
        if problems is None:
            continue
        ran += 1
        first = block.strip().splitlines()[0]
        failures += [f"{page.name}: `{first}`: {p}" for p in problems]
    for f in failures:
        print("FAIL", f)
    print(f"test_page_commands: {ran} block(s) of {page.name} run")
    if ran == 0:
        print(f"FAIL {page.name}: no command to run")
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(*sys.argv[1:]))
