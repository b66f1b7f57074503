#!/usr/bin/env python3
"""The scaling study (issue 11, chapter 03's page, performance.md): chapters
04 and 10 on N random spheres over a floor, for each layout and order, into
OUT/scaling.json, scaling.dat (for tools/plot_scaling.gp) and scaling.md.

    tools/scaling.py --bin build/bin --out docs/perf/<device> [--max N] [--file-max N]
                     [--width W] [--height H] [--frames F] [--repeat R]
    tools/scaling.py --out docs/perf/<device> --tables-only   (from its scaling.json)

N goes 10, 100, ... up to --max (default 10^5). The scene file's random
order (--file-order) is measured up to --file-max (default 10^4): on a
builder that splits the list at its middle (lavapipe) it is slow by design.
Scenes come from tools/make_scene.py (compact from 10^5 on). Standard
library only, so it runs on the GPU machine too.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def run(exe, scene, args, extra):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "r.png")
        cmd = [exe, "--headless", "--width", str(args.width), "--height", str(args.height),
               "--frames", str(args.frames), "--scene", scene, "--output", out] + extra
        start = time.time()
        done = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.time() - start
        if done.returncode != 0:
            sys.exit(f"scaling.py: {' '.join(cmd)} failed:\n{done.stdout}{done.stderr}")
        report = json.load(open(os.path.join(tmp, "r.json")))
    accel = report["acceleration"]
    return {
        "gpu_ms": report["gpu_ms"]["median"],
        "mrays_per_s": report["mrays_per_s"],
        "blas_bytes": accel["blas_bytes"],
        "tlas_bytes": accel["tlas_bytes"],
        "build_ms": accel["blas_build_ms"] + accel["tlas_build_ms"],
        "wall_s": wall,
    }


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--bin")
    p.add_argument("--tables-only", action="store_true")
    p.add_argument("--out", required=True)
    p.add_argument("--max", type=int, default=100000)
    p.add_argument("--file-max", type=int, default=10000)
    p.add_argument("--width", type=int, default=640)
    p.add_argument("--height", type=int, default=360)
    p.add_argument("--frames", type=int, default=5)
    p.add_argument("--repeat", type=int, default=1,
                   help="the median of this many runs, in rounds over every N (a run of over 20 s runs once)")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if args.tables_only:
        saved = json.load(open(os.path.join(args.out, "scaling.json")))
        rows, args.width, args.height = saved["rows"], saved["width"], saved["height"]
        sizes = sorted({r["n"] for r in rows})
    else:
        if not args.bin:
            sys.exit("scaling.py: --bin is needed to measure")
        sizes = [n for n in (10, 100, 1000, 10000, 100000, 1000000) if n <= args.max]
        rows = measure(args, sizes)
        json.dump({"width": args.width, "height": args.height, "rows": rows},
                  open(os.path.join(args.out, "scaling.json"), "w"), indent=1)
    write_tables(args, sizes, rows)


CASES = [("instances", "median"), ("grouped", "median"), ("instances", "file")]


def measure(args, sizes):
    """Each case --repeat times, the repeats in rounds over every N, so that a
    slow minute of a shared machine touches all N alike; the median run."""
    runs = {}
    with tempfile.TemporaryDirectory() as scenes:
        for n in sizes:
            subprocess.run([sys.executable, os.path.join(HERE, "make_scene.py"), "floor", str(n),
                            os.path.join(scenes, f"floor_{n}.json")]
                           + (["--compact"] if n >= 100000 else []), check=True)
        for round_ in range(args.repeat):
            for n in sizes:
                for chapter in ("04_raygen_miss", "10_refraction"):
                    for layout, order in CASES:
                        key = (n, chapter[:2], layout, order)
                        if order == "file" and n > args.file_max:
                            continue
                        if round_ > 0 and runs[key][0]["wall_s"] >= 20:
                            continue  # slow by design: once is enough
                        extra = ["--layout", layout] + (["--file-order"] if order == "file" else [])
                        r = run(os.path.join(args.bin, chapter), os.path.join(scenes, f"floor_{n}.json"), args, extra)
                        runs.setdefault(key, []).append(r)
                        print(f"{n:>8} {chapter} {layout:9} {order:6} {r['gpu_ms']:10.3f} ms "
                              f"build {r['build_ms']:7.2f} ms", flush=True)
    rows = []
    for (n, chapter, layout, order), done in runs.items():
        r = dict(sorted(done, key=lambda x: x["gpu_ms"])[len(done) // 2])
        r.update(n=n, chapter=chapter, layout=layout, order=order, runs=len(done))
        rows.append(r)
    return rows


def write_tables(args, sizes, rows):
    def find(n, chapter, layout, order, key):
        for r in rows:
            if (r["n"], r["chapter"], r["layout"], r["order"]) == (n, chapter, layout, order):
                return r[key]
        return None

    def structures_mb(n):  # chapter 04, median splits: instances, grouped
        return [(find(n, "04", l, "median", "blas_bytes") + find(n, "04", l, "median", "tlas_bytes")) / 1e6
                for l in ("instances", "grouped")]

    def build_ms(n):
        return [find(n, "04", l, "median", "build_ms") for l in ("instances", "grouped")]

    with open(os.path.join(args.out, "scaling.dat"), "w") as f:
        f.write("# N  ch04: instances grouped file-order  ch10: instances grouped file-order"
                "  AS MB: instances grouped  build ms: instances grouped (ch04, median splits)\n")
        for n in sizes:
            values = [find(n, c, l, o, "gpu_ms") for c in ("04", "10") for l, o in CASES]
            values += structures_mb(n) + build_ms(n)
            f.write(f"{n} " + " ".join("?" if v is None else f"{v:.6g}" for v in values) + "\n")

    def cell(v):
        return "-" if v is None else f"{v:,.0f}" if v >= 1000 else f"{v:.3g}"

    with open(os.path.join(args.out, "scaling.md"), "w") as f:
        f.write(f"#### Scaling: spheres on a floor ({args.width}x{args.height}, median GPU ms per frame)\n\n")
        f.write("| spheres | 04 instances | 04 grouped | 04 file order | 10 instances | 10 grouped | 10 file order "
                "| structures MB, instances / grouped | build ms, instances / grouped |\n")
        f.write("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n")
        for n in sizes:
            ms = [cell(find(n, c, l, o, "gpu_ms")) for c in ("04", "10") for l, o in CASES]
            mb, build = structures_mb(n), build_ms(n)
            f.write(f"| {n:,} | " + " | ".join(ms) + f" | {cell(mb[0])} / {cell(mb[1])} | "
                    f"{cell(build[0])} / {cell(build[1])} |\n")
        base = find(sizes[0], "04", "grouped", "median", "gpu_ms")
        f.write(f"\nChapter 04 grouped, frame time against {sizes[0]:,} spheres: "
                + ", ".join(f"{n:,}: {find(n, '04', 'grouped', 'median', 'gpu_ms') / base:.2f}x" for n in sizes[1:])
                + ".\n")
        f.write("\nInstances and grouped in median-split order; file order: instances in the scene file's random order. "
                "Structures: compacted BLASes plus the TLAS. Build: GPU time of the BLAS and TLAS builds.\n")
    print("wrote", os.path.join(args.out, "scaling.md"))


if __name__ == "__main__":
    main()
