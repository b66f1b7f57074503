#!/usr/bin/env python3
"""Chapter 15's sampling compared (issue 48, performance.md): visible
normals against chapter 11's cone (mixed half and half with visible normals,
so that it stays unbiased and free of fireflies: microfacet.glsl's
sampleConeMixture) for the same microfacet model, at equal GPU time, into
OUT/frosted.json and OUT/frosted.md.

    tools/frosted_study.py --bin build/bin --out docs/perf/<device>
                           [--width W] [--height H] [--truth-frames N] [--max-frames M]
    tools/frosted_study.py --out docs/perf/<device> --tables-only   (from its frosted.json)

Two scenes, camera rays only (--caustics off: the photons' noise is
chapter 14's): the default scene (frosted glass and a brushed mirror), and
the same with every glass smooth (the brushed mirror alone rough). The
"converged" picture of each is the chapter's with visible normals after N
frames. Then 1, 2, 4, ... M frames with each sampler: the RMSE (linear,
all pixels) against it, and the GPU time per frame. Standard library
only, so it runs on the GPU machine too.
"""
import json
import os
import tempfile

from study import read_pfm, rmse, run_chapter, run_study

EXE = "15_frosted_glass"
SAMPLERS = ("visible", "cone")


def smooth_glass(scene_path, out_path):
    """The default scene with every transmissive material smooth."""
    with open(scene_path) as f:
        scene = json.load(f)
    for material in scene["materials"].values():
        if material.get("transmission", 0) > 0:
            material["roughness"] = 0
    with open(out_path, "w") as f:
        json.dump(scene, f)


def measure(args):
    size = (args.width, args.height)
    exe = os.path.join(args.bin, EXE)
    data = {"width": size[0], "height": size[1], "truth_frames": args.truth_frames, "cone": "mixture", "runs": []}
    with tempfile.TemporaryDirectory() as tmp:
        mirror = os.path.join(tmp, "mirror_scene.json")
        smooth_glass(os.path.join(args.bin, "assets", "scenes", "frosted.json"), mirror)
        for name, scene in (("frosted glass and a brushed mirror", []), ("the brushed mirror alone",
                                                                         ["--scene", mirror])):
            base = scene + ["--caustics", "off"]
            print(f"{EXE} at {size[0]}x{size[1]}, {name}: converged picture of {args.truth_frames} frames")
            report = run_chapter("frosted_study.py", exe, size, base + ["--frames", str(args.truth_frames)],
                                 os.path.join(tmp, "truth.png"))
            data["device"], data["driver"] = report["device"], report["driver"]
            truth = read_pfm(os.path.join(tmp, "truth.pfm"))
            every = list(range(size[0] * size[1]))
            frames = 1
            while frames <= args.max_frames:
                for sampler in SAMPLERS:
                    png = os.path.join(tmp, f"{sampler}_{frames}.png")
                    report = run_chapter("frosted_study.py", exe, size,
                                         base + ["--frames", str(frames), "--sampling", sampler], png)
                    ms = report["gpu_ms"]["median"]
                    error = rmse(read_pfm(os.path.splitext(png)[0] + ".pfm"), truth, every)
                    data["runs"].append({"scene": name, "sampler": sampler, "frames": frames,
                                         "gpu_ms_per_frame": ms, "seconds": frames * ms / 1000, "rmse": error})
                    print(f"  {sampler:8s} {frames:5d} frames: {ms:.2f} ms/frame, RMSE {error:.5f}")
                frames *= 2
    return data


def tables(data):
    out = [f"**Chapter 15, visible normals against chapter 11's cone** on {data['device']} "
           f"(`tools/frosted_study.py`): {data['width']}x{data['height']}, `--caustics off`; RMSE (linear, "
           f"all pixels) against the picture after {data['truth_frames']} frames with visible normals; "
           + ("the cone mixed half and half with visible normals (`--sampling cone`).\n"
              if data.get("cone") == "mixture" else
              "the cone alone, as `--sampling cone` drew it before it was mixed with visible normals "
              "(until 2026-12-08); its error includes its bias.\n")]
    for scene in dict.fromkeys(r["scene"] for r in data["runs"]):
        runs = [r for r in data["runs"] if r["scene"] == scene]
        by = {(r["sampler"], r["frames"]): r for r in runs}
        out += [f"\n*{scene}*\n", "| frames | visible: ms a frame | visible: RMSE | cone: ms a frame | cone: RMSE |",
                "| --- | --- | --- | --- | --- |"]
        for frames in sorted({r["frames"] for r in runs}):
            v, c = by[("visible", frames)], by[("cone", frames)]
            out.append(f"| {frames} | {v['gpu_ms_per_frame']:.2f} | {v['rmse']:.5f} | "
                       f"{c['gpu_ms_per_frame']:.2f} | {c['rmse']:.5f} |")
        # at equal time: each cone run against the visible run of the nearest time
        ratios = []
        for c in (r for r in runs if r["sampler"] == "cone"):
            v = min((r for r in runs if r["sampler"] == "visible"), key=lambda r: abs(r["seconds"] - c["seconds"]))
            if c["rmse"] > 0:
                ratios.append(v["rmse"] / c["rmse"])
        if ratios:
            out.append(f"\nAt about equal time, visible normals' RMSE over the cone's: "
                       f"{min(ratios):.2f} to {max(ratios):.2f}.")
    return "\n".join(out) + "\n"


def options(p):
    p.set_defaults(width=320, height=180)
    p.add_argument("--truth-frames", type=int, default=1024)
    p.add_argument("--max-frames", type=int, default=64)


if __name__ == "__main__":
    run_study("frosted", __doc__, measure, tables, options)
