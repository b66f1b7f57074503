#!/usr/bin/python3
"""Puts chapter renders side by side into one PNG for the docs.

Reads the PFM files the chapters write beside their PNGs (linear float RGB),
applies RayGlass's one display transform (shared/core/display.h: clamp to [0, 1],
then sRGB) and writes an 8-bit PNG, with a gap between the panels (numpy and
PIL: Debian's python3-numpy and python3-pil).

    tools/montage.py OUT.png A.pfm B.pfm ... [--gap PIXELS] [--scale N] [--stack]

--scale N draws each pixel as an N x N square, so that single pixels (a
staircase at an edge, chapter 04's antialiasing) can be seen. --stack puts
the panels one above the other, so that a page's column shows each at full
width (chapter 12's mip levels).
"""
import sys

import numpy as np
from PIL import Image


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


def main(argv):
    options = {"--gap": 4, "--scale": 1}
    args = list(argv)
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
    Image.fromarray(canvas, "RGB").save(out, optimize=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
