#!/usr/bin/env python3
"""A correct rasterizer in plain Python, certified by refrast over a pipe (docs/protocol.md).

Coverage is exact: vertices snap to 1/256 pixel (round half to even), edge functions are
Python integers, and a sample exactly on an edge belongs to the triangle only if the edge is a
top or a left edge (D3D11's top-left rule). Triangles are clipped in clip space against the
near plane (unless depth clipping is off), the far plane when asked, and a guard band 16384
pixels from the viewport's centre,
each cut computed from the inside end; a clipped polygon covers the samples its snapped fan winds
around. Barycentrics are perspective-correct, depth is z/w through the viewport's depth range
(reversed too), linear on screen and clamped to that range, a scissor rectangle
drops the fragments outside it, the sample mask's bit 0 keeps its one sample or drops it, and its own depth buffer answers `resolve`. It draws triangle
lists, strips and fans (refrast_pipe assembles a strip's or fan's triangles in Vulkan's order),
and each fragment carries its triangle's provoking vertex (first or last) as its flat vertex.
Clip distances are tested per sample, as D3D11.3 §15.4.1 words it (a sample is drawn where each
distance, interpolated perspective-correctly, is >= 0), not by cutting the polygon as refrast
does; a triangle every corner of which is negative in one cull distance is not drawn.

Run it with refrast:  refrast certify --exec "python3 clients/python/topleft.py"

With `--cull MODE` (none, back or front) it is a fixed-function rasterizer: it declares that one
cull mode and uses it whatever a draw asks, as one that cannot switch culling would; refrast
must still judge it on every rule (its triangles are turned to face front).
"""

import argparse
import math
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from refrast_pipe import Fragment, check_indices, serve  # noqa: E402

BITS = 8
ONE = 1 << BITS
GUARD_BAND = 16384.0
COORD_LIMIT = 32768.0

PROFILE = {
    "name": "python-topleft",
    "about": f"clients/python/topleft.py on Python {sys.version.split()[0]}",
    "snapping": f"grid {BITS}",
    "fill": "top-left",
    "depth": "z-over-w",
    "tolerance": 1,
    "precision": 18,
    "features": "perspective-barycentrics screen-barycentrics depth-test ties-to-even scissor "
    "sample-mask inverted-depth unclipped-depth",
    # The guard band's half-side less half the largest viewport (16384 px): its reach beyond
    # every side of every viewport.
    "guard-band": int(GUARD_BAND) - 16384 // 2,
    "topology": "triangle-list triangle-strip triangle-fan",
    "provoking-vertex": "first last",
    "cull": "none front back front-and-back",
    "front-face": "ccw cw",
    "depth-compare": "never less equal less-equal greater not-equal greater-equal always",
    "depth-write": "on off",
    "far-clipping": "off on",
    "depth-range": "zero-to-one negative-one-to-one",
    # f32 depth, the slope as max(|dz/dx|, |dz/dy|) (the approximation Vulkan allows), the clamp.
    "depth-bias": "float32 max clamp",
    # Tested per sample; at most 8 together.
    "clip-distances": 4,
    "cull-distances": 4,
}


def f32(v):
    """v rounded to the nearest f32, as the fragment and the depth buffer store it."""
    return struct.unpack("<f", struct.pack("<f", v))[0]


def orient2d(a, b, c):
    """Twice the signed area of a, b, c in snapped units: positive when clockwise on screen."""
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def owns_edge(a, b):
    """Top-left: for a clockwise triangle, an edge going up is a left edge, a horizontal one
    going right is a top edge."""
    return a[1] > b[1] if a[1] != b[1] else b[0] > a[0]


def snap(v):
    """A raster coordinate to the grid, or None when it is not a number or out of range."""
    if v != v or abs(v) > COORD_LIMIT:
        return None
    return round(v * ONE)


def planes(draw):
    """Signed distances to the clip planes: inside when >= 0."""
    kx, ky = 2 * GUARD_BAND / draw.width, 2 * GUARD_BAND / draw.height
    out = []
    if not draw.near_clipping:
        pass
    elif draw.depth_range == "zero-to-one":
        out.append(lambda p: p[2])
    else:
        out.append(lambda p: p[2] + p[3])
    if draw.far_clipping:
        out.append(lambda p: p[3] - p[2])
    out += [
        lambda p: p[0] + kx * p[3],
        lambda p: kx * p[3] - p[0],
        lambda p: p[1] + ky * p[3],
        lambda p: ky * p[3] - p[1],
    ]
    return out


def clip(polygon, distance):
    """One Sutherland–Hodgman pass; each cut from the inside end, so shared edges cut alike."""
    out = []
    for i, a in enumerate(polygon):
        b = polygon[(i + 1) % len(polygon)]
        da, db = distance(a[0]), distance(b[0])
        if da >= 0:
            out.append(a)
        if (da >= 0) != (db >= 0):
            inside, outside, di, do = (a, b, da, db) if da >= 0 else (b, a, db, da)
            t = di / (di - do)
            out.append((
                tuple(p + (q - p) * t for p, q in zip(inside[0], outside[0])),
                tuple(p + (q - p) * t for p, q in zip(inside[1], outside[1])),
            ))
    return out


def project(draw, vertex, input_w):
    """Snapped position, window depth, 1/w, barycentrics and screen barycentrics of a vertex."""
    (x, y, z, w), bary = vertex
    if not w > 0:
        return None
    px = (x / w + 1.0) * 0.5 * draw.width
    py = (1.0 - y / w) * 0.5 * draw.height
    sx, sy = snap(px), snap(py)
    if sx is None or sy is None:
        return None
    u = z / w if draw.depth_range == "zero-to-one" else (z / w + 1.0) * 0.5
    n, f = draw.viewport_depth
    depth = n + (f - n) * u
    screen = None
    if input_w is not None:
        scaled = [b * wi for b, wi in zip(bary, input_w)]
        total = sum(scaled)
        screen = [s / total for s in scaled]
    return (sx, sy), depth, 1.0 / w, bary, screen


def clipped_clockwise(tri):
    """Olano–Greer: the sign of det[x y w] of the clip-space vertices; None when too close to 0."""
    a, b, c = tri
    terms = [
        a[0] * (b[1] * c[3] - c[1] * b[3]),
        -a[1] * (b[0] * c[3] - c[0] * b[3]),
        a[3] * (b[0] * c[1] - c[0] * b[1]),
    ]
    det = sum(terms)
    scale = (
        abs(a[0]) * max(abs(b[1] * c[3]), abs(c[1] * b[3]))
        + abs(a[1]) * max(abs(b[0] * c[3]), abs(c[0] * b[3]))
        + abs(a[3]) * max(abs(b[0] * c[1]), abs(c[0] * b[1]))
    )
    return det < 0 if abs(det) > 1e-10 * scale else None


def finite(values):
    return all(c == c and c not in (float("inf"), float("-inf")) for c in values)


def triangle_fragments(draw, t, tri, corners_of=None):
    """Every fragment of triangle t, whose clip-space vertices are tri (the draw's vertices
    corners_of, for their clip and cull distances)."""
    if not all(finite(p) for p in tri):
        return []
    clip_distances = None
    if corners_of is not None and draw.cull_distances is not None:
        culls = [draw.cull_distances[i] for i in corners_of]
        if not all(finite(c) for c in culls):
            return []
        if any(all(c[j] < 0 for c in culls) for j in range(len(culls[0]))):
            return []  # culled: every corner negative in one cull distance
    if corners_of is not None and draw.clip_distances is not None:
        clip_distances = [draw.clip_distances[i] for i in corners_of]
        if not all(finite(c) for c in clip_distances):
            return []
    corners = [(p, tuple(1.0 if j == k else 0.0 for j in range(3))) for k, p in enumerate(tri)]
    input_w = [p[3] for p in tri] if all(p[3] > 0 for p in tri) else None
    unclipped = [project(draw, v, input_w) for v in corners] if input_w else [None]
    if all(v is not None for v in unclipped):
        area = orient2d(*(v[0] for v in unclipped))
        if area == 0:
            return []  # zero area, decided before clipping
    polygon = corners
    needs_clipping = False
    for distance in planes(draw):
        if len(polygon) < 3:
            return []
        if any(distance(v[0]) < 0 for v in polygon):
            needs_clipping = True
            polygon = clip(polygon, distance)
    if len(polygon) < 3:
        return []
    raster = [project(draw, v, input_w) for v in polygon]
    if any(v is None for v in raster):
        return []
    points = [v[0] for v in raster]
    fan_area = sum(orient2d(points[0], points[k], points[k + 1]) for k in range(1, len(points) - 1))
    if needs_clipping:
        clockwise = clipped_clockwise(tri)
        if clockwise is None:
            if fan_area == 0:
                return []
            clockwise = fan_area > 0
    else:
        clockwise = fan_area > 0
    front = clockwise == (draw.front_face == "cw")
    if draw.cull == "front-and-back" or (draw.cull == "back" and not front) or (draw.cull == "front" and front):
        return []
    return fan_fragments(draw, t, raster, front, clip_distances)


def edge_function(p, q):
    """orient2d(p, q, s) as A·s.x + B·s.y + C: integers, so stepping it one pixel is exact."""
    return p[1] - q[1], q[0] - p[0], (q[1] - p[1]) * p[0] - (q[0] - p[0]) * p[1]


def depth_offset(draw, raster):
    """The polygon's depth bias o: m from its widest fan triangle (max measure), r = 2^(e - 23)."""
    if draw.depth_bias is None:
        return 0.0
    constant, slope, clamp = draw.depth_bias
    (ax, ay), az = raster[0][0], raster[0][1]
    widest = max(
        ((raster[k], raster[k + 1]) for k in range(1, len(raster) - 1)),
        key=lambda bc: abs(orient2d(raster[0][0], bc[0][0], bc[1][0])),
    )
    (bx, by), bz = widest[0][0], widest[0][1]
    (cx, cy), cz = widest[1][0], widest[1][1]
    det = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    m = 0.0
    if det != 0:
        dzdx = ((bz - az) * (cy - ay) - (cz - az) * (by - ay)) / det * ONE
        dzdy = ((cz - az) * (bx - ax) - (bz - az) * (cx - ax)) / det * ONE
        m = max(abs(dzdx), abs(dzdy))
    largest = max(abs(f32(v[1])) for v in raster)
    exponent = math.frexp(largest)[1] - 1 if largest >= 2.0**-126 else -126
    o = m * slope + 2.0 ** (exponent - 23) * constant
    if clamp > 0:
        o = min(o, clamp)
    elif clamp < 0:
        o = max(o, clamp)
    return o


def fan_fragments(draw, t, raster, front, clip_distances=None):
    """Samples the snapped fan winds around, each with its interpolated values, those where a
    clip distance (given per corner of the input triangle) interpolates to < 0 left out."""
    # A lone triangle covers each of its samples once; a fan's windings are summed per sample.
    lone = len(raster) == 3
    hits, covered = [], {}
    for k in range(1, len(raster) - 1):
        corners = [raster[0], raster[k], raster[k + 1]]
        area = orient2d(*(c[0] for c in corners))
        if area == 0:
            continue
        sign = 1 if area > 0 else -1
        if sign < 0:
            corners = [corners[0], corners[2], corners[1]]
            area = -area
        a, b, c = (v[0] for v in corners)
        # Edge k is opposite corner k; a sample exactly on an edge it does not own is outside,
        # so that edge's value must reach 1 rather than 0 (the bias).
        (a0, b0, c0), (a1, b1, c1), (a2, b2, c2) = (edge_function(p, q) for p, q in [(b, c), (c, a), (a, b)])
        bias0, bias1, bias2 = (0 if owns_edge(p, q) else -1 for p, q in [(b, c), (c, a), (a, b)])
        x0 = max(0, (min(a[0], b[0], c[0]) - ONE // 2) // ONE)
        x1 = min(draw.width - 1, (max(a[0], b[0], c[0]) - ONE // 2) // ONE + 1)
        y0 = max(0, (min(a[1], b[1], c[1]) - ONE // 2) // ONE)
        y1 = min(draw.height - 1, (max(a[1], b[1], c[1]) - ONE // 2) // ONE + 1)
        sx0 = x0 * ONE + ONE // 2
        steps = (a0 * ONE, a1 * ONE, a2 * ONE)
        for py in range(y0, y1 + 1):
            sy = py * ONE + ONE // 2
            # The edge values at the row's first sample; along the row each grows by its step.
            starts = (a0 * sx0 + b0 * sy + c0, a1 * sx0 + b1 * sy + c1, a2 * sx0 + b2 * sy + c2)
            lo, hi = x0, x1
            for e, step, bias in zip(starts, steps, (bias0, bias1, bias2)):
                # Inside this edge where e + step·(px − x0) + bias >= 0: solved for px exactly.
                need = -(e + bias)
                if step > 0:
                    lo = max(lo, x0 - (-need // step))
                elif step < 0:
                    hi = min(hi, x0 + need // step)
                elif need > 0:
                    hi = lo - 1
            e0, e1, e2 = starts
            for px in range(lo, hi + 1):
                d = px - x0
                values = (e0 + steps[0] * d, e1 + steps[1] * d, e2 + steps[2] * d)
                if lone:
                    hits.append((px, py, corners, values, area))
                    continue
                entry = covered.setdefault((px, py), [0, None])
                entry[0] += sign
                if entry[1] is None:
                    entry[1] = (corners, values, area)
    if not lone:
        hits = [(px, py, *found) for (px, py), (winding, found) in covered.items() if winding != 0]
    out = []
    offset = depth_offset(draw, raster)
    for px, py, (ca, cb, cc), (v0, v1, v2), area in hits:
        s0, s1, s2 = v0 / area, v1 / area, v2 / area
        depth = (ca[1] * v0 + cb[1] * v1 + cc[1] * v2) / area + offset
        q0, q1, q2 = s0 * ca[2], s1 * cb[2], s2 * cc[2]
        total = q0 + q1 + q2
        ba, bb, bc = ca[3], cb[3], cc[3]
        bary = (
            (ba[0] * q0 + bb[0] * q1 + bc[0] * q2) / total,
            (ba[1] * q0 + bb[1] * q1 + bc[1] * q2) / total,
            (ba[2] * q0 + bb[2] * q1 + bc[2] * q2) / total,
        )
        if clip_distances is not None and any(
            sum(bary[k] * clip_distances[k][j] for k in range(3)) < 0 for j in range(len(clip_distances[0]))
        ):
            continue
        screen = (0.0, 0.0, 0.0)
        if ca[4] is not None:
            sa, sb, sc = ca[4], cb[4], cc[4]
            screen = (
                sa[0] * s0 + sb[0] * s1 + sc[0] * s2,
                sa[1] * s0 + sb[1] * s1 + sc[1] * s2,
                sa[2] * s0 + sb[2] * s1 + sc[2] * s2,
            )
        out.append(
            Fragment(px, py, t, front, f32(min(max(depth, min(draw.viewport_depth)), max(draw.viewport_depth))), bary, screen, flat=provoking(draw, t))
        )
    return out


# The one cull mode of a fixed-function rasterizer (--cull), or None for all three.
FIXED_CULL = None


def rasterize(draw):
    check_indices(draw)
    if FIXED_CULL is not None:
        draw = draw._replace(cull=FIXED_CULL)
    out = []
    for t, tri in enumerate(draw.triangles):
        out += triangle_fragments(draw, t, [draw.positions[i] for i in tri], tri)
    return [f for f in out if in_scissor(draw, f.x, f.y) and in_sample_mask(draw, f.sample)]


def provoking(draw, t):
    """The vertex giving triangle t its flat values: the first or last of its primitive in the
    index stream (Vulkan's topology sections; OpenGL 4.6 Table 13.2)."""
    first, last = {
        "triangle-list": (3 * t, 3 * t + 2),
        "triangle-strip": (t, t + 2),
        "triangle-fan": (t + 1, t + 2),
    }[draw.topology]
    return draw.indices[last if draw.provoking_vertex == "last" else first]


def in_sample_mask(draw, sample):
    """The sample mask test: bit `sample` of the draw's mask is set (Vulkan's Sample Mask
    Test; at one sample, bit 0)."""
    return (draw.sample_mask >> sample) & 1 == 1


def in_scissor(draw, x, y):
    """The scissor test: the pixel lies in the draw's rectangle, or the draw has none."""
    if draw.scissor is None:
        return True
    sx, sy, width, height = draw.scissor
    return sx <= x < sx + width and sy <= y < sy + height


PASSES = {
    "never": lambda new, old: False,
    "less": lambda new, old: new < old,
    "equal": lambda new, old: new == old,
    "less-equal": lambda new, old: new <= old,
    "greater": lambda new, old: new > old,
    "not-equal": lambda new, old: new != old,
    "greater-equal": lambda new, old: new >= old,
    "always": lambda new, old: True,
}


def resolve(draw):
    """The depth test in primitive order: a passing fragment names its primitive and, with
    writes on, stores its depth."""
    depth = [draw.depth_clear] * (draw.width * draw.height)
    primitive = [None] * (draw.width * draw.height)
    passes = PASSES[draw.depth_compare]
    for f in sorted(rasterize(draw), key=lambda f: f.primitive):
        i = f.y * draw.width + f.x
        if passes(f.depth, depth[i]):
            primitive[i] = f.primitive
            if draw.depth_write:
                depth[i] = f.depth
    return depth, primitive


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description="A correct top-left rasterizer for refrast's pipe protocol.")
    parser.add_argument(
        "--cull",
        choices=["none", "back", "front"],
        help="declare and use only this cull mode, whatever a draw asks",
    )
    FIXED_CULL = parser.parse_args().cull
    if FIXED_CULL is not None:
        PROFILE["cull"] = FIXED_CULL
        PROFILE["name"] = f"python-topleft-cull-{FIXED_CULL}"
    serve(PROFILE, rasterize, resolve)
