#!/usr/bin/env python3
"""Seed 004's fill rasterizer (TU Wien EVC, "Beispiel 5 – Rasterisierung"), as the lab describes
it, certified by refrast over a pipe (docs/protocol.md).

- Clipping: Sutherland–Hodgman in clip space against six planes in Hesse normal form; a vertex
  is inside a plane p when v · p <= 0. Each edge is cut at t = l_a / (l_a - l_b), nudged by 1e-6
  toward its inside end, and positions and attributes are mixed with that t.
- Fill: the clipped polygon as a fan from its first vertex; for each triangle the line equations
  O_i(x, y) = A_i x + B_i y + C_i of its edges, and a pixel (x, y) of the bounding box is inside
  when O_i <= 0 for all three. The pixel is its top-left corner (the lab never adds 1/2), and
  with y down only counter-clockwise triangles have an inside.
- Attributes: alpha = O_1(P) / O_1(V_1), likewise beta and gamma, mix the vertices' attributes
  (barycentricMix); here those are the weights in the input triangle and the depth z/w.

refrast's zoo holds the same lab in Rust (`lab004-lineeq`); this port gives the same verdicts.
Run it with refrast:  refrast certify --exec "python3 clients/python/lab004.py"
"""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from refrast_pipe import Fragment, check_indices, serve  # noqa: E402

NUDGE = 1e-6

PROFILE = {
    "name": "python-lab004",
    "about": f"clients/python/lab004.py on Python {sys.version.split()[0]}",
    "snapping": "float",
    "fill": "none",
    "depth": "z-over-w",
    "tolerance": 1,
    "precision": 18,
    "features": "screen-barycentrics",
    "cull": "none",
    "front-face": "ccw cw",
    "depth-compare": "less",
    "depth-write": "on",
    "far-clipping": "off on",
    "depth-range": "zero-to-one negative-one-to-one",
}


def clipping_planes(depth_range):
    """x and y against +-w, far z <= w, and near by the depth range."""
    near = (0.0, 0.0, -1.0, -1.0) if depth_range == "negative-one-to-one" else (0.0, 0.0, -1.0, 0.0)
    return [
        (1.0, 0.0, 0.0, -1.0),
        (-1.0, 0.0, 0.0, -1.0),
        (0.0, 1.0, 0.0, -1.0),
        (0.0, -1.0, 0.0, -1.0),
        (0.0, 0.0, 1.0, -1.0),
        near,
    ]


def distance(v, p):
    position = v[0]
    return position[0] * p[0] + position[1] * p[1] + position[2] * p[2] + position[3] * p[3]


def inside(v, p):
    return distance(v, p) <= 0.0


def mix(a, b, t):
    return (
        tuple((1.0 - t) * pa + t * pb for pa, pb in zip(a[0], b[0])),
        tuple((1.0 - t) * wa + t * wb for wa, wb in zip(a[1], b[1])),
    )


def intersect(a, b, p):
    la, lb = distance(a, p), distance(b, p)
    t = la / (la - lb)
    if inside(a, p):
        t -= NUDGE
    elif inside(b, p):
        t += NUDGE
    return mix(a, b, t)


def clip_plane(polygon, p):
    out = []
    for i, a in enumerate(polygon):
        b = polygon[(i + 1) % len(polygon)]
        if inside(a, p):
            out.append(a)
        if inside(a, p) != inside(b, p):
            out.append(intersect(a, b, p))
    return out


def to_screen(v, width, height, depth_range):
    """Divide by w, map to pixels (y down) and window depth; None if that is not a number."""
    x, y, z, w = v[0]
    try:
        sx = (x / w + 1.0) * 0.5 * width
        sy = (1.0 - y / w) * 0.5 * height
        depth = z / w if depth_range == "zero-to-one" else (z / w + 1.0) * 0.5
    except ZeroDivisionError:
        return None
    finite = all(abs(c) != float("inf") and c == c for c in (sx, sy, depth))
    return (sx, sy, depth, v[1]) if w > 0.0 and finite else None


def line_eq(edge, on):
    a, b = -edge[1], edge[0]
    return (a, b, -(a * on[0] + b * on[1]))


def evaluate(o, x, y):
    return o[0] * x + o[1] * y + o[2]


def draw_triangle(v1, v2, v3, width, height, emit):
    e = [
        (v3[0] - v2[0], v3[1] - v2[1]),
        (v1[0] - v3[0], v1[1] - v3[1]),
        (v2[0] - v1[0], v2[1] - v1[1]),
    ]
    o = [line_eq(e[0], v2), line_eq(e[1], v3), line_eq(e[2], v1)]
    denominators = [evaluate(o[0], v1[0], v1[1]), evaluate(o[1], v2[0], v2[1]), evaluate(o[2], v3[0], v3[1])]
    # Zero area has no weights; a positive O_i(V_i) (clockwise) leaves no point inside.
    if not all(d < 0.0 for d in denominators):
        return
    f = [1.0 / d for d in denominators]
    if not all(abs(x) != float("inf") for x in f):
        return
    xs, ys = (v1[0], v2[0], v3[0]), (v1[1], v2[1], v3[1])
    x0, x1 = max(float(math.ceil(min(xs))), 0.0), min(float(math.floor(max(xs))), width - 1.0)
    y0, y1 = max(float(math.ceil(min(ys))), 0.0), min(float(math.floor(max(ys))), height - 1.0)
    if not (x0 <= x1 and y0 <= y1):
        return
    for py in range(int(y0), int(y1) + 1):
        for px in range(int(x0), int(x1) + 1):
            values = [evaluate(oi, float(px), float(py)) for oi in o]
            if not all(value <= 0.0 for value in values):
                continue
            alpha, beta, gamma = values[0] * f[0], values[1] * f[1], values[2] * f[2]
            weights = tuple(alpha * v1[3][k] + beta * v2[3][k] + gamma * v3[3][k] for k in range(3))
            emit(px, py, weights, alpha * v1[2] + beta * v2[2] + gamma * v3[2])


def rasterize(draw):
    check_indices(draw)
    planes = clipping_planes(draw.depth_range)
    # Every drawn triangle is counter-clockwise on screen, the only winding O_i <= 0 accepts.
    front = draw.front_face == "ccw"
    out = []
    for t, tri in enumerate(draw.triangles):
        positions = [draw.positions[i] for i in tri]
        if any(c != c or abs(c) == float("inf") for p in positions for c in p):
            continue
        polygon = [(tuple(p), tuple(1.0 if j == k else 0.0 for j in range(3))) for k, p in enumerate(positions)]
        for p in planes:
            if len(polygon) < 3:
                break
            polygon = clip_plane(polygon, p)
        screen = [to_screen(v, draw.width, draw.height, draw.depth_range) for v in polygon]
        if len(screen) < 3 or any(s is None for s in screen):
            continue
        seen = set()

        def emit(x, y, weights, depth):
            if len(screen) > 3:
                if (x, y) in seen:
                    return
                seen.add((x, y))
            out.append(Fragment(x, y, t, front, min(max(depth, 0.0), 1.0), weights, weights))

        for k in range(1, len(screen) - 1):
            draw_triangle(screen[0], screen[k], screen[k + 1], draw.width, draw.height, emit)
    return out


if __name__ == "__main__":
    serve(PROFILE, rasterize)
