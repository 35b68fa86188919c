#!/usr/bin/env python3
"""A student's rasterizer: bounding box, float edge functions, near-plane clipping (docs/protocol.md).

Edge functions are Python floats, each evaluated from the lower of its two end points, so that
the edge a triangle shares with its neighbour gives exactly opposite values in both
(antisymmetric); a sample exactly on an edge belongs to the triangle only if the
edge is a top or a left edge. Triangles are clipped in clip space against the near plane, each
cut computed from the inside end, so that two triangles sharing an edge cut it at one point.
Barycentrics are perspective-correct and depth is z/w.

cli/tests/integration/student.rs breaks it at the lines marked `# MISTAKE:` to check that refrast says why.
Run it with refrast:  refrast certify --exec "python3 clients/python/student.py"
"""

import math
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from refrast_pipe import Fragment, check_indices, serve  # noqa: E402

PROFILE = {"name": "python-student", "snapping": "float", "fill": "top-left",
           "features": "perspective-barycentrics", "cull": "none front back",
           "depth-range": "zero-to-one negative-one-to-one"}


def f32(v):
    """v rounded to the nearest f32, as a GPU's single precision would."""
    return struct.unpack("<f", struct.pack("<f", v))[0]


# The rounding of each step of an edge function: Python's doubles.
ROUND = float  # MISTAKE: precision


def edge(a, b, p):
    """Twice the signed area of a, b, p, from the lower end: edge(b, a, p) == -edge(a, b, p) exactly."""
    if (b[1], b[0]) < (a[1], a[0]):  # MISTAKE: antisymmetry
        return -edge(b, a, p)
    dx, dy = ROUND(b[0] - a[0]), ROUND(b[1] - a[1])
    return ROUND(ROUND(dx * ROUND(p[1] - a[1])) - ROUND(dy * ROUND(p[0] - a[0])))


def owns(a, b):
    """Top-left for a clockwise triangle: an edge going up is a left edge, a flat one going right a top edge."""
    return a[1] > b[1] or (a[1] == b[1] and b[0] > a[0])


def planes(draw):
    """Signed distances to the near plane and to a guard band 16384 px out (which keeps w > 0)."""
    kx, ky = 32768 / draw.width, 32768 / draw.height
    near = (lambda p: p[2]) if draw.depth_range == "zero-to-one" else (lambda p: p[2] + p[3])
    return [near, lambda p: kx * p[3] + p[0], lambda p: kx * p[3] - p[0],  # MISTAKE: near plane
            lambda p: ky * p[3] + p[1], lambda p: ky * p[3] - p[1]]


def clip(polygon, plane):
    """One Sutherland–Hodgman pass; each cut from the inside end, so shared edges cut alike."""
    out = []
    for i, a in enumerate(polygon):
        b = polygon[(i + 1) % len(polygon)]
        da, db = plane(a[0]), plane(b[0])
        if da >= 0:
            out.append(a)
        if (da >= 0) != (db >= 0):
            inside, outside, di, do = (a, b, da, db) if da >= 0 else (b, a, db, da)
            t = di / (di - do)
            out.append(tuple(tuple(p + (q - p) * t for p, q in zip(inside[k], outside[k])) for k in range(2)))
    return out


def triangle_fragments(draw, t, tri):
    corners = [(p, tuple(float(j == k) for j in range(3))) for k, p in enumerate(tri)]
    polygon = corners
    for plane in planes(draw):
        polygon = clip(polygon, plane) if len(polygon) >= 3 else []
    if any(not v[0][3] > 0 for v in polygon):  # MISTAKE: w epsilon
        return []
    raster = [((x / w + 1) * 0.5 * draw.width, (1 - y / w) * 0.5 * draw.height, z / w, 1 / w, bary)
              for (x, y, z, w), bary in polygon]
    out = []
    for k in range(1, len(raster) - 1):
        out += fan_triangle(draw, t, raster[0], raster[k], raster[k + 1])
    return out


def fan_triangle(draw, t, a, b, c):
    area = edge(a, b, c)
    if area == 0:
        return []
    front = (area > 0) == (draw.front_face == "cw")  # clockwise on screen when area > 0
    if (draw.cull == "back" and not front) or (draw.cull == "front" and front):
        return []
    if area < 0:
        b, c, area = c, b, -area
    x0, x1 = max(0, int(min(a[0], b[0], c[0]))), min(draw.width - 1, int(max(a[0], b[0], c[0])))
    y0, y1 = max(0, int(min(a[1], b[1], c[1]))), min(draw.height - 1, int(max(a[1], b[1], c[1])))
    out = []
    for py in range(y0, y1 + 1):
        for px in range(x0, x1 + 1):
            p = (px + 0.5, py + 0.5)
            e = [edge(b, c, p), edge(c, a, p), edge(a, b, p)]
            ties = [owns(b, c), owns(c, a), owns(a, b)]
            if not all(v > 0 or (v == 0 and tie) for v, tie in zip(e, ties)):  # MISTAKE: tie rule
                continue
            s = [v / area for v in e]
            q = [s[0] * a[3], s[1] * b[3], s[2] * c[3]]
            bary = tuple(sum(q[j] * v[4][i] for j, v in enumerate((a, b, c))) / sum(q) for i in range(3))
            depth = s[0] * a[2] + s[1] * b[2] + s[2] * c[2]
            if draw.depth_range != "zero-to-one":
                depth = (depth + 1) * 0.5
            out.append(Fragment(px, py, t, front, min(max(depth, 0.0), 1.0), bary))
    return out


def rasterize(draw):
    check_indices(draw)
    out = []
    for t, tri in enumerate(draw.triangles):
        corners = [draw.positions[i] for i in tri]
        # A NaN or infinite coordinate has no place on screen: its triangles are skipped.
        if all(math.isfinite(c) for p in corners for c in p):
            out += triangle_fragments(draw, t, corners)
    return out


if __name__ == "__main__":
    serve(PROFILE, rasterize)
