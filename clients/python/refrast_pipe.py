"""The child side of refrast's pipe protocol, version 3 (docs/protocol.md), standard library only.

Copy this file beside your rasterizer and call `serve(profile, rasterize)`: refrast starts your
program, reads the profile, then sends draws on stdin and reads fragments from stdout. Print
anything meant for people to stderr: stdout belongs to the protocol.
"""

import struct
import sys
from collections import namedtuple

VERSION = 3

# x, y, primitive, front-facing (u32), depth, perspective barycentrics, screen barycentrics (f32),
# sample, flat vertex (u32; 0xFFFFFFFF for none).
FRAGMENT = struct.Struct("<4I7f2I")

Draw = namedtuple(
    "Draw",
    "width height positions triangles cull front_face depth_compare depth_write depth_clear "
    "depth_range far_clipping topology samples scissor indices provoking_vertex near_clipping "
    "viewport_depth depth_bias polygon_mode clip_distances cull_distances sample_mask interpolation "
    "conservative",
    defaults=(None, None, "first", True, (0.0, 1.0), None, "fill", None, None, 0xFFFFFFFF, "sample", None),
)
Draw.__doc__ = """One draw: clip-space positions (x, y, z, w), triangles (i, j, k) and state.

cull is none/front/back (or front-and-back, sent only to a profile whose cull line lists it), front_face ccw/cw, depth_compare less/less-equal/greater/
greater-equal/equal/not-equal/always/never, depth_write and far_clipping booleans, depth_clear a
float, depth_range zero-to-one or negative-one-to-one. scissor is None, or (x, y, width, height)
in pixels (origin top-left) for a profile whose features name scissor: then no fragment may lie
outside x <= px < x + width, y <= py < y + height. topology is triangle-list, or triangle-strip
or triangle-fan for a profile whose topology line lists them; samples is 1 unless the profile's
samples line lists more. indices are the draw's as sent; triangles are its triangles in the
order Vulkan makes them (triangle i of a strip: indices i, i+1+i%2, i+2-i%2; of a fan: i+1, i+2,
0), so a triangle rasterizer draws strips and fans unchanged, barycentric k being the weight of
its triangle's vertex k. Lines and points are read (their indices) but make no triangles.
provoking_vertex is first or last: which vertex of a primitive gives its flat values (a
fragment's flat), last only for a profile whose provoking-vertex line lists it. near_clipping is
False only for a profile whose features name unclipped-depth (and far_clipping is then False too):
nothing is cut at the near or far plane and depth is clamped to the viewport's depth range.
sample_mask is a 32-bit int whose bit i keeps sample i (all ones keeps every sample); other
than all ones only for a profile whose features name sample-mask: then no fragment may be at a
sample whose bit is clear (bit 0 at one sample).
interpolation is sample, or centroid for a triangle draw at several samples to a profile whose
features name centroid: then all of a triangle's fragments in a pixel carry the barycentrics of
one location, the pixel centre where it covers every sample (before the mask), else its first
covered sample the mask keeps.
conservative is None, or ("over", extra) or ("under",) for a filled triangle draw to a profile
with a conservative line: each pixel whose closed square the snapped triangle touches (grown by
extra pixels at each edge), or under underestimation lies wholly inside, is drawn at every sample.
viewport_depth is (min, max), where the near and far planes land in window depth (n + (f - n) * u),
other than (0.0, 1.0) only for a profile whose features name viewport-depth (min > max only for
inverted-depth); depth clamps to [min(n, f), max(n, f)]. depth_bias is None, or (constant, slope,
clamp) for a triangle draw to a profile with a depth-bias line: each triangle's depth is offset
by o = m * slope + r * constant (min(o, clamp) when clamp > 0, max(o, clamp) when clamp < 0),
m its depth slope and r its format's resolvable difference, before the clamp to the range.
polygon_mode is fill, or line or point for a triangle draw to a profile whose polygon-mode line
lists it: each triangle, clipped, faced and culled as a filled one, draws its edges (first to
second, second to third, third to first) by the profile's line rule, or its vertices as points.
clip_distances and cull_distances are None, or one list per vertex for a profile with a
clip-distances or cull-distances line: a primitive is drawn only where each clip distance,
interpolated perspective-correctly, is >= 0, and not at all when every vertex has a negative
value of one cull distance. Indices are not checked: raise Refused for one that names no vertex."""

Fragment = namedtuple(
    "Fragment", "x y primitive front_facing depth barycentric screen_barycentric sample flat"
)
Fragment.__new__.__defaults__ = ((0.0, 0.0, 0.0), 0, None)
Fragment.__doc__ = """One covered sample. screen_barycentric may be None for a triangle with a
vertex at w <= 0, which has no shape on screen (sent as three NaN words, "none"); for any other
triangle of a profile declaring screen-barycentrics, None fails the bary. rules. flat is the
draw's vertex whose flat values the fragment carries (its primitive's provoking vertex), or None
for a profile without a provoking-vertex line."""

# Three NaN words: no screen-space barycentrics (docs/protocol.md, fragment records).
NO_WEIGHTS = (float("nan"),) * 3


class Refused(Exception):
    """Raise it to refuse a draw (a bad index, say): refrast gets `error MESSAGE`."""


class Unsupported(Exception):
    """Raise it for a draw asking something this rasterizer cannot do: `unsupported MESSAGE`."""


def check_indices(draw):
    """Raises Refused for a triangle naming a vertex the draw does not have."""
    vertices = len(draw.positions)
    for t, tri in enumerate(draw.triangles):
        bad = [i for i in tri if i >= vertices]
        if bad:
            raise Refused(f"triangle {t} uses vertex {bad[0]}, but the draw has {vertices} vertices")


def _read_exactly(stream, n):
    data = stream.read(n)
    if data is None or len(data) != n:
        raise EOFError(f"stdin ended inside a draw ({0 if data is None else len(data)} of {n} bytes)")
    return data


def index_count(topology, primitives):
    """How many indices follow a request's positions: docs/protocol.md's `triangles=T` rule."""
    if primitives == 0:
        return 0
    per = {"triangle-list": 3 * primitives, "line-list": 2 * primitives, "point-list": primitives}
    joined = {"line-strip": primitives + 1, "triangle-strip": primitives + 2, "triangle-fan": primitives + 2}
    if topology in per:
        return per[topology]
    if topology in joined:
        return joined[topology]
    raise ValueError(f"topology {topology!r} is none this helper reads; docs/protocol.md lists them")


def assemble(topology, indices):
    """The triangles `indices` make, each in Vulkan's vertex order; none for lines and points."""
    if topology == "triangle-list":
        return [tuple(indices[i : i + 3]) for i in range(0, len(indices) - 2, 3)]
    count = max(0, len(indices) - 2)
    if topology == "triangle-strip":
        return [(indices[i], indices[i + 1 + i % 2], indices[i + 2 - i % 2]) for i in range(count)]
    if topology == "triangle-fan":
        return [(indices[i + 1], indices[i + 2], indices[0]) for i in range(count)]
    return []


def _read_draw(words, stream):
    fields = dict(word.split("=", 1) for word in words[1:])
    width, height = int(fields["width"]), int(fields["height"])
    vertices, primitives = int(fields["vertices"]), int(fields["triangles"])
    topology = fields.get("topology", "triangle-list")
    n = index_count(topology, primitives)
    floats = struct.unpack(f"<{4 * vertices}f", _read_exactly(stream, 16 * vertices))
    indices = struct.unpack(f"<{n}I", _read_exactly(stream, 4 * n))
    clip, cull = (int(v) for v in fields.get("distances", "0,0").split(","))
    per = clip + cull
    values = struct.unpack(f"<{per * vertices}f", _read_exactly(stream, 4 * per * vertices))
    rows = [values[v * per : (v + 1) * per] for v in range(vertices)]
    return Draw(
        width=width,
        height=height,
        positions=[floats[i : i + 4] for i in range(0, len(floats), 4)],
        triangles=assemble(topology, indices),
        indices=list(indices),
        cull=fields["cull"],
        front_face=fields["front-face"],
        depth_compare=fields["depth-compare"],
        depth_write=fields["depth-write"] == "on",
        depth_clear=float(fields["depth-clear"]),
        depth_range=fields["depth-range"],
        far_clipping=fields["far-clipping"] == "on",
        topology=topology,
        samples=int(fields.get("samples", "1")),
        scissor=tuple(int(v) for v in fields["scissor"].split(",")) if "scissor" in fields else None,
        provoking_vertex=fields.get("provoking-vertex", "first"),
        near_clipping=fields.get("near-clipping", "on") == "on",
        viewport_depth=tuple(float(v) for v in fields["viewport-depth"].split(","))
        if "viewport-depth" in fields
        else (0.0, 1.0),
        depth_bias=tuple(float(v) for v in fields["depth-bias"].split(",")) if "depth-bias" in fields else None,
        polygon_mode=fields.get("polygon-mode", "fill"),
        clip_distances=[list(r[:clip]) for r in rows] if clip else None,
        cull_distances=[list(r[clip:]) for r in rows] if cull else None,
        sample_mask=int(fields.get("sample-mask", "4294967295")),
        interpolation=fields.get("interpolation", "sample"),
        conservative=_conservative(fields.get("conservative")),
    )


def _conservative(word):
    """The conservative key's value as ("over", extra) or ("under",); None without one."""
    if word is None:
        return None
    if word == "under":
        return ("under",)
    mode, _, extra = word.partition(",")
    return (mode, float(extra))


def _one_line(message):
    return " ".join(str(message).split()) or "no reason given"


def serve(profile, rasterize, resolve=None):
    """Declares `profile` (a dict of docs/protocol.md's profile keys to their values) and answers
    draws until stdin ends.

    `rasterize(draw)` returns an iterable of Fragment. `resolve(draw)`, needed only when the
    profile's features include depth-test, returns (depth, primitive): two row-major lists of
    width * height values, a float and an int or None.
    """
    out, inp = sys.stdout.buffer, sys.stdin.buffer
    lines = [f"refrast-protocol {VERSION}"]
    lines += [f"{key} {value}" for key, value in profile.items()]
    lines.append("ready")
    out.write(("\n".join(lines) + "\n").encode())
    out.flush()
    while True:
        header = inp.readline()
        if not header:
            return
        words = header.decode().split()
        if not words:
            continue
        draw = _read_draw(words, inp)
        try:
            if words[0] == "rasterize":
                fragments = list(rasterize(draw))
                reply = [f"fragments {len(fragments)}\n".encode()]
                for f in fragments:
                    reply.append(
                        FRAGMENT.pack(
                            f.x, f.y, f.primitive, 1 if f.front_facing else 0, f.depth,
                            *f.barycentric, *(f.screen_barycentric or NO_WEIGHTS), f.sample,
                            0xFFFFFFFF if f.flat is None else f.flat,
                        )
                    )
            elif words[0] == "resolve" and resolve is not None:
                depth, primitive = resolve(draw)
                n = draw.width * draw.height
                reply = [
                    f"resolved {draw.width} {draw.height}\n".encode(),
                    struct.pack(f"<{n}f", *depth),
                    struct.pack(f"<{n}I", *(0xFFFFFFFF if p is None else p for p in primitive)),
                ]
            else:
                raise Unsupported(f"no `{words[0]}` here")
            reply.append(b"end\n")
            out.write(b"".join(reply))
        except Refused as e:
            out.write(f"error {_one_line(e)}\n".encode())
        except Unsupported as e:
            out.write(f"unsupported {_one_line(e)}\n".encode())
        out.flush()
