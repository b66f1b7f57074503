#!/usr/bin/python3
"""A ray tracing chapter's window, driven as a user would (issue 10).

Starts its own Xvfb (whose framebuffer file is the screenshot), runs the
chapter with the validation layer, and moves the mouse and presses keys with
xdotool. Standard library only.

    test_interactive.py EXE OUT_DIR SCENE_JSON [--full] [--reload] [--preview] [--antialias] [--size WxH]

Every chapter: a drag changes the picture, R brings the first one back (also
after a whole drag that reaches the viewer within one frame, and when the
drag and the R reach it in one frame), Esc
ends the process with exit 0 and no validation message. --full (chapter
10: it has a depth parameter) adds: a right drag pans; F2's report has the
moved camera; the overlay is in the window but not in the F2 PNG, which
equals the headless PNG; a click picks a material; the overlay's depth
slider changes the parameter and the picture; the View and light section's
field of view, light position and exposure change the picture and F2's
report; a resize re-creates the target.
--reload (at 480x270, where the overlay's error line fits) edits the sky's
miss shader in a copy of the shader tree: the picture changes; a broken
edit shows its file and line in the overlay and the last picture stays; the
fix brings the first picture back; F5 compiles again.
--preview (a chapter whose full frames are slow: 13 on lavapipe, at
480x270) drags for three seconds: the window shows more pictures meanwhile
than full frames (a headless run's fastest) could: a smaller launch;
then full frames once it rests; Esc during a drag still
writes a full frame as the run's PNG.
--antialias: the window as it starts, antialiasing: at rest F2's picture is
what a headless run of the frames it reports writes, and after a drag too
(the average started again); it differs from the pixel centres' picture.
Chapter 14 (its report has photons): the photon map was traced for fewer
frames than the window showed (kept while only the view moved).
The other modes run with --antialias off, to compare single frames.
"""
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time

import numpy as np
from PIL import Image

from timescale import seconds as scaled  # a wait's limit on a busy machine

EXE, OUT, SCENE = (os.path.abspath(a) for a in sys.argv[1:4])
FULL = "--full" in sys.argv[4:]
RELOAD = "--reload" in sys.argv[4:]
PREVIEW = "--preview" in sys.argv[4:]
ANTIALIAS = "--antialias" in sys.argv[4:]
NAME = os.path.basename(EXE)
W, H = (560, 315) if FULL else (480, 270) if RELOAD or PREVIEW else (160, 90)
if "--size" in sys.argv:
    W, H = map(int, sys.argv[sys.argv.index("--size") + 1].split("x"))
BLUE_SPHERE = (203 * W // 320, 125 * H // 180)  # where the default scene's small blue sphere is
failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what, flush=True)
    if not ok:
        failures.append(what)


def display_in_use(display):
    """True when a live X server holds the display (a killed one leaves its
    lock file and socket behind: those are removed)."""
    lock, socket = f"/tmp/.X{display}-lock", f"/tmp/.X11-unix/X{display}"
    try:
        pid = int(open(lock).read().strip())
        os.kill(pid, 0)
        return True
    except (FileNotFoundError, ValueError):
        if not os.path.exists(lock):
            return os.path.exists(socket) and not os.access(socket, os.W_OK)
    except ProcessLookupError:
        pass
    except PermissionError:
        return True  # alive, another user's
    for stale in (lock, socket):
        try:
            os.remove(stale)
        except OSError:
            pass
    return False


def start_xvfb(fbdir):
    for display in range(90, 140):
        if display_in_use(display):
            continue
        proc = subprocess.Popen(["Xvfb", f":{display}", "-screen", "0", "800x600x24", "-fbdir", fbdir,
                                 "-nolisten", "tcp"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        end = time.time() + scaled(5)
        while time.time() < end:
            if os.path.exists(os.path.join(fbdir, "Xvfb_screen0")) and os.path.exists(f"/tmp/.X11-unix/X{display}"):
                return proc, f":{display}"
            if proc.poll() is not None:
                break
            time.sleep(0.1)
        proc.kill()
    sys.exit("no free X display for Xvfb")


def xdotool(*args):
    return subprocess.run(["xdotool", *map(str, args)], env=ENV, check=True, capture_output=True,
                          text=True).stdout.strip()


def screen(fbdir):
    """The Xvfb framebuffer (XWD format) as (width, height, rows of RGB tuples)."""
    with open(os.path.join(fbdir, "Xvfb_screen0"), "rb") as f:
        data = f.read()
    header = struct.unpack(">25I", data[:100])
    size, width, height, bpp, stride, ncolors = header[0], header[4], header[5], header[11], header[12], header[19]
    assert bpp == 32, bpp
    start = size + 12 * ncolors
    rows = []
    for y in range(height):
        row = data[start + y * stride:start + y * stride + 4 * width]
        rows.append([(row[4 * x + 2], row[4 * x + 1], row[4 * x]) for x in range(width)])  # B G R X
    return width, height, rows


def window_shot(box):
    x0, y0, w, h = box
    _, _, rows = screen(FBDIR)
    return [r[x0:x0 + w] for r in rows[y0:y0 + h]]


def diff(a, b, region=None):
    """Mean absolute difference (0-255) over a region (x0, y0, x1, y1) of two shots."""
    x0, y0, x1, y1 = region or (0, 0, len(a[0]), len(a))
    total = n = 0
    for y in range(y0, y1):
        for x in range(x0, x1):
            total += sum(abs(p - q) for p, q in zip(a[y][x], b[y][x]))
            n += 3
    return total / max(n, 1)


def read_png_rgb(path):
    """A PNG's pixels as rows of (r, g, b) (Debian's python3-pil decodes it)."""
    with Image.open(path) as image:
        pixels = np.asarray(image.convert("RGB"))
    return [[tuple(p) for p in row] for row in pixels.tolist()]


def write_png(path, rows):
    """The window's pixels as an 8-bit RGB PNG (saved beside the test's output)."""
    Image.fromarray(np.array(rows, dtype=np.uint8), "RGB").save(path)


def shot_when(condition, what, seconds=20):
    """Screenshots until `condition(shot)` holds (a loaded machine renders
    slowly: no fixed sleeps); records a failure after `seconds`, scaled."""
    end = time.time() + scaled(seconds)
    while True:
        shot = window_shot(BOX)
        if condition(shot):
            return shot
        if time.time() > end:
            check(False, what + " (timed out)")
            return shot
        time.sleep(0.3)


def stable_shot(seconds=60):
    """A screenshot once the window shows a picture and three in a row, over
    a second, agree (a loaded machine may show one frame for half a second)."""
    previous, agreeing = window_shot(BOX), 0
    end = time.time() + scaled(seconds)
    while time.time() < end:
        time.sleep(0.5)
        shot = window_shot(BOX)
        same = diff(previous, shot) < 0.3 and diff(shot, [[(0, 0, 0)] * W] * H) > 5
        agreeing = agreeing + 1 if same else 0
        if agreeing >= 2:
            return shot
        previous = shot
    check(False, "the picture settles")
    return previous


def settled_shot(seconds=30):
    """The window once two shots half a second apart agree: past a slow
    machine's short preview at a smaller size (viewer.h)."""
    previous, end = window_shot(BOX), time.time() + scaled(seconds)
    while time.time() < end:
        time.sleep(0.5)
        shot = window_shot(BOX)
        if diff(previous, shot) < 0.3:
            return shot
        previous = shot
    return previous


def drag(box, dx, dy, button=1):
    x0, y0, w, h = box
    cx, cy = x0 + w * 3 // 4, y0 + h * 3 // 4  # away from the overlay (top left)
    xdotool("mousemove", cx, cy)
    time.sleep(0.3)
    xdotool("mousedown", button)
    time.sleep(0.3)
    for i in range(1, 6):
        xdotool("mousemove", cx + dx * i // 5, cy + dy * i // 5)
        time.sleep(0.15)
    xdotool("mouseup", button)
    time.sleep(0.2)


def key(box, name):
    xdotool("mousemove", box[0] + box[2] * 3 // 4, box[1] + box[3] * 3 // 4)  # focus follows the pointer
    xdotool("key", name)


def wait_for(text, log, seconds=10):
    end = time.time() + scaled(seconds)
    while time.time() < end:
        with open(log) as f:
            if text in f.read():
                return True
        time.sleep(0.1)
    return False


shutil.rmtree(OUT, ignore_errors=True)  # F2 numbers its files after those already there
os.makedirs(OUT)
FBDIR = tempfile.mkdtemp(prefix="rg-xvfb-")
xvfb, display = start_xvfb(FBDIR)
ENV = dict(os.environ, DISPLAY=display)
ENV.pop("WAYLAND_DISPLAY", None)
log = os.path.join(OUT, "stdout.txt")
args = [EXE, "--validation", "--width", str(W), "--height", str(H), "--no-ui", "--output", "window.png"]
if not ANTIALIAS:  # the checks below compare pictures: one frame's, not an average still converging
    args += ["--antialias", "off"]
if RELOAD:  # a copy of what the shaders read, to edit
    TREE = os.path.join(OUT, "tree")
    SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    shutil.copytree(os.path.join(SOURCE, "shaders"), os.path.join(TREE, "shaders"))
    os.makedirs(os.path.join(TREE, "shared"))
    shutil.copy(os.path.join(SOURCE, "shared", "host_device.h"), os.path.join(TREE, "shared"))
    args += ["--shader-source", TREE]
with open(log, "w") as out:
    chapter = subprocess.Popen(args, cwd=OUT, env=ENV, stdout=out, stderr=subprocess.STDOUT)
try:
    wid = xdotool("search", "--sync", "--onlyvisible", "--name", "RayGlass")
    geometry = dict(line.split("=") for line in xdotool("getwindowgeometry", "--shell", wid).split())
    box = BOX = (int(geometry["X"]), int(geometry["Y"]), W, H)
    first = stable_shot()
    check(diff(first, [[(0, 0, 0)] * W] * H) > 5, "the window shows a picture")
    def changed(s, region=None):
        return diff(first, s, region) > 2
    def restored(s):
        return diff(first, s) < 0.5

    drag(box, 60, 20)
    dragged = shot_when(changed, "a left drag changes the picture")
    check(changed(dragged), f"a left drag changes the picture (mean difference {diff(first, dragged):.1f})")

    key(box, "r")
    reset = shot_when(restored, "R brings the first picture back")
    check(restored(reset), f"R brings the first picture back (mean difference {diff(first, reset):.2f})")

    # A whole drag within one frame (as after a slow frame on a loaded
    # machine): press, moves and release reach the viewer in one poll.
    cx, cy = box[0] + W * 3 // 4, box[1] + H * 3 // 4
    xdotool("mousemove", cx, cy)
    time.sleep(0.3)
    xdotool("mousedown", 1, *[a for i in range(1, 6) for a in ("mousemove", cx + 12 * i, cy + 4 * i)], "mouseup", 1)
    quick = shot_when(changed, "a drag within one frame orbits")
    check(changed(quick), f"a drag within one frame orbits (mean difference {diff(first, quick):.1f})")
    key(box, "r")
    shot_when(restored, "R after the quick drag")
    # A drag and then R, within one frame: taken in that order, R wins.
    xdotool("mousedown", 1, *[a for i in range(1, 6) for a in ("mousemove", cx + 12 * i, cy + 4 * i)],
            "mouseup", 1, "key", "r")
    time.sleep(1)
    last = shot_when(restored, "a drag and R within one frame end at the first picture")
    check(restored(last), f"a drag and R within one frame end at the first picture "
          f"(mean difference {diff(first, last):.2f})")

    xdotool("mousemove", box[0] + W * 3 // 4, box[1] + H * 3 // 4)
    xdotool("click", "--repeat", 3, "--delay", 100, 4)  # wheel up: zoom in
    zoomed = shot_when(changed, "the wheel zooms")
    check(changed(zoomed), f"the wheel zooms (mean difference {diff(first, zoomed):.1f})")
    key(box, "r")
    shot_when(restored, "R after zooming")
    xdotool("keydown", "w")  # fly forward for a moment
    time.sleep(0.5)
    xdotool("keyup", "w")
    flown = shot_when(changed, "W flies forward")
    check(changed(flown), f"W flies forward (mean difference {diff(first, flown):.1f})")
    key(box, "c")
    check(wait_for('"camera": {"fov_y_deg"', log), "C prints the camera as a scene-file block")
    key(box, "r")
    shot_when(restored, "R after flying")

    if RELOAD:
        sky = os.path.join(TREE, "shaders", "common", "sky.rmiss")
        original = open(sky).read()
        call = "skyRadiance(gl_WorldRayDirectionEXT);"
        assert call in original

        def save(text):
            with open(sky, "w") as f:
                f.write(text)

        def reloads(count):
            end = time.time() + scaled(60)
            while time.time() < end:
                if open(log).read().count("shaders: reloaded") >= count:
                    return True
                time.sleep(0.2)
            return False

        def red(p):  # the overlay's error text
            return p[0] > 180 and p[0] - p[1] > 80 and p[0] - p[2] > 80

        def red_text(before, after):
            """Where pixels became the error's red."""
            return {(x, y) for y, (a, b) in enumerate(zip(before, after)) for x, (p, q) in enumerate(zip(a, b))
                    if red(q) and not red(p)}

        right = (W * 3 // 4, 0, W, H)  # beside the overlay (310 px wide)
        away = (box[0] + W + 20, box[1] + H + 20)  # the pointer: its shape changes with the overlay's
        xdotool("mousemove", *away)
        save(original.replace(call, call[:-1] + ".bgr;"))  # the sky's red and blue swapped
        check(reloads(1), "saving an edited shader reloads it")
        shot_when(lambda s: changed(s, right), "the edited shader changes the picture")
        edited = settled_shot()
        check(changed(edited, right), f"the edited shader changes the picture ({diff(first, edited, right):.1f})")

        save(original.replace("skyRadiance(", "skyRadianc("))
        check(wait_for("shader error: shaders/common/sky.rmiss:13: 'skyRadianc'", log, 60),
              "a compile error names the file and line")
        broken = shot_when(lambda s: len(red_text(edited, s)) > 20, "the overlay shows the error in red")
        write_png(os.path.join(OUT, "window_shader_error.png"), broken)
        error_text = red_text(edited, broken)
        check(len(error_text) > 20, f"the overlay shows the error ({len(error_text)} red pixels)")
        time.sleep(1)  # frames go on with the last good pipeline
        check(diff(edited, window_shot(box), right) < 0.5, "the last good pipeline keeps running")

        save(original)
        check(reloads(2), "the fixed shader reloads")
        fixed = shot_when(lambda s: diff(first, s, right) < 0.5, "the fix brings the first picture back")
        check(diff(first, fixed, right) < 0.5, f"the fix brings the first picture back ({diff(first, fixed, right):.2f})")
        still = sum(red(fixed[y][x]) for x, y in error_text)
        check(still < len(error_text) // 20, f"the error is gone from the overlay ({still} red pixels left)")
        key(box, "F5")
        xdotool("mousemove", *away)
        check(reloads(3), "F5 compiles and reloads the shaders")
        key(box, "h")  # the error showed the overlay: hide it again
        shot_when(restored, "H hides the overlay again")

    if FULL:
        drag(box, -50, 0, button=3)  # right drag: pan
        panned = shot_when(changed, "a right drag pans")
        check(changed(panned), f"a right drag pans (mean difference {diff(first, panned):.1f})")
        key(box, "F2")
        check(wait_for(f"{NAME}_shot1.png", log), "F2 writes a screenshot")
        shot = json.load(open(os.path.join(OUT, f"{NAME}_shot1.json")))
        scene_camera = json.load(open(SCENE))["camera"]
        moved = max(abs(a - b) for a, b in zip(shot["camera"]["position"], scene_camera["position"]))
        check(moved > 0.01, f"F2's report has the moved camera ({shot['camera']['position']})")
        check(shot["width"] == W and shot["height"] == H, "F2's report has the image size")

        key(box, "r")
        hidden = shot_when(restored, "R after panning")
        corner = (0, 0, W // 3, H // 3)  # where the overlay opens
        right = (W * 2 // 3, 0, W, H)    # beside it, for a parameter's effect
        check(diff(first, hidden, corner) < 0.5, "--no-ui starts without the overlay")
        xdotool("mousemove", box[0] + BLUE_SPHERE[0], box[1] + BLUE_SPHERE[1])
        xdotool("click", 1)  # a quick click, overlay hidden: picks the sphere's material
        key(box, "h")
        shown = shot_when(lambda s: diff(hidden, s, corner) > 5, "H shows the overlay")
        time.sleep(1)
        shown = window_shot(box)  # the overlay fully drawn
        write_png(os.path.join(OUT, "window_overlay.png"), shown)
        check(diff(hidden, shown, corner) > 5, f"H shows the overlay (top left differs by {diff(hidden, shown, corner):.1f})")
        key(box, "F2")
        check(wait_for(f"{NAME}_shot2.png", log), "F2 with the overlay shown")
        picked = json.load(open(os.path.join(OUT, f"{NAME}_shot2.json")))
        check(picked.get("selected_material") == "blue", f"a click picks the blue sphere's material ({picked.get('selected_material')})")
        headless = os.path.join(OUT, "headless.png")
        subprocess.run([EXE, "--headless", "--width", str(W), "--height", str(H), "--frames", "1", "--output",
                        headless], cwd=OUT, check=True, capture_output=True)
        f2 = read_png_rgb(os.path.join(OUT, f"{NAME}_shot2.png"))
        png = read_png_rgb(headless)
        check(diff(f2, png) < 0.01, f"F2's PNG has no overlay: it equals the headless PNG ({diff(f2, png):.3f})")
        check(diff(png, shown, corner) > 5, "the headless PNG differs from the window where the overlay is")

        # The overlay's "depth" slider (ImGui's fixed layout: its row 101 px
        # down, the slider from x = 16): a click at its left end sets 0.
        # From outside the window, moved there and clicked in one go, as a
        # quick hand does: the click comes before a frame has seen the
        # pointer over the overlay.
        xdotool("mousemove", box[0] + W + 20, box[1] + H + 20)
        time.sleep(0.5)
        xdotool("mousemove", box[0] + 18, box[1] + 101, "click", 1)
        depth0 = shot_when(lambda s: diff(shown, s, right) > 2, "depth 0 changes the picture live")
        write_png(os.path.join(OUT, "window_depth0.png"), depth0)
        key(box, "F2")
        check(wait_for(f"{NAME}_shot3.png", log), "F2 after changing a parameter in the overlay")
        changed3 = json.load(open(os.path.join(OUT, f"{NAME}_shot3.json")))
        check(changed3["parameters"]["depth"] == 0, f"the overlay's depth slider set depth {changed3['parameters']['depth']}")
        # That click came with the pointer's move onto the overlay: it is the
        # overlay's, and must not reach the scene's picker behind it.
        check(changed3.get("selected_material") == "blue",
              f"a click on the overlay picks nothing in the scene ({changed3.get('selected_material')})")
        f3 = read_png_rgb(os.path.join(OUT, f"{NAME}_shot3.png"))
        check(diff(f2, f3, right) > 2, f"depth 0 changes the picture live ({diff(f2, f3, right):.1f})")

        # The View and light section (its header 194 px down, under the
        # parameters): the fov slider's left end is 5 degrees, a drag on the
        # first light's x moves it (row 285: after the antialias choice and
        # the exposure), the exposure slider's left end is -10 EV.
        def brightness(s, region):
            x0, y0, x1, y1 = region
            return sum(sum(s[y][x]) for y in range(y0, y1) for x in range(x0, x1)) / ((x1 - x0) * (y1 - y0))
        closed = window_shot(box)
        xdotool("mousemove", box[0] + 60, box[1] + 194, "click", 1)
        # The section's rows below its header: its sliders are there to click
        # once a frame has drawn them (a loaded machine takes its time).
        below = (0, 200, W * 2 // 3, min(H, 300))
        shot_when(lambda s: diff(closed, s, below) > 2, "the View and light section opens")
        wide = stable_shot()
        xdotool("mousemove", box[0] + 18, box[1] + 216, "click", 1)
        narrow = shot_when(lambda s: diff(wide, s, right) > 2, "the fov slider changes the view")
        key(box, "F2")
        check(wait_for(f"{NAME}_shot4.png", log), "F2 after the fov slider")
        fov = json.load(open(os.path.join(OUT, f"{NAME}_shot4.json")))
        check(fov["camera"]["fov_y_deg"] == 5, f"the fov slider set 5 degrees ({fov['camera']['fov_y_deg']})")
        light = fov["lights"][0]["position"]
        key(box, "r")  # back to 45 degrees: the light and exposure act on the whole view
        wide = shot_when(lambda s: diff(wide, s, right) < 0.5, "R brings the field of view back")
        xdotool("mousemove", box[0] + 30, box[1] + 285)
        time.sleep(0.3)
        xdotool("mousedown", 1)
        for i in range(1, 7):
            xdotool("mousemove", box[0] + 30 + 10 * i, box[1] + 285)
            time.sleep(0.15)
        xdotool("mouseup", 1)
        xdotool("mousemove", box[0] + W + 20, box[1] + H + 20)  # no tooltip over the picture
        lit = shot_when(lambda s: diff(wide, s, right) > 1, "a drag on the light's x changes the light")
        key(box, "F2")
        check(wait_for(f"{NAME}_shot5.png", log), "F2 after the light's drag")
        moved = json.load(open(os.path.join(OUT, f"{NAME}_shot5.json")))["lights"][0]["position"]
        check(moved[0] > light[0] + 0.1 and moved[1:] == light[1:], f"the drag moved the light along x ({light} -> {moved})")
        xdotool("mousemove", box[0] + 18, box[1] + 262, "click", 1)
        # The pointer stays on the slider until the picture shows the click:
        # ImGui 1.86 reads the pointer's position once a frame, so moved away
        # within the same slow frame, the click would land where it went.
        dark = shot_when(lambda s: brightness(s, right) < brightness(lit, right) / 4, "exposure -10 darkens the picture")
        xdotool("mousemove", box[0] + W + 20, box[1] + H + 20)
        write_png(os.path.join(OUT, "window_view.png"), [a + b for a, b in zip(lit, dark)])
        check(brightness(dark, right) < brightness(lit, right) / 4,
              f"exposure -10 darkens the picture ({brightness(lit, right):.0f} -> {brightness(dark, right):.0f})")
        key(box, "F2")
        check(wait_for(f"{NAME}_shot6.png", log), "F2 after the exposure slider")
        exposed = json.load(open(os.path.join(OUT, f"{NAME}_shot6.json")))
        check(exposed["parameters"]["exposure"] == -10, f"the exposure slider set -10 ({exposed['parameters']['exposure']})")

        xdotool("windowsize", wid, 400, 240)
        check(wait_for("resized: the target is now 400x240", log), "a resize re-creates the target at 400x240")
        key(box, "F2")
        check(wait_for(f"{NAME}_shot7.png", log), "F2 after the resize")
        resized = json.load(open(os.path.join(OUT, f"{NAME}_shot7.json")))
        check((resized["width"], resized["height"]) == (400, 240), "the report says 400x240 after the resize")

    if ANTIALIAS:
        # A window antialiases by default (--antialias auto): at rest its
        # picture is the mean of the frames since the view last changed,
        # which F2 reports; a headless run of that many frames writes the
        # same picture. After a drag the average starts again, from the new
        # view alone.
        def rendered_again(report, tag):
            """The headless PNG of an F2 report's camera and frames."""
            scene = json.load(open(report["scene"]))
            scene["camera"] = report["camera"]
            with open(os.path.join(OUT, f"{tag}_scene.json"), "w") as f:
                json.dump(scene, f)
            frames = max(1, report["accumulated_frames"])
            subprocess.run([EXE, "--headless", "--width", str(W), "--height", str(H), "--scene", f"{tag}_scene.json",
                            "--antialias", "on", "--frames", str(frames), "--output", f"{tag}.png"], cwd=OUT,
                           check=True, capture_output=True)
            return read_png_rgb(os.path.join(OUT, f"{tag}.png"))
        time.sleep(2)
        for n, moved in ((1, False), (2, True)):
            if moved:
                drag(box, 40, 10)
                time.sleep(2)
            key(box, "F2")
            check(wait_for(f"{NAME}_shot{n}.png", log), f"F2 ({n})")
            report = json.load(open(os.path.join(OUT, f"{NAME}_shot{n}.json")))
            frames = report["accumulated_frames"]
            check(report["parameters"]["antialias"] == "on" and frames >= 4,
                  f"at rest the window averages frames ({report['parameters']['antialias']}, {frames} frames)")
            shot = read_png_rgb(os.path.join(OUT, f"{NAME}_shot{n}.png"))
            again = rendered_again(report, f"again{n}")
            check(diff(shot, again) < 0.01, f"{'after a drag, ' if moved else ''}F2's picture is a headless run's "
                  f"of {frames} antialiased frames ({diff(shot, again):.3f})")
        subprocess.run([EXE, "--headless", "--width", str(W), "--height", str(H), "--scene", "again2_scene.json",
                        "--frames", "1", "--output", "centre.png"], cwd=OUT, check=True, capture_output=True)
        edges = diff(shot, read_png_rgb(os.path.join(OUT, "centre.png")))
        check(edges > 0.05, f"and differs from one ray through each pixel's centre, at the edges ({edges:.3f})")

    if PREVIEW:
        def press_and_move(seconds, step=4):
            """A left drag that goes on for `seconds`; returns the distinct pictures seen."""
            x0, y0 = box[0] + W * 3 // 4, box[1] + H * 3 // 4
            xdotool("mousemove", x0, y0)
            time.sleep(0.3)
            xdotool("mousedown", 1)
            seen, end, i = set(), time.time() + seconds, 0
            while time.time() < end:
                i += 1
                xdotool("mousemove", x0 - step * (i % 40), y0)
                with open(os.path.join(FBDIR, "Xvfb_screen0"), "rb") as f:
                    seen.add(hash(f.read()))
                time.sleep(0.05)
            return len(seen)
        # A full frame's GPU time, from a headless run of the same size now.
        # The drag lasts 3 s, or three full frames on a loaded machine (the
        # full frame in flight when it starts must end first); full frames
        # alone could show at most 2 + that / full_ms pictures in it.
        subprocess.run([EXE, "--headless", "--width", str(W), "--height", str(H), "--frames", "2",
                        "--output", "full.png", "--report", "full.json"], cwd=OUT, check=True,
                       capture_output=True)
        full_ms = json.load(open(os.path.join(OUT, "full.json")))["gpu_ms"]["min"]
        drag_s = max(3.0, 3 * full_ms / 1000)
        bound = 2 + int(drag_s * 1000 / max(full_ms, 1.0))
        pictures = press_and_move(drag_s)
        xdotool("mouseup", 1)
        check(wait_for("slow frames: 1/", log), "slow frames: a smaller launch while the view moves")
        check(full_ms > 0 and pictures > bound, f"the window shows more pictures during a {drag_s:.1f} s drag "
              f"than full frames of {full_ms:.0f} ms could ({pictures} > {bound})")
        key(box, "F2")  # taken from the first full frame
        check(wait_for(f"{NAME}_shot1.png", log, 30), "F2 after the drag")
        shot = read_png_rgb(os.path.join(OUT, f"{NAME}_shot1.png"))
        settled = shot_when(lambda s: diff(shot, s) < 1, "at rest the window shows full frames again")
        check(diff(shot, settled) < 1, f"at rest the window shows full frames again ({diff(shot, settled):.2f})")
        press_and_move(1.0)
        xdotool("key", "Escape")  # during the drag: its frames are the small ones
        xdotool("mouseup", 1)
    else:
        key(box, "Escape")
    try:
        code = chapter.wait(timeout=scaled(10))
    except subprocess.TimeoutExpired:
        chapter.kill()
        code = None
    check(code == 0, f"Esc ends the process with exit 0 (got {code}; --validation fails on any message)")
    report = json.load(open(os.path.join(OUT, "window.json"))) if code == 0 else {}
    if "photons" in report:  # chapter 14: the photon map is kept while only the view moves
        traced = report["photons"]["maps_traced"]
        check(0 < traced < report["frames"], f"the drags, R and flying kept the photon map: {traced} maps "
              f"traced for {report['frames']} frames")
    if PREVIEW and code == 0:  # the run's PNG: a full frame of the last view
        report = json.load(open(os.path.join(OUT, "window.json")))
        scene = json.load(open(report["scene"]))
        scene["camera"] = report["camera"]
        with open(os.path.join(OUT, "last_view_scene.json"), "w") as f:  # its files: from bin/assets
            json.dump(scene, f)
        subprocess.run([EXE, "--headless", "--width", str(W), "--height", str(H), "--frames", "1", "--scene",
                        "last_view_scene.json", "--output", "last_view.png"], cwd=OUT, check=True,
                       capture_output=True)
        last = read_png_rgb(os.path.join(OUT, "window.png"))
        again = read_png_rgb(os.path.join(OUT, "last_view.png"))
        check(diff(last, again) < 1, f"Esc during a drag writes a full frame ({diff(last, again):.2f} from a headless one)")
finally:
    if chapter.poll() is None:
        chapter.kill()
    xvfb.terminate()  # lets it remove its lock file and socket
    try:
        xvfb.wait(timeout=scaled(5))
    except subprocess.TimeoutExpired:
        xvfb.kill()
    shutil.rmtree(FBDIR, ignore_errors=True)
    print(open(log).read())
sys.exit(1 if failures else 0)
