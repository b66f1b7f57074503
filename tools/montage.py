#!/usr/bin/env python3
"""Puts chapter renders side by side into one PNG for the docs.

Reads the PFM files the chapters write beside their PNGs (linear float RGB),
applies RayGlass's one display transform (shared/core/display.h: clamp to [0, 1],
then sRGB) and writes an 8-bit PNG, with a gap between the panels. Python's
standard library only.

    tools/montage.py OUT.png A.pfm B.pfm ... [--gap PIXELS] [--scale N]

--scale N draws each pixel as an N x N square, so that single pixels (a
staircase at an edge, chapter 04's antialiasing) can be seen.
"""
import math
import struct
import sys
import zlib


def read_pfm(path):
    with open(path, "rb") as f:
        data = f.read()
    parts = data.split(b"\n", 3)
    if len(parts) < 4 or parts[0] != b"PF":
        raise SystemExit(f"montage.py: {path}: not a colour PFM file")
    width, height = map(int, parts[1].split())
    scale = float(parts[2])
    fmt = "<" if scale < 0 else ">"
    floats = struct.unpack(f"{fmt}{width * height * 3}f", parts[3][: width * height * 12])
    rows = [floats[(height - 1 - y) * width * 3:(height - y) * width * 3] for y in range(height)]  # PFM is bottom-up
    return width, height, rows


def to_display8(linear):
    if linear != linear:  # NaN: black, as shared/core/display.h
        return 0
    c = min(1.0, max(0.0, linear))
    s = 12.92 * c if c <= 0.0031308 else 1.055 * math.pow(c, 1 / 2.4) - 0.055
    return int(math.floor(s * 255.0 + 0.5))


def write_png(path, width, height, rows):
    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


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
    if len(args) < 2:
        print("usage: tools/montage.py OUT.png A.pfm B.pfm ... [--gap PIXELS] [--scale N]", file=sys.stderr)
        return 2
    out, inputs = args[0], [read_pfm(p) for p in args[1:]]
    if scale > 1:  # each pixel an N x N square
        inputs = [(w * scale, h * scale, [tuple(v for x in range(w) for v in row[3 * x:3 * x + 3] * scale)
                                          for row in image for _ in range(scale)]) for w, h, image in inputs]
    height = max(h for _, h, _ in inputs)
    width = sum(w for w, _, _ in inputs) + gap * (len(inputs) - 1)
    rows = [[255] * (3 * width) for _ in range(height)]  # white gaps
    x0 = 0
    for w, h, image in inputs:
        for y in range(h):
            rows[y][3 * x0:3 * (x0 + w)] = [to_display8(v) for v in image[y]]
        x0 += w + gap
    write_png(out, width, height, rows)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
