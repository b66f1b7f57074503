#!/usr/bin/env python3
"""Writes big scenes for the scaling study (chapter 03's page, performance.md).

    tools/make_scene.py floor N OUT.json [--seed S]   N random spheres (radius 0.2-0.5,
                                                       mixed materials) on a floor
    tools/make_scene.py ball N OUT.json [--seed S]    N random spheres in a dense ball,
                                                       in random order (a public sample's test)
    --compact   the spheres of each material as one "spheres" object with a flat
                array x, y, z, r, ... (docs/scene-format.md): for 10^5 spheres and more
    --moving K  the first K spheres move (chapter 03 refits the TLAS for them every
                frame: what moving costs); not with --compact, whose spheres are static

The spheres are written in random order, as a scene file written by hand or
by another tool would be: what the order of the list does to an
acceleration structure's build is what the study measures. Deterministic for
a given seed. Python's standard library only.
"""
import json
import math
import random
import sys

MATERIALS = {
    "floor": {"ka": 0.5, "kd": 0.6, "ks": 0.1, "shininess": 16},
    "red": {"ka": [0.8, 0.1, 0.1], "kd": [0.8, 0.1, 0.1], "ks": 0.5, "shininess": 64},
    "green": {"ka": [0.1, 0.7, 0.2], "kd": [0.1, 0.7, 0.2], "ks": 0.3, "shininess": 32},
    "mirror": {"ka": 0.05, "kd": 0.05, "ks": 0.8, "shininess": 256, "reflectivity": 0.9},
    "glass": {"ka": 0.0, "kd": 0.0, "ks": 0.9, "shininess": 512, "transmission": 1.0, "ior": 1.517},
}


def floor_scene(n, rng):
    side = max(4.0, 1.6 * math.sqrt(n))  # about one sphere per 2.5 square units
    spheres = []
    for _ in range(n):
        r = rng.uniform(0.2, 0.5)
        spheres.append({"type": "sphere", "center": [round(rng.uniform(-side, side), 4), round(r, 4),
                                                     round(rng.uniform(-side, side), 4)],
                        "radius": round(r, 4), "material": rng.choice(["red", "green", "mirror", "glass"])})
    return {
        "comment": f"{n} random spheres on a floor (tools/make_scene.py floor).",
        "camera": {"position": [0, 0.35 * side + 2, side + 6], "look_at": [0, 0, 0], "fov_y_deg": 50},
        "sky": {"image": "sky.png"},
        "ambient": 0.15,
        "lights": [{"position": [-side, 2 * side + 5, side], "intensity": 0.8}],
        "materials": MATERIALS,
        "objects": [{"type": "quad", "center": [0, 0, 0], "u": [side + 1, 0, 0], "v": [0, 0, -side - 1],
                     "material": "floor"}] + spheres,
    }


def ball_scene(n, rng):
    radius = 0.5 * n ** (1 / 3)  # dense: the spheres overlap a little
    spheres = []
    for _ in range(n):
        while True:
            p = [rng.uniform(-1, 1) for _ in range(3)]
            if sum(c * c for c in p) <= 1:
                break
        spheres.append({"type": "sphere", "center": [round(c * radius, 4) for c in p],
                        "radius": round(rng.uniform(0.2, 0.4), 4),
                        "material": rng.choice(["red", "green", "mirror"])})
    return {
        "comment": f"{n} random spheres in a dense ball, in random order (tools/make_scene.py ball).",
        "camera": {"position": [0, 0, 3.2 * radius + 2], "look_at": [0, 0, 0], "fov_y_deg": 45},
        "sky": {"image": "sky.png"},
        "ambient": 0.2,
        "lights": [{"position": [3 * radius, 4 * radius, 4 * radius], "intensity": 0.8}],
        "materials": MATERIALS,
        "objects": spheres,
    }


def compact(scene):
    """One "spheres" object per material, the spheres in their order within it."""
    lists = {}
    others = []
    for o in scene["objects"]:
        if o["type"] == "sphere":
            lists.setdefault(o["material"], []).extend(o["center"] + [o["radius"]])
        else:
            others.append(o)
    scene["objects"] = others + [{"type": "spheres", "material": m, "data": d} for m, d in lists.items()]
    return scene


def main(argv):
    args = list(argv)
    seed = 1
    packed = "--compact" in args
    if packed:
        args.remove("--compact")
    moving = 0
    if "--moving" in args:
        i = args.index("--moving")
        moving = int(args[i + 1]) if i + 1 < len(args) and args[i + 1].isdigit() else -1
        del args[i:i + 2]
    if "--seed" in args:
        i = args.index("--seed")
        seed = int(args[i + 1])
        del args[i:i + 2]
    if (len(args) != 3 or args[0] not in ("floor", "ball") or not args[1].isdigit() or int(args[1]) < 1
            or moving < 0 or (moving and packed)):
        print("usage: tools/make_scene.py floor|ball N OUT.json [--seed S] [--compact | --moving K]", file=sys.stderr)
        return 2
    rng = random.Random(seed)
    n = int(args[1])
    scene = floor_scene(n, rng) if args[0] == "floor" else ball_scene(n, rng)
    for o in [o for o in scene["objects"] if o["type"] == "sphere"][:moving]:
        o["moving"] = True
    if packed:
        scene = compact(scene)
    with open(args[2], "w") as f:
        json.dump(scene, f, separators=(",", ":"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
