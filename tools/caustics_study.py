#!/usr/bin/env python3
"""Chapter 14's speed against error (issue 47, performance.md): the error of
the progressive photon map against the frames averaged and the GPU time
they took, with the shrinking radius (Knaus and Zwicker's alpha = 2/3) and
with the first radius kept (alpha = 1), into OUT/caustics.json and
OUT/caustics.md.

    tools/caustics_study.py --bin build/bin --out docs/perf/<device>
                            [--width W] [--height H] [--truth-frames N] [--max-frames M]
                            [--photons P] [--gather-cap C]
    tools/caustics_study.py --out docs/perf/<device> --tables-only   (from its caustics.json)

On the default scene (caustics.json). The "converged" picture is the
chapter's own after N frames of 4 P photons each with the shrinking radius,
drawn independently of the runs' photons (--photon-seed 1):
a consistent estimate, so its bias and noise are the smallest of all the
runs. Its own noise is measured too, against a second such picture
(--photon-seed 2): their RMSE over sqrt(2) is one picture's noise, which
an independent truth adds to every run's RMSE (in quadrature); the tables
give each shrinking-radius RMSE with it taken out as well (the CPU reference is not used: its dense photon grid grows sparse at
the small radii of late frames, page 14). Then 1, 2, 4, ... M frames of P
photons, each mode: the RMSE (linear) over the caustic pixels (where the
converged picture differs from --caustics off by more than 1/255 in
display) and over the whole image, and the GPU time per frame over the run.
With --gather-cap C, a third mode: the shrinking radius with the gather
reading at most C photons a cell (chapter 14's performance trick), whose
frames cost less and carry more noise; the converged picture reads them all.
Standard library only, so it runs on the GPU machine too.
"""
import math
import os
import tempfile

from study import read_pfm, rmse, run_chapter, run_study, srgb

EXE = "14_caustics"
MODES = (("shrinking", ["--alpha", "0.6667"]), ("fixed", ["--alpha", "1"]))


def run(exe, size, extra, png):
    return run_chapter("caustics_study.py", exe, size, extra, png)


def modes(cap):
    """(name, options) of each mode; a cap adds the capped shrinking mode."""
    shrinking = dict(MODES)["shrinking"]
    return MODES + ((f"cap {cap}", shrinking + ["--gather-cap", str(cap)]),) if cap else MODES


def measure(args):
    size = (args.width, args.height)
    exe = os.path.join(args.bin, EXE)
    data = {"width": size[0], "height": size[1], "truth_frames": args.truth_frames, "photons": args.photons,
            "gather_cap": args.gather_cap, "runs": []}
    with tempfile.TemporaryDirectory() as tmp:
        print(f"{EXE} at {size[0]}x{size[1]}: converged picture of {args.truth_frames} frames")
        # its own photons (--photon-seed), independent of the runs' below
        truth_report = run(exe, size, ["--frames", str(args.truth_frames), "--photons", str(4 * args.photons),
                                       "--photon-seed", "1"], os.path.join(tmp, "truth.png"))
        data["device"], data["driver"] = truth_report["device"], truth_report["driver"]
        truth = read_pfm(os.path.join(tmp, "truth.pfm"))
        run(exe, size, ["--frames", str(args.truth_frames), "--photons", str(4 * args.photons),
                        "--photon-seed", "2"], os.path.join(tmp, "truth2.png"))
        truth2 = read_pfm(os.path.join(tmp, "truth2.pfm"))
        run(exe, size, ["--frames", "1", "--caustics", "off"], os.path.join(tmp, "off.png"))
        off = read_pfm(os.path.join(tmp, "off.pfm"))
        n = truth[2]
        caustic = [i for i in range(size[0] * size[1])
                   if max(abs(srgb(truth[3][n * i + c]) - srgb(off[3][n * i + c])) for c in range(3)) * 255 > 1]
        data["caustic_pixels"] = len(caustic)
        data["truth_noise"] = rmse(truth, truth2, caustic) / math.sqrt(2)
        print(f"  the converged picture's own noise over the caustic: {data['truth_noise']:.5f}")
        # the scale a relative error is read against (issue 47: "1 % RMSE")
        data["caustic_mean"] = (sum(truth[3][n * i + c] for i in caustic for c in range(3)) /
                                max(1, 3 * len(caustic)))
        frames = 1
        while frames <= args.max_frames:
            for mode, extra in modes(args.gather_cap):
                png = os.path.join(tmp, f"{mode}_{frames}.png")
                report = run(exe, size, ["--frames", str(frames), "--photons", str(args.photons)] + extra, png)
                image = read_pfm(os.path.splitext(png)[0] + ".pfm")
                ms = report["gpu_ms"]["median"]
                data["runs"].append({"mode": mode, "frames": frames, "gpu_ms_per_frame": ms,
                                     "seconds": frames * ms / 1000,
                                     "rmse_caustic": rmse(image, truth, caustic),
                                     "rmse_all": rmse(image, truth, list(range(size[0] * size[1])))})
                print(f"  {mode:9s} {frames:5d} frames: {ms:.1f} ms/frame, RMSE caustic "
                      f"{data['runs'][-1]['rmse_caustic']:.4f}")
            frames *= 2
    return data


def tables(data):
    cap = data.get("gather_cap", 0)
    out = [f"**Chapter 14, speed against error** on {data['device']} (`tools/caustics_study.py`): "
           f"the default scene at {data['width']}x{data['height']}, {data['photons']} photons a frame; "
           f"RMSE (linear) against the chapter's picture after {data['truth_frames']} frames of "
           f"{4 * data['photons']} photons with the shrinking radius, over the {data['caustic_pixels']} "
           "caustic pixels (and over all pixels)" +
           (f"; their mean radiance is {data['caustic_mean']:.4f}, so 1 % of it is "
            f"{data['caustic_mean'] / 100:.4f}" if "caustic_mean" in data else "") +
           (f"; the converged picture's own noise there is {data['truth_noise']:.4f} (against a second "
            "one drawn with other photons), taken out of the shrinking radius's RMSE in quadrature "
            "in the column \"less the truth's noise\"" if "truth_noise" in data else "") + ".\n"]
    noise = data.get("truth_noise")
    head = "| frames | seconds (shrinking) | RMSE, shrinking radius |"
    if noise is not None:
        head += " less the truth's noise |"
    head += " RMSE, fixed radius |"
    if cap:
        head += f" seconds (cap {cap}) | RMSE, shrinking, cap {cap} |"
    out += [head + " all pixels, shrinking | all pixels, fixed |",
            "| --- " * (head.count("|") + 1) + "|"]
    by = {(r["mode"], r["frames"]): r for r in data["runs"]}
    for frames in sorted({r["frames"] for r in data["runs"]}):
        s, f = by[("shrinking", frames)], by[("fixed", frames)]
        row = f"| {frames} | {s['seconds']:.2f} | {s['rmse_caustic']:.4f} |"
        if noise is not None:
            row += f" {math.sqrt(max(0.0, s['rmse_caustic'] ** 2 - noise ** 2)):.4f} |"
        row += f" {f['rmse_caustic']:.4f} |"
        if cap:
            c = by[(f"cap {cap}", frames)]
            row += f" {c['seconds']:.2f} | {c['rmse_caustic']:.4f} |"
        out.append(row + f" {s['rmse_all']:.4f} | {f['rmse_all']:.4f} |")
    return "\n".join(out) + "\n"


def options(p):
    p.set_defaults(width=320, height=180)
    p.add_argument("--truth-frames", type=int, default=512)
    p.add_argument("--max-frames", type=int, default=256)
    p.add_argument("--photons", type=int, default=100000)
    p.add_argument("--gather-cap", type=int, default=0)


if __name__ == "__main__":
    run_study("caustics", __doc__, measure, tables, options)
