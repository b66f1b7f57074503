#!/usr/bin/env python3
"""Chapter 13's measurements (issue 26, chapter 13's page, performance.md):
its frame time against chapter 10's rule on the same scenes, what
dispersion costs, and how fast the prism's spectrum converges over
accumulated frames, into OUT/real_glass.json and OUT/real_glass.md.

    tools/real_glass_study.py --bin build/bin --out docs/perf/<device>
                              [--width W] [--height H] [--frames F] [--repeat R]
                              [--study-width W] [--study-height H] [--reference-frames N]
    tools/real_glass_study.py --out docs/perf/<device> --tables-only   (from its real_glass.json)

GPU times are the median over frames, the fastest of --repeat runs; each
run of chapter 13 averages its frames (that is its cost per accumulated
frame). The convergence study compares the prism after 1, 2, 4, ...
frames against the CPU reference of --reference-frames frames: the
reference integrates over the wavelengths the GPU drew, so the first
frames' wavelengths are a part of its, and the error it shows is the
error of stopping early. Standard library only, so it runs on the GPU
machine too.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

from study import read_pfm, run_study, srgb


def run(exe, scene, size, frames, extra, out=None, reference=False):
    """One headless run of `frames` frames at `size`; its report."""
    with tempfile.TemporaryDirectory() as tmp:
        png = out or os.path.join(tmp, "r.png")
        cmd = [exe, "--headless", "--width", str(size[0]), "--height", str(size[1]), "--frames", str(frames),
               "--scene", scene, "--output", png] + extra + (["--reference"] if reference else [])
        done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if done.returncode != 0:
            sys.exit(f"real_glass_study.py: {' '.join(cmd)} failed:\n{done.stdout}")
        with open(os.path.splitext(png)[0] + ".json") as f:
            return json.load(f)


def fastest(args, exe, scene, extra):
    best = None
    for _ in range(args.repeat):
        r = run(exe, scene, (args.width, args.height), args.frames, extra)
        if best is None or r["gpu_ms"]["median"] < best["gpu_ms"]["median"]:
            best = r
    return best


def error(test, reference):
    """RMSE of the linear values, and the share of pixels off by more than 1/255 in display."""
    w, h, n, a = read_pfm(test)
    _, _, _, b = read_pfm(reference)
    squares, off = 0.0, 0
    for i in range(w * h):
        worst = 0.0
        for c in range(3):
            squares += (a[n * i + c] - b[n * i + c]) ** 2
            worst = max(worst, abs(srgb(a[n * i + c]) - srgb(b[n * i + c])))
        off += worst > 1 / 255 + 1e-12
    return math.sqrt(squares / (3 * w * h)), off / (w * h)


def dispersive_copy(scene, material, out):
    """The scene with one material made of N-BK7 by name (its dispersion)."""
    with open(scene) as f:
        data = json.load(f)
    m = data["materials"][material]
    m.pop("ior", None)
    m["dispersion"] = "bk7"
    with open(out, "w") as f:
        json.dump(data, f)
    return out


def measure(args, tmp):
    ch10, ch12, ch13 = (os.path.join(args.bin, n) for n in ("10_refraction", "12_triangle_meshes", "13_real_glass"))
    scenes = os.path.join(args.bin, "assets", "scenes")
    data = {"width": args.width, "height": args.height, "frames": args.frames, "repeat": args.repeat}
    print(f"1/2 frame times at {args.width}x{args.height}")
    glass_bk7 = dispersive_copy(os.path.join(scenes, "glass_sphere.json"), "glass", os.path.join(tmp, "bk7.json"))
    rule = ["--depth", "8", "--fresnel", "exact"]  # chapter 10's rule, as deep as chapter 13, its Fresnel
    sphere = ["--depth", "6", "--fresnel", "exact"]  # chapter 10's depth
    rows = [  # (label, scene, chapter 10's rule: exe and options, chapter 13's options)
        ("`glass_sphere.json`", os.path.join(scenes, "glass_sphere.json"), ch10, sphere, sphere),
        ("`glass_sphere.json`, its glass N-BK7 (dispersion)", glass_bk7, ch10, sphere, sphere),
        ("`real_glass.json` (meshes, nested)", os.path.join(scenes, "real_glass.json"), ch12, rule, []),
        ("`prism.json` (meshes, dispersion)", os.path.join(scenes, "prism.json"), ch12, rule, []),
        ("`prism.json`, one wavelength (`--wavelength 587.6`)", os.path.join(scenes, "prism.json"), ch12, rule,
         ["--wavelength", "587.6"]),
    ]
    data["speed"] = []
    for label, scene, exe, before, after in rows:
        a = fastest(args, exe, scene, before)
        b = fastest(args, ch13, scene, after)
        data["device"], data["driver"] = b["device"], b["driver"]
        data["speed"].append({"scene": label, "rule": os.path.basename(exe), "rule_ms": a["gpu_ms"]["median"],
                              "ms": b["gpu_ms"]["median"], "rule_rays": a["rays_per_frame"],
                              "rays": b["rays_per_frame"]})
        print(f"  {label}: {a['gpu_ms']['median']:.3f} ms ({os.path.basename(exe)}), {b['gpu_ms']['median']:.3f} ms")
    size = (args.study_width, args.study_height)
    print(f"2/2 the prism's convergence at {size[0]}x{size[1]}, against {args.reference_frames} frames")
    prism = os.path.join(scenes, "prism.json")
    ref = run(ch13, prism, size, args.reference_frames, [], os.path.join(tmp, "ref.png"), reference=True)
    reference = os.path.join(tmp, "ref_reference.pfm")
    data["convergence"] = {"width": size[0], "height": size[1], "reference_frames": args.reference_frames,
                           "reference_cpu_ms": ref["error"]["reference_cpu_ms"],
                           "gpu_vs_reference": ref["error"]["frac_over_1_255"], "rows": []}
    frames = 1
    while frames <= args.reference_frames // 16:
        r = run(ch13, prism, size, frames, [], os.path.join(tmp, f"p{frames}.png"))
        rmse, off = error(os.path.join(tmp, f"p{frames}.pfm"), reference)
        data["convergence"]["rows"].append({"frames": frames, "rmse": rmse, "frac_over_1_255": off,
                                            "gpu_ms": r["gpu_ms"]["median"]})
        print(f"  {frames} frames: RMSE {rmse:.2e}, {100 * off:.2f} % of pixels off")
        frames *= 2
    return data


def slope(rows):
    """Log-log slope of RMSE against frames, fitted from 4 frames on."""
    pts = [(math.log(r["frames"]), math.log(r["rmse"])) for r in rows if r["frames"] >= 4 and r["rmse"] > 0]
    n = len(pts)
    if n < 2:
        return 0.0
    sx, sy = sum(p[0] for p in pts), sum(p[1] for p in pts)
    sxx, sxy = sum(p[0] ** 2 for p in pts), sum(p[0] * p[1] for p in pts)
    return (n * sxy - sx * sy) / (n * sxx - sx * sx)


def tables(data):
    size = f"{data['width']}x{data['height']}, {data['frames']} frames, fastest of {data['repeat']}"
    lines = [f"**Chapter 13 against chapter 10's rule** ({size}; exact Fresnel and the same depth for both: 6 "
             "on `glass_sphere.json`, 8 on the meshes, chapter 10's rule from chapter 12 there; chapter 13's "
             "frames accumulate, so its time is per accumulated frame):", "",
             "| scene | chapter 10's rule | ms | chapter 13 ms | ratio | rays a frame (13) |",
             "| --- | --- | --- | --- | --- | --- |"]
    for r in data["speed"]:
        lines.append(f"| {r['scene']} | {r['rule']} | {r['rule_ms']:.3f} | {r['ms']:.3f} | "
                     f"{r['ms'] / r['rule_ms']:.2f} | {r['rays']} |")
    c = data["convergence"]
    lines += ["", f"**Chapter 13, the prism's spectrum against accumulated frames** (`prism.json`, "
              f"{c['width']}x{c['height']}; against the CPU reference of {c['reference_frames']} frames, which "
              f"took {c['reference_cpu_ms'] / 1000:.1f} s and which the GPU's {c['reference_frames']} frames match "
              f"to {100 * c['gpu_vs_reference']:.4f} % of pixels):", "",
              "| frames | RMSE | pixels off > 1/255 |", "| --- | --- | --- |"]
    for r in c["rows"]:
        lines.append(f"| {r['frames']} | {r['rmse']:.2e} | {100 * r['frac_over_1_255']:.2f} % |")
    lines += ["", f"Log-log slope of RMSE against frames from 4 frames on: {slope(c['rows']):.2f} "
              "(-0.5 would be independent random wavelengths).", ""]
    return "\n".join(lines)


def main():
    def options(p):
        p.add_argument("--study-width", type=int, default=160)
        p.add_argument("--study-height", type=int, default=90)
        p.add_argument("--reference-frames", type=int, default=4096)

    def check(args):
        if min(args.study_width, args.study_height) < 1 or args.reference_frames < 16:
            return "--study-width and --study-height must be at least 1, --reference-frames 16"
        return ""

    def measured(args):
        with tempfile.TemporaryDirectory() as tmp:
            return measure(args, tmp)

    run_study("real_glass", __doc__, measured, tables, options, check)


if __name__ == "__main__":
    main()
