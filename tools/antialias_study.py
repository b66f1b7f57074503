#!/usr/bin/env python3
"""Chapter 04's antialiasing measured (issue 28, chapter 04's page,
performance.md): the error at silhouettes against the number of frames
averaged, into OUT/antialias.json and OUT/antialias.md.

    tools/antialias_study.py --bin build/bin --out docs/perf/<device>
                             [--width W] [--height H] [--reference-frames N] [--max-frames M]
    tools/antialias_study.py --out docs/perf/<device> --tables-only   (from its antialias.json)

For each chapter (04 normals, 06 diffuse with shadows, 10 glass), on the
default scene: the CPU reference of N antialiased frames (--reference
--antialias on --frames N) is the pixel's mean over N points of its
sequence, the "converged" picture; the edge pixels are where it differs
from the one ray through the centre by more than 1/255 in display (the
silhouettes, shadow edges and what glass shows of them). Then 1, 2, 4, ...
M frames on the GPU against it: RMSE over those pixels and over the whole
image; and the GPU time per frame, with and without antialiasing, over as
many frames. Standard library only, so it runs on the
GPU machine too.
"""
import math
import os
import tempfile

from study import read_pfm, rmse, run_chapter, run_study, srgb

CHAPTERS = ("04_raygen_miss", "06_diffuse", "10_refraction")


def run(exe, size, extra, png):
    return run_chapter("antialias_study.py", exe, size, extra, png)


def measure(args):
    size = (args.width, args.height)
    data = {"width": size[0], "height": size[1], "reference_frames": args.reference_frames, "chapters": []}
    with tempfile.TemporaryDirectory() as tmp:
        for name in CHAPTERS:
            exe = os.path.join(args.bin, name)
            print(f"{name} at {size[0]}x{size[1]}: reference of {args.reference_frames} frames")
            ref = run(exe, size, ["--reference", "--antialias", "on", "--frames", str(args.reference_frames)],
                      os.path.join(tmp, "ref.png"))
            data["device"], data["driver"] = ref["device"], ref["driver"]
            centre = run(exe, size, ["--reference", "--frames", "1"], os.path.join(tmp, "centre.png"))
            converged = read_pfm(os.path.join(tmp, "ref_reference.pfm"))
            one_ray = read_pfm(os.path.join(tmp, "centre_reference.pfm"))
            n = converged[2]
            every = range(size[0] * size[1])
            edges = [i for i in every if max(abs(srgb(converged[3][n * i + c]) - srgb(one_ray[3][n * i + c]))
                                             for c in range(3)) > 1 / 255]
            gpu_centre = read_pfm(os.path.join(tmp, "centre.pfm"))
            timed = run(exe, size, ["--frames", str(args.max_frames)], os.path.join(tmp, "timed.png"))  # as many frames
            row = {"chapter": name, "edge_pixels": len(edges), "pixels": len(every),
                   "gpu_vs_reference": ref["error"]["frac_over_1_255"],
                   "reference_cpu_ms": ref["error"]["reference_cpu_ms"],
                   "centre": {"edge_rmse": rmse(gpu_centre, converged, edges),
                              "rmse": rmse(gpu_centre, converged, every),
                              "gpu_ms": timed["gpu_ms"]["median"]},
                   "frames": []}
            frames = 1
            while frames <= args.max_frames:
                r = run(exe, size, ["--antialias", "on", "--frames", str(frames)], os.path.join(tmp, f"f{frames}.png"))
                image = read_pfm(os.path.join(tmp, f"f{frames}.pfm"))
                row["frames"].append({"frames": frames, "edge_rmse": rmse(image, converged, edges),
                                      "rmse": rmse(image, converged, every), "gpu_ms": r["gpu_ms"]["median"]})
                print(f"  {frames} frames: edge RMSE {row['frames'][-1]['edge_rmse']:.2e}")
                frames *= 2
            data["chapters"].append(row)
    return data


def slope(rows):
    """Log-log slope of the edge RMSE against frames, from 4 frames on."""
    pts = [(math.log(r["frames"]), math.log(r["edge_rmse"])) for r in rows if r["frames"] >= 4 and r["edge_rmse"] > 0]
    if len(pts) < 2:
        return 0.0
    n, sx, sy = len(pts), sum(p[0] for p in pts), sum(p[1] for p in pts)
    sxx, sxy = sum(p[0] ** 2 for p in pts), sum(p[0] * p[1] for p in pts)
    return (n * sxy - sx * sy) / (n * sxx - sx * sx)


def tables(data):
    counts = [r["frames"] for r in data["chapters"][0]["frames"]]
    lines = [f"**Antialiasing** (chapter 04's `--antialias`, default scene, {data['width']}x{data['height']}): "
             f"RMSE at the edge pixels against the CPU reference's mean over {data['reference_frames']} points "
             "of each pixel; edge pixels: where that mean differs from the ray through the centre by more than "
             "1/255. `centre` is one ray through each pixel's centre, as without `--antialias`.", "",
             "| chapter | edge pixels | centre | " + " | ".join(f"{n}" for n in counts) + " | slope (4 up) | ms a frame: centre, antialiased |",
             "| --- | --- | --- | " + " | ".join("---" for _ in counts) + " | --- | --- |"]
    for c in data["chapters"]:
        share = 100 * c["edge_pixels"] / c["pixels"]
        ms = c["frames"][-1]["gpu_ms"]
        lines.append(f"| {c['chapter']} | {share:.1f} % | {c['centre']['edge_rmse']:.2e} | " +
                     " | ".join(f"{r['edge_rmse']:.2e}" for r in c["frames"]) +
                     f" | {slope(c['frames']):.2f} | {c['centre']['gpu_ms']:.3f}, {ms:.3f} |")
    worst = max(c["gpu_vs_reference"] for c in data["chapters"])
    lines += ["", f"The GPU's {data['reference_frames']} frames match that reference on all but "
              f"{100 * worst:.3f} % of pixels (by more than 1/255). One jittered frame is worse than the "
              "centre (one point anywhere in the pixel against the best single point); two frames already beat "
              "it, and the error keeps falling as frames add up. Slope -1 would be the error of a half-plane "
              "edge sampled by a well spread point set; -0.5 that of independent random points. The last "
              "column: the median GPU time of a frame over as many frames as the longest run, without "
              "antialiasing and with it (the point's hashing and the running mean's image load).", ""]
    return "\n".join(lines)


def main():
    def options(p):
        p.add_argument("--reference-frames", type=int, default=256)
        p.add_argument("--max-frames", type=int, default=64)

    def check(args):
        if args.reference_frames < 4 * args.max_frames or args.max_frames < 1:
            return "--reference-frames must be at least 4 x --max-frames, --max-frames at least 1"
        return ""

    run_study("antialias", __doc__, measure, tables, options, check)


if __name__ == "__main__":
    main()
