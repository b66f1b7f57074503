#!/usr/bin/python3
"""How many photons chapter 14's gather reads at each pixel (the
performance page, "Chapter 14: what the photons cost"): from one frame's
photons (14_caustics --photons-ply FILE) and the scene's camera, for the
pixels whose camera ray meets the scene's first quad (the floor), the
photons of the 2x2x2 cells of side 2r nearest the hit (gather.glsl), with
no cap and with each cap given. Prints the total, the mean, the largest
and the sum over 8x4 pixel tiles of each tile's largest count (a GPU runs
a tile's loops side by side, as long as its longest). Occlusion by other
objects, the rays through glass and hash collisions are left out.

    tools/gather_reads.py PLY SCENE RADIUS [--width W] [--height H] [--caps 64,16]
"""
import argparse
import json
import math
import sys

import numpy


def fail(message):
    """Bad input: one line naming the file and the cause, exit 2."""
    print(f"gather_reads.py: {message}", file=sys.stderr)
    sys.exit(2)


def read_ply(path):
    """The photons' positions from --photons-ply's binary PLY: x, y, z and
    power_r, power_g, power_b (floats), red, green, blue (bytes)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.find(b"end_header\n")
    if end < 0:
        fail(f"{path}: not a PLY file (no end_header)")
    header = data[:end].decode("ascii", "replace").split("\n")
    counts = [line.split()[-1] for line in header if line.startswith("element vertex")]
    if not counts or "format binary_little_endian" not in data[:end].decode("ascii", "replace"):
        fail(f"{path}: not a binary little-endian PLY of vertices")
    n = int(counts[0])
    body = data[end + len(b"end_header\n"):]
    vertex = numpy.dtype([("xyz", "<f4", 3), ("power", "<f4", 3), ("colour", "u1", 3)])
    if len(body) < n * vertex.itemsize:
        fail(f"{path}: {n} vertices announced, {len(body) // vertex.itemsize} present")
    return numpy.frombuffer(body[:n * vertex.itemsize], dtype=vertex)["xyz"].astype(numpy.float64)


def floor_hits(scene, width, height):
    """Where each pixel's camera ray (through its centre) meets the first quad:
    points, and the mask of the pixels that do."""
    cam = scene["camera"]
    eye, look = numpy.array(cam["position"], float), numpy.array(cam["look_at"], float)
    forward = (look - eye) / numpy.linalg.norm(look - eye)
    right = numpy.cross(forward, [0.0, 1.0, 0.0])
    right /= numpy.linalg.norm(right)
    up = numpy.cross(right, forward)
    tan = math.tan(math.radians(cam["fov_y_deg"]) / 2)
    ys, xs = numpy.mgrid[0:height, 0:width]
    nx, ny = (xs + 0.5) / width * 2 - 1, (ys + 0.5) / height * 2 - 1
    d = forward + (nx * tan * width / height)[..., None] * right - (ny * tan)[..., None] * up
    quad = next(o for o in scene["objects"] if o["type"] == "quad")
    c, u, v = (numpy.array(quad[k], float) for k in ("center", "u", "v"))
    normal = numpy.cross(u, v)
    with numpy.errstate(divide="ignore", invalid="ignore"):
        t = ((c - eye) @ normal) / (d @ normal)
    p = eye + t[..., None] * d
    # the quad is the parallelogram center +- u +- v (docs/scene-format.md)
    a, b = (p - c) @ u / (u @ u), (p - c) @ v / (v @ v)
    hit = (t > 0) & (abs(a) <= 1) & (abs(b) <= 1)
    return p, hit


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("ply")
    parser.add_argument("scene")
    parser.add_argument("radius", type=float)
    parser.add_argument("--width", type=int, default=1920)
    parser.add_argument("--height", type=int, default=1080)
    parser.add_argument("--caps", default="64,16")
    args = parser.parse_args()
    if args.radius <= 0 or args.width % 8 or args.height % 4:
        fail("the radius must be > 0, the width a multiple of 8, the height of 4")
    caps = [int(c) for c in args.caps.split(",") if c]
    photons = read_ply(args.ply)
    with open(args.scene) as f:
        scene = json.load(f)
    side = 2 * args.radius
    cells, counts = numpy.unique(numpy.floor(photons / side).astype(numpy.int64), axis=0, return_counts=True)
    keys = {tuple(cell): count for cell, count in zip(cells.tolist(), counts.tolist())}
    print(f"{len(photons)} photons in {len(cells)} cells of side {side:.6g}; "
          f"the fullest holds {counts.max()}")
    points, hit = floor_hits(scene, args.width, args.height)
    base = numpy.floor(points[hit] / side - 0.5).astype(numpy.int64)
    per_cell = []  # each of the 8 cells' count, per pixel
    for k in range(8):
        corner = base + numpy.array([k & 1, (k >> 1) & 1, k >> 2])
        per_cell.append(numpy.array([keys.get(tuple(c), 0) for c in corner.tolist()]))
    print(f"{int(hit.sum())} of {args.width * args.height} pixels see the floor")
    for cap in [0] + caps:
        reads = sum(numpy.minimum(c, cap) if cap else c for c in per_cell)
        image = numpy.zeros((args.height, args.width), dtype=numpy.int64)
        image[hit] = reads
        tiles = image.reshape(args.height // 4, 4, args.width // 8, 8).max(axis=(1, 3))
        print(f"{'no cap' if cap == 0 else f'cap {cap}':7s}: {reads.sum():.3e} photons read, mean {reads.mean():.1f}, "
              f"largest {reads.max()}; tiles of 8x4 as long as their longest: {32 * tiles.sum():.3e}")


if __name__ == "__main__":
    try:
        main()
    except OSError as e:
        fail(f"{e.filename}: {e.strerror}")
    except (ValueError, KeyError, StopIteration, TypeError) as e:
        fail(f"{sys.argv[2] if len(sys.argv) > 2 else 'scene'}: not a scene this tool can read ({e!r})")
