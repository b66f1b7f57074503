#!/usr/bin/python3
"""Puts chapter renders side by side into one PNG for the docs.

Reads the PFM files the chapters write beside their PNGs (linear float RGB),
applies RayGlass's one display transform (shared/core/display.h: clamp to [0, 1],
then sRGB) and writes an 8-bit PNG, with a gap between the panels (numpy and
PIL: Debian's python3-numpy and python3-pil).

    tools/montage.py OUT.png A.pfm B.pfm ... [--gap PIXELS] [--scale N] [--stack]
                     [--label X,Y,TX,TY,TEXT ...]

--scale N draws each pixel as an N x N square, so that single pixels (a
staircase at an edge, chapter 04's antialiasing) can be seen. --stack puts
the panels one above the other, so that a page's column shows each at full
width (chapter 12's mip levels). --label draws an arrow from the text,
written at TX,TY (its left end, the middle of its height), to the point
X,Y of the finished picture (pixels, top left 0,0): what a page names.
"""
import sys

import numpy as np
from PIL import Image, ImageDraw, ImageFont


def fail(message):
    print(f"montage.py: {message}", file=sys.stderr)
    sys.exit(2)


def read_pfm(path):
    """A colour PFM file as linear RGB floats, top row first (PFM stores the bottom row first)."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        fail(f"{path}: {e.strerror}")
    parts = data.split(b"\n", 3)
    try:
        if len(parts) < 4 or parts[0] != b"PF":
            raise ValueError
        width, height = map(int, parts[1].split())
        dtype = "<f4" if float(parts[2]) < 0 else ">f4"  # a negative scale: little endian
        floats = np.frombuffer(parts[3], dtype=dtype, count=width * height * 3)
    except ValueError:
        fail(f"{path}: not a colour PFM file, or a truncated one")
    return floats.reshape(height, width, 3)[::-1]


def to_display8(linear):
    """RayGlass's one display transform (shared/core/display.h): NaN is
    black; clamp to [0, 1], then the sRGB transfer function, rounded."""
    c = np.clip(np.nan_to_num(linear.astype(np.float64), nan=0.0), 0.0, 1.0)
    s = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
    return np.floor(s * 255.0 + 0.5).astype(np.uint8)


def parse_label(text):
    """X,Y,TX,TY,TEXT: the point, where the text starts, the text."""
    parts = text.split(",", 4)
    try:
        x, y, tx, ty = (int(v) for v in parts[:4])
        return (x, y), (tx, ty), parts[4]
    except (ValueError, IndexError):
        fail(f"--label {text!r}: give X,Y,TX,TY,TEXT (whole pixels, then the text)")


def draw_labels(image, labels):
    """Each label: its text in white on a dark box, and an arrow from the
    box to the point, dark with a white edge so it shows on any picture."""
    draw = ImageDraw.Draw(image)
    size = max(12, image.width // 53)  # 18 px on a 960-pixel-wide picture
    try:  # Debian's fonts-dejavu-core; PIL's own bitmap font without it
        font = ImageFont.truetype("DejaVuSans.ttf", size)
    except OSError:
        font = ImageFont.load_default()
    for (x, y), (tx, ty), text in labels:
        left, top, right, bottom = draw.textbbox((tx, ty), text, font=font, anchor="lm")
        pad = size // 4
        box = (left - pad, top - pad, right + pad, bottom + pad)
        # the arrow leaves the box's side nearest the point
        sx = box[2] if x > box[2] else box[0] if x < box[0] else (box[0] + box[2]) / 2
        sy = box[3] if y > box[3] else box[1] if y < box[1] else (box[1] + box[3]) / 2
        length = max(1e-6, ((x - sx) ** 2 + (y - sy) ** 2) ** 0.5)
        ux, uy = (x - sx) / length, (y - sy) / length
        head = [(x, y), (x - size * 0.6 * ux + size * 0.3 * uy, y - size * 0.6 * uy - size * 0.3 * ux),
                (x - size * 0.6 * ux - size * 0.3 * uy, y - size * 0.6 * uy + size * 0.3 * ux)]
        for colour, width in (("white", 5), ("black", 2)):
            draw.line([(sx, sy), (x - size * 0.5 * ux, y - size * 0.5 * uy)], fill=colour, width=width)
        draw.polygon(head, fill="black", outline="white")
        draw.rectangle(box, fill=(20, 20, 20), outline="white")
        draw.text((tx, ty), text, font=font, fill="white", anchor="lm")


def main(argv):
    options = {"--gap": 4, "--scale": 1}
    args = list(argv)
    labels = []
    while "--label" in args:
        i = args.index("--label")
        if i + 1 >= len(args):
            fail("--label needs X,Y,TX,TY,TEXT")
        labels.append(parse_label(args[i + 1]))
        del args[i:i + 2]
    for name in options:
        if name in args:
            i = args.index(name)
            try:
                options[name] = int(args[i + 1])
            except (IndexError, ValueError):
                options[name] = -1
            if options[name] < (0 if name == "--gap" else 1):
                print(f"montage.py: {name} needs a whole number (at least {0 if name == '--gap' else 1})",
                      file=sys.stderr)
                return 2
            del args[i:i + 2]
    gap, scale = options["--gap"], options["--scale"]
    stack = "--stack" in args
    if stack:
        args.remove("--stack")
    if len(args) < 2:
        print("usage: tools/montage.py OUT.png A.pfm B.pfm ... [--gap PIXELS] [--scale N] [--stack]",
              file=sys.stderr)
        return 2
    out, inputs = args[0], [read_pfm(p) for p in args[1:]]
    if scale > 1:  # each pixel an N x N square
        inputs = [image.repeat(scale, axis=0).repeat(scale, axis=1) for image in inputs]
    if stack:  # one above the other: transpose, lay out side by side, transpose back
        inputs = [image.transpose(1, 0, 2) for image in inputs]
    height = max(image.shape[0] for image in inputs)
    width = sum(image.shape[1] for image in inputs) + gap * (len(inputs) - 1)
    canvas = np.full((height, width, 3), 255, dtype=np.uint8)  # white gaps
    x0 = 0
    for image in inputs:
        h, w = image.shape[:2]
        canvas[:h, x0:x0 + w] = to_display8(image)
        x0 += w + gap
    if stack:
        canvas = np.ascontiguousarray(canvas.transpose(1, 0, 2))
    picture = Image.fromarray(canvas, "RGB")
    draw_labels(picture, labels)
    picture.save(out, optimize=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
