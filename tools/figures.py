#!/usr/bin/env python3
"""Draws the docs' explanatory figures as SVG into docs/images/:

  03_split_order.svg  the boxes lavapipe's midpoint builder makes of a list in file order and in median-split order
  04_pixel_jitter.svg where in a pixel chapter 04's antialiased frames sample (sampling.glsl's points, ported)
  04_sbt_layout.svg   the shader binding table of chapters 06-11 and how a ray picks its record
  10_ray_tree.svg     chapter 10's ray tree through a glass sphere (n = 1.517), traced here exactly
  10_inside_reach.svg chapter 10's tMax for a ray inside a sphere, and the boxes it skips
  11_lobe.svg         64 directions of chapter 11's lobe: the scrambled Sobol points, mapped
  13_absorption.svg   Beer-Lambert in chapter 13's amber glass: what each channel keeps against thickness

    tools/figures.py            write them
    tools/figures.py --check    exit 1 if a file differs from what this script draws (ctest: docs)

Deterministic: the same script draws the same bytes. The lobe uses a Python
port of shaders/common/sampling.glsl (its Sobol points and Owen scrambling).
"""
import math
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
OUT = DOCS / "images"
M32 = 0xFFFFFFFF


class Svg:
    def __init__(self, w, h):
        self.w, self.h, self.items = w, h, []

    def add(self, s):
        self.items.append(s)

    def line(self, x1, y1, x2, y2, color="#333", width=1.5, dash=None, arrow=False):
        extra = f" stroke-dasharray='{dash}'" if dash else ""
        extra += " marker-end='url(#arrow)'" if arrow else ""
        self.add(f"<line x1='{x1:.1f}' y1='{y1:.1f}' x2='{x2:.1f}' y2='{y2:.1f}' stroke='{color}' "
                 f"stroke-width='{width}'{extra}/>")

    def text(self, x, y, s, anchor="start", color="#222", size=13, weight="normal"):
        s = s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
        self.add(f"<text x='{x:.1f}' y='{y:.1f}' text-anchor='{anchor}' fill='{color}' font-family='sans-serif' "
                 f"font-size='{size}' font-weight='{weight}'>{s}</text>")

    def rect(self, x, y, w, h, fill="#fff", stroke="#333", opacity=1.0, width=1.0):
        self.add(f"<rect x='{x:.1f}' y='{y:.1f}' width='{w:.1f}' height='{h:.1f}' fill='{fill}' "
                 f"fill-opacity='{opacity}' stroke='{stroke}' stroke-width='{width}'/>")

    def circle(self, x, y, r, fill="none", stroke="#333", width=1.5):
        self.add(f"<circle cx='{x:.1f}' cy='{y:.1f}' r='{r:.1f}' fill='{fill}' stroke='{stroke}' stroke-width='{width}'/>")

    def polyline(self, points, color="#333", width=1.5):
        pts = " ".join(f"{x:.1f},{y:.1f}" for x, y in points)
        self.add(f"<polyline points='{pts}' fill='none' stroke='{color}' stroke-width='{width}'/>")

    def svg(self):
        head = (f"<svg xmlns='http://www.w3.org/2000/svg' width='{self.w}' height='{self.h}' "
                f"viewBox='0 0 {self.w} {self.h}'>\n<defs><marker id='arrow' viewBox='0 0 10 10' refX='9' refY='5' "
                "markerWidth='7' markerHeight='7' orient='auto-start-reverse'><path d='M0,0 L10,5 L0,10 z' "
                "fill='context-stroke'/></marker></defs>\n"
                f"<rect width='{self.w}' height='{self.h}' fill='white'/>\n")
        return head + "\n".join(self.items) + "\n</svg>\n"


# --- chapter 03: what the order of a list does to a midpoint builder --------------------------------
def median_split(points, order):
    """shared/raytracing/accel.cpp's splitAtMedian in 2D: longest axis, ceil(n / 2) to the front, ties by index."""
    if len(order) <= 2:
        return order
    xs = [points[i][0] for i in order]
    zs = [points[i][1] for i in order]
    axis = 0 if max(xs) - min(xs) >= max(zs) - min(zs) else 1
    order = sorted(order, key=lambda i: (points[i][axis], i))
    middle = (len(order) + 1) // 2
    return median_split(points, order[:middle]) + median_split(points, order[middle:])


def lavapipe_nodes(first, last, depth):
    """The runs [first, last] of the list that lavapipe's builder makes the nodes of one depth."""
    if depth == 0 or first == last:
        return [(first, last)]
    split = (first + last) // 2
    return lavapipe_nodes(first, split, depth - 1) + lavapipe_nodes(split + 1, last, depth - 1)


def split_order():
    import random
    rng = random.Random(3)
    n, depth = 400, 3
    points = [(rng.uniform(0, 1), rng.uniform(0, 1)) for _ in range(n)]
    colors = ["#c0392b", "#2b6f99", "#27ae60", "#8e44ad", "#d35400", "#16a085", "#7f8c8d", "#b7950b"]
    s = Svg(760, 400)
    s.text(20, 24, f"{n} spheres seen from above: the {2 ** depth} nodes of lavapipe's tree at depth {depth}",
           weight="bold")
    panels = [("file order (random)", list(range(n))), ("median-split order", median_split(points, list(range(n))))]
    for p, (title, order) in enumerate(panels):
        ox, oy, size = 40 + p * 380, 50, 300
        s.rect(ox, oy, size, size, fill="#f7f7f7", stroke="#bbb")
        for k, (first, last) in enumerate(lavapipe_nodes(0, n - 1, depth)):
            run = [points[order[i]] for i in range(first, last + 1)]
            x0, x1 = min(q[0] for q in run), max(q[0] for q in run)
            z0, z1 = min(q[1] for q in run), max(q[1] for q in run)
            c = colors[k]
            s.rect(ox + x0 * size, oy + z0 * size, (x1 - x0) * size, (z1 - z0) * size, fill=c, stroke=c,
                   opacity=0.08, width=1.5)
            for x, z in run:
                s.circle(ox + x * size, oy + z * size, 2.2, fill=c, stroke=c, width=0.5)
        s.text(ox + size / 2, oy + size + 22, title, anchor="middle", size=13)
    s.text(380, 392, "a node's box holds its run of the list: a ray that enters it tests what is inside",
           anchor="middle", size=12, color="#444")
    return s.svg()


# --- chapter 04: the SBT -------------------------------------------------------------------------
def sbt_layout():
    handle, handle_align, base_align = 32, 32, 64  # an example; shared/raytracing/sbt.h computes it from the device
    stride = -(-handle // handle_align) * handle_align
    up = lambda v: -(-v // base_align) * base_align
    raygen_size = up(stride)
    misses = ["sky", "shadow"]
    hits = ["quad", "sphere", "sphere mesh", "quad", "sphere", "sphere mesh"]
    miss_off, hit_off = raygen_size, raygen_size + up(len(misses) * stride)
    total = hit_off + up(len(hits) * stride)
    s = Svg(900, 270)
    scale, x0, y0 = 2.0, 20, 70
    s.text(x0, 24, "The shader binding table of chapters 06-11 (handles of 32 bytes, alignments 32 / 64 bytes: "
           "an example)", weight="bold")
    s.text(x0, 44, "raygen | miss | hit regions each start at a multiple of shaderGroupBaseAlignment; "
           "records inside a region are one stride apart", size=12, color="#444")

    def region(off, names, color, label, count_size, first=0):
        for i, n in enumerate(names):
            x = x0 + (off + i * stride) * scale
            s.rect(x, y0, stride * scale, 56, fill=color)
            s.text(x + stride * scale / 2, y0 + 24, str(first + i), anchor="middle", weight="bold")
            s.text(x + stride * scale / 2, y0 + 42, n, anchor="middle", size=10)
        pad_from = off + len(names) * stride
        pad_to = off + count_size
        if pad_to > pad_from:
            s.rect(x0 + pad_from * scale, y0, (pad_to - pad_from) * scale, 56, fill="#eee", stroke="#aaa")
            s.text(x0 + (pad_from + pad_to) / 2 * scale, y0 + 32, "pad", anchor="middle", size=10, color="#777")
        if label:
            s.text(x0 + off * scale, y0 + 76, f"{label} @ {off}", size=12)

    region(0, ["raygen"], "#d7e3fc", "raygen", raygen_size)
    region(miss_off, misses, "#d8f3dc", "miss", up(len(misses) * stride))
    region(hit_off, hits[:3], "#ffe5b4", "hit", up(len(hits) * stride))
    region(hit_off + 3 * stride, hits[3:], "#fcd5ce", "", 0, first=3)
    s.text(x0 + total * scale, y0 + 76, f"{total} bytes", anchor="end", size=12)
    s.text(x0 + (hit_off + 1.5 * stride) * scale, y0 - 8, "camera and bounce rays (ray type 0)", anchor="middle",
           size=11)
    s.text(x0 + (hit_off + 4.5 * stride) * scale, y0 - 8, "shadow rays (ray type offset 3)", anchor="middle",
           size=11)
    y = 190
    s.text(x0, y, "hit record = hit region + stride × (instance SBT offset + ray type offset)", weight="bold")
    s.text(x0, y + 22, "instance SBT offset: 0 quad, 1 analytic sphere, 2 sphere mesh (set per instance in the TLAS, "
           "chapter 03)", size=12)
    s.text(x0, y + 42, "ray type offset: traceRayEXT's sbtRecordOffset, 0 for camera and bounce rays, 3 for shadow "
           "rays (chapter 06)", size=12)
    s.text(x0, y + 62, "miss record = miss region + stride × missIndex: 0 sky, 1 shadow (nothing in the way: lit)",
           size=12)
    # the example: a shadow ray hitting a sphere uses record 1 + 3 = 4
    xr = x0 + (hit_off + 4.5 * stride) * scale
    s.line(xr, y - 14, xr, y0 + 60, color="#c0392b", arrow=True)
    s.text(xr + 8, y - 24, "a shadow ray hits a sphere: 1 + 3 = record 4", color="#c0392b", size=11)
    return s.svg()


# --- chapter 10: the ray tree ---------------------------------------------------------------------
def refract(d, n, eta):
    c1 = -(d[0] * n[0] + d[1] * n[1])
    k = 1 - eta * eta * (1 - c1 * c1)
    if k < 0:
        return None
    c2 = math.sqrt(k)
    return (eta * d[0] + (eta * c1 - c2) * n[0], eta * d[1] + (eta * c1 - c2) * n[1])


def reflect(d, n):
    dn = d[0] * n[0] + d[1] * n[1]
    return (d[0] - 2 * dn * n[0], d[1] - 2 * dn * n[1])


def fresnel(cos_i, n1, n2):
    s2 = (n1 / n2) ** 2 * max(0.0, 1 - cos_i * cos_i)
    if s2 >= 1:
        return 1.0
    cos_t = math.sqrt(1 - s2)
    rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t)
    rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t)
    return 0.5 * (rs * rs + rp * rp)


def exit_point(o, d, c, r):
    """The far intersection of the ray o + t d (|d| = 1, o on or in the circle) with the circle."""
    ox, oy = o[0] - c[0], o[1] - c[1]
    b = ox * d[0] + oy * d[1]
    q = ox * ox + oy * oy - r * r
    t = -b + math.sqrt(max(0.0, b * b - q))
    return (o[0] + t * d[0], o[1] + t * d[1])


def ray_tree():
    n_glass = 1.517
    s = Svg(760, 420)
    c, r = (380.0, 225.0), 120.0
    s.circle(*c, r, fill="#e8f4fb", stroke="#2b6f99", width=2)
    s.text(c[0], c[1] + r + 24, f"glass, n = {n_glass}", anchor="middle", color="#2b6f99")
    s.text(20, 24, "Chapter 10's ray tree: every glass hit splits into a reflected (F) and a refracted (1 - F) "
           "ray", weight="bold")
    s.text(20, 44, "Traced here with Snell's law and the exact Fresnel equations; weights are the fraction "
           "of the camera ray's light each branch carries", size=12, color="#444")
    eye = (20.0, 170.0)
    d = (1.0, 0.0)
    # first hit on the sphere's near side
    oy = eye[1] - c[1]
    x_hit = c[0] - math.sqrt(r * r - oy * oy)
    p1 = (x_hit, eye[1])
    s.line(*eye, *p1, color="#111", width=2.2, arrow=True)
    s.text(eye[0], eye[1] - 10, "camera ray, depth 0")
    n1 = ((p1[0] - c[0]) / r, (p1[1] - c[1]) / r)
    cos1 = -(d[0] * n1[0] + d[1] * n1[1])
    f1 = fresnel(cos1, 1.0, n_glass)
    rd = reflect(d, n1)
    s.line(*p1, p1[0] + 110 * rd[0], p1[1] + 110 * rd[1], color="#c0392b", width=1.8, arrow=True)
    s.text(p1[0] + 110 * rd[0] - 6, p1[1] + 110 * rd[1] - 8, f"reflected, depth 1: F = {f1:.3f}", anchor="middle",
           color="#c0392b", size=12)
    t1 = refract(d, n1, 1 / n_glass)
    p2 = exit_point(p1, t1, c, r)
    s.line(*p1, *p2, color="#1e7b4f", width=1.8, arrow=True)
    s.text((p1[0] + p2[0]) / 2 + 10, (p1[1] + p2[1]) / 2 - 8, f"refracted: {1 - f1:.3f}", color="#1e7b4f", size=12)
    # inside: hits the far side from within
    n2 = ((c[0] - p2[0]) / r, (c[1] - p2[1]) / r)  # the normal facing the ray (inward)
    cos2 = -(t1[0] * n2[0] + t1[1] * n2[1])
    f2 = fresnel(cos2, n_glass, 1.0)
    t2 = refract(t1, n2, n_glass)
    s.line(*p2, p2[0] + 150 * t2[0], p2[1] + 150 * t2[1], color="#1e7b4f", width=1.8, arrow=True)
    s.text(p2[0] + 150 * t2[0] - 40, p2[1] + 150 * t2[1] + 18,
           f"leaves, depth 2: {(1 - f1) * (1 - f2):.3f}", color="#1e7b4f", size=12)
    r2 = reflect(t1, n2)
    p3 = exit_point(p2, r2, c, r)
    s.line(*p2, *p3, color="#c0392b", width=1.4, dash="5,3", arrow=True)
    s.text(p3[0] - 20, p3[1] + 26, f"reflected inside, depth 2: {(1 - f1) * f2:.4f}", anchor="end",
           color="#c0392b", size=12)
    for p in (p1, p2, p3):
        s.circle(*p, 3.5, fill="#111", stroke="#111")
    # page 10's caption gives the same shares, rounded: they must stay true
    caption = (f"{100 * f1:.1f} % is reflected at the\nfirst hit and {100 * (1 - f1) * (1 - f2):.1f} % leaves "
               f"through the far side; the ray reflected inside\ncarries {100 * (1 - f1) * f2:.1f} %")
    if caption not in (DOCS / "10_refraction.md").read_text():
        raise SystemExit(f"figures.py: docs/10_refraction.md's ray tree caption no longer says: {caption!r}")
    s.text(20, 392, f"The ray enters at {math.degrees(math.acos(cos1)):.1f}° from the normal and meets the far side "
           f"at {math.degrees(math.acos(cos2)):.1f}° from inside, the angle it refracted to:", size=12, color="#444")
    s.text(20, 410, "so it can always leave (no total internal reflection). Each branch splits again at its next "
           "hit, until --depth.", size=12, color="#444")
    return s.svg()


def inside_reach():
    """Chapter 10's bound on a ray inside a sphere: tMax = 2r, and the boxes beyond it."""
    n_glass = 1.517
    s = Svg(760, 320)
    s.text(20, 24, "A ray that starts inside a sphere leaves it within 2r: chapter 10 makes 2r its tMax",
           weight="bold")
    s.text(20, 44, "Traversal skips every box that starts beyond tMax, however many spheres lie further along "
           "the line", size=12, color="#444")
    c, r = (250.0, 175.0), 80.0
    s.circle(*c, r, fill="#e8f4fb", stroke="#2b6f99", width=2)
    s.line(c[0] - r, c[1] + r + 14, c[0] + r, c[1] + r + 14, color="#2b6f99", width=1.2)
    s.text(c[0], c[1] + r + 30, "2r: no two points of the sphere are farther apart", anchor="middle",
           color="#2b6f99", size=12)
    a = math.radians(-25)  # upwards, passing 0.85 r from the centre: the chord is 0.83 of 2r
    d = (math.cos(a), math.sin(a))
    eye = (c[0] - 230 * d[0] + 0.85 * r * d[1], c[1] - 230 * d[1] - 0.85 * r * d[0])
    ox, oy = eye[0] - c[0], eye[1] - c[1]
    b = ox * d[0] + oy * d[1]
    t = -b - math.sqrt(b * b - (ox * ox + oy * oy - r * r))  # the near intersection
    p1 = (eye[0] + t * d[0], eye[1] + t * d[1])
    s.line(*eye, *p1, color="#111", width=2, arrow=True)
    s.text(eye[0] + 6, eye[1] + 20, "a ray hits the glass")
    n1 = ((p1[0] - c[0]) / r, (p1[1] - c[1]) / r)
    t1 = refract(d, n1, 1 / n_glass)
    p2 = exit_point(p1, t1, c, r)
    reach = (p1[0] + 2 * r * t1[0], p1[1] + 2 * r * t1[1])
    s.line(*p1, *p2, color="#1e7b4f", width=2.2, arrow=True)
    s.line(*p2, *reach, color="#1e7b4f", width=1.2)
    s.line(*reach, p1[0] + 560 * t1[0], p1[1] + 560 * t1[1], color="#999", width=1.2, dash="5,4")
    s.line(reach[0] - 7 * t1[1], reach[1] + 7 * t1[0], reach[0] + 7 * t1[1], reach[1] - 7 * t1[0],
           color="#1e7b4f", width=2)
    s.text(reach[0], reach[1] - 14, "tMax = 2r", anchor="middle", color="#1e7b4f", size=12, weight="bold")
    s.text(p2[0] - 4, p2[1] + 22, "closest hit: where it leaves", anchor="middle", color="#1e7b4f", size=12)
    for p in (p1, p2):
        s.circle(*p, 3.5, fill="#111", stroke="#111")
    for along, side, radius in ((230, -22, 16), (300, 18, 20), (370, -12, 14), (440, 24, 18)):
        x = p1[0] + along * t1[0] - side * t1[1]
        y = p1[1] + along * t1[1] + side * t1[0]
        s.rect(x - radius, y - radius, 2 * radius, 2 * radius, fill="#f2f2f2", stroke="#bbb")
        s.circle(x, y, radius, fill="#fbe9e7", stroke="#c0392b", width=1.2)
    s.text(560, reach[1] + 60, "boxes beyond tMax: never opened", anchor="middle", color="#777", size=12)
    s.text(20, 310, "With tMax infinite the search may open them before it finds the exit; the bound only "
           "ends the search sooner: the closest hit is the same.", size=12, color="#444")
    return s.svg()


# --- chapter 11: the lobe -------------------------------------------------------------------------
def pcg_hash(v):
    state = (v * 747796405 + 2891336453) & M32
    word = (((state >> ((state >> 28) + 4)) ^ state) * 277803737) & M32
    return ((word >> 22) ^ word) & M32


def bit_reverse(x):
    return int(f"{x:032b}"[::-1], 2)


def sobol_second(i):
    v, y = 0x80000000, 0
    while i:
        if i & 1:
            y ^= v
        i >>= 1
        v ^= v >> 1
    return y


def owen(x, seed):
    x = bit_reverse(x)
    x = (x + seed) & M32
    for k in (0x6c50b47c, 0xb82f1e52, 0xc7afe638, 0x8d22f6e6):
        x ^= (x * k) & M32
    return bit_reverse(x)


def sobol_point(i, seed):
    i = owen(i, pcg_hash((seed + 2) & M32))  # the shuffled index
    x = owen(bit_reverse(i), pcg_hash(seed))
    y = owen(sobol_second(i), pcg_hash((seed + 1) & M32))
    return (x >> 8) / 16777216.0, (y >> 8) / 16777216.0


def lobe():
    roughness, count, seed = 0.3, 64, pcg_hash(12345)
    theta_max = roughness * math.pi / 2
    cos_max = math.cos(theta_max)
    pts = [sobol_point(i, seed) for i in range(count)]
    cells = {(int(u1 * 8), int(u2 * 8)) for u1, u2 in pts}
    assert len(cells) == 64, "the first 64 points must fill the 8 x 8 strata (a (0,6,2)-net)"
    s = Svg(760, 380)
    s.text(20, 24, f"Chapter 11's lobe: {count} directions for roughness {roughness} (cone half-angle "
           f"{math.degrees(theta_max):.0f}°), scrambled Sobol points", weight="bold")
    # left: side view, directions as unit vectors projected on the plane of r and t1
    cx, cy, L = 200.0, 330.0, 240.0
    s.line(cx - 170, cy, cx + 170, cy, color="#555", width=2)
    s.text(cx + 170, cy + 18, "surface", anchor="end", size=11, color="#555")
    for sign in (-1, 1):
        a = sign * theta_max
        s.line(cx, cy, cx + L * math.sin(a), cy - L * math.cos(a), color="#999", dash="4,3")
    for u1, u2 in pts:
        ct = 1 - u1 * (1 - cos_max)
        st = math.sqrt(max(0.0, 1 - ct * ct))
        x = st * math.cos(2 * math.pi * u2)
        s.line(cx, cy, cx + L * 0.92 * x, cy - L * 0.92 * ct, color="#2b6f99", width=0.8)
    s.line(cx, cy, cx, cy - L - 10, color="#c0392b", width=2.2, arrow=True)
    s.text(cx + 6, cy - L - 4, "r (mirror direction)", color="#c0392b", size=12)
    s.text(cx, 352 + 16, "side view: each line one sample direction", anchor="middle", size=12, color="#444")
    # right: equal-area view from above along r, with the 8 x 8 strata of (u1, u2)
    ox, oy, R = 560.0, 190.0, 132.0
    for k in range(1, 9):
        s.circle(ox, oy, R * math.sqrt(k / 8), stroke="#bbb", width=1)
    for k in range(8):
        a = 2 * math.pi * k / 8
        s.line(ox, oy, ox + R * math.cos(a), oy - R * math.sin(a), color="#bbb", width=1)
    for u1, u2 in pts:
        rho, phi = R * math.sqrt(u1), 2 * math.pi * u2
        s.circle(ox + rho * math.cos(phi), oy - rho * math.sin(phi), 3.2, fill="#2b6f99", stroke="#2b6f99", width=1)
    s.text(ox, oy + R + 22, "from above, equal-area (radius ∝ √(1 − cos θ)):", anchor="middle", size=12,
           color="#444")
    s.text(ox, oy + R + 40, "one point in each of the 64 cells of equal solid angle", anchor="middle", size=12,
           color="#444")
    return s.svg()


# --- chapter 04: where in the pixel each frame's ray passes ----------------------------------------
JITTER_STREAM = 0xA511E9B3  # sampling.glsl's


def pixel_jitter_point(pixel, k):
    """Frame k's point of `pixel`: sampling.glsl's pixelJitter."""
    x, y = pixel
    seed = pcg_hash((x + pcg_hash((y + pcg_hash(JITTER_STREAM)) & M32)) & M32)
    return sobol_point(k, seed)


def pixel_jitter():
    pixel, size = (100, 40), 190.0
    s = Svg(760, 330)
    s.text(20, 24, "Chapter 04's antialiasing: where frame k's ray passes through one pixel (scrambled Sobol points)",
           weight="bold")
    edge = lambda x: 0.3 + 0.35 * x  # a silhouette: below it (larger y) the sphere, above it the sky
    covered = 1 - (edge(0) + edge(1)) / 2
    for panel, (count, cells) in enumerate(((4, 2), (16, 4), (64, 8))):
        x0, y0 = 30 + panel * 250.0, 50.0
        pts = [pixel_jitter_point(pixel, k) for k in range(count)]
        assert len({(int(u * cells), int(v * cells)) for u, v in pts}) == count, "one point per cell"
        if panel == 2:
            s.add(f"<polygon points='{x0:.1f},{y0 + size * edge(0):.1f} {x0 + size:.1f},{y0 + size * edge(1):.1f} "
                  f"{x0 + size:.1f},{y0 + size:.1f} {x0:.1f},{y0 + size:.1f}' fill='#f3d9b1'/>")
        for k in range(1, cells):
            s.line(x0 + size * k / cells, y0, x0 + size * k / cells, y0 + size, color="#ccc", width=1)
            s.line(x0, y0 + size * k / cells, x0 + size, y0 + size * k / cells, color="#ccc", width=1)
        s.rect(x0, y0, size, size, fill="none", stroke="#333", width=1.5)
        s.circle(x0 + size / 2, y0 + size / 2, 3, fill="#c0392b", stroke="#c0392b", width=1)
        for u, v in pts:
            s.circle(x0 + size * u, y0 + size * v, 3.2, fill="#2b6f99", stroke="#2b6f99", width=1)
        s.text(x0 + size / 2, y0 + size + 22, f"{count} frames: one point in each of {count} cells",
               anchor="middle", size=12, color="#444")
        if panel == 2:
            s.line(x0, y0 + size * edge(0), x0 + size, y0 + size * edge(1), color="#a04000", width=2)
            inside = sum(1 for u, v in pts if v > edge(u))
            s.text(x0 + size / 2, y0 + size + 40, f"sphere (shaded) covers {covered:.3f} of the pixel;",
                   anchor="middle", size=12, color="#444")
            s.text(x0 + size / 2, y0 + size + 56, f"{inside} of 64 points fall on it: {inside / 64:.3f}",
                   anchor="middle", size=12, color="#444")
    s.text(30, 322, "Red: the centre, the one point every frame samples without --antialias: the pixel is all "
           "sphere or all sky.", size=12, color="#444")
    return s.svg()


def srgb(linear):
    c = min(max(linear, 0.0), 1.0)
    return 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055


def absorption():
    """Beer-Lambert for assets/scenes/real_glass.json's amber: attenuation_color c after distance d_c."""
    color, dc = (0.85, 0.45, 0.12), 0.4
    sigma = [-math.log(c) / dc for c in color]
    s = Svg(760, 356)
    s.text(20, 24, "Beer-Lambert: what white light keeps inside the amber glass, T = exp(-sigma d)",
           weight="bold")
    s.text(20, 44, "attenuation_color (0.85, 0.45, 0.12) after attenuation_distance 0.4: "
           "sigma = -ln(c) / 0.4 = (%.2f, %.2f, %.2f) per unit" % tuple(sigma), size=12, color="#444")
    x0, y0, w, h, dmax = 70.0, 292.0, 440.0, 200.0, 1.2
    X = lambda d: x0 + w * d / dmax
    Y = lambda t: y0 - h * t
    s.line(x0, y0, x0 + w, y0, width=1.2)
    s.line(x0, y0, x0, y0 - h - 6, width=1.2)
    for k in range(7):
        d = 0.2 * k
        s.line(X(d), y0, X(d), y0 + 5, width=1)
        s.text(X(d), y0 + 19, f"{d:.1f}", anchor="middle", size=11)
    for k in range(5):
        t = 0.25 * k
        s.line(x0 - 5, Y(t), x0, Y(t), width=1)
        s.text(x0 - 9, Y(t) + 4, f"{t:.2f}", anchor="end", size=11)
    s.text(x0 + w / 2, y0 + 38, "thickness d (scene units)", anchor="middle", size=12)
    s.text(x0 - 52, y0 - h - 14, "T, transmitted", size=12)
    for sg, name, col in zip(sigma, "RGB", ("#c0392b", "#1e8449", "#2471a3")):
        s.polyline([(X(d), Y(math.exp(-sg * d))) for d in [dmax * i / 120 for i in range(121)]], color=col,
                   width=2.2)
        s.text(X(dmax) + 6, Y(math.exp(-sg * dmax)) + 4, name, color=col, size=12, weight="bold")
    for d, label in ((0.4, "small ball's diameter: T = c"), (0.8, "large ball's: T = c^2")):
        s.line(X(d), y0, X(d), Y(1.0), color="#888", width=1, dash="4,4")
        s.text(X(d) + 4, Y(1.0) - 6 if d < 0.5 else Y(0.92), label, size=11, color="#555")
    s.text(560, 80, "the colour it leaves", size=12, weight="bold")
    for k, d in enumerate((0.1, 0.2, 0.4, 0.8, 1.2)):
        rgb = [round(255 * srgb(math.exp(-sg * d))) for sg in sigma]
        y = 96 + 40 * k
        s.rect(560, y, 60, 30, fill="#%02x%02x%02x" % tuple(rgb), stroke="#666")
        s.text(630, y + 20, f"d = {d:g}", size=12)
    s.text(20, 346, "Blue is gone first: thicker amber is not only darker but redder. A ray through a ball "
           "crosses less glass near the rim than through the centre.", size=12, color="#444")
    return s.svg()


FIGURES = {"03_split_order.svg": split_order, "04_pixel_jitter.svg": pixel_jitter, "04_sbt_layout.svg": sbt_layout, "10_ray_tree.svg": ray_tree,
           "10_inside_reach.svg": inside_reach, "11_lobe.svg": lobe, "13_absorption.svg": absorption}


def main(argv):
    check = "--check" in argv
    stale = []
    for name, draw in FIGURES.items():
        want, path = draw(), OUT / name
        if check:
            if not path.exists() or path.read_text() != want:
                stale.append(name)
        else:
            path.write_text(want)
    if stale:
        print("figures.py: these differ from what tools/figures.py draws (run it): " + ", ".join(stale))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
