# A first rasterizer, written from refrast's README: bounding box, float edge functions,
# top-left tie rule, depth z/w, perspective-correct barycentrics. No clipping yet.
from refrast_pipe import Fragment, check_indices, serve


def edge(a, b, px, py):
    return (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])


def owns(a, b, e, area):
    # Top-left rule for y down: an edge with e == 0 owns the sample when it is a top edge
    # (horizontal, interior below) or a left edge (interior to its right).
    dx, dy = b[0] - a[0], b[1] - a[1]
    if area < 0:
        dx, dy = -dx, -dy
    if e != 0:
        return (e > 0) == (area > 0)
    return (dy == 0 and dx < 0) or dy < 0


def rasterize(draw):
    check_indices(draw)
    for prim, tri in enumerate(draw.triangles):
        verts = [draw.positions[i] for i in tri]
        if any(v[3] <= 0 for v in verts):
            continue
        screen = []
        for x, y, z, w in verts:
            sx = (x / w + 1) * 0.5 * draw.width
            sy = (1 - y / w) * 0.5 * draw.height
            screen.append((sx, sy, z / w, 1 / w))
        area = edge(screen[0], screen[1], screen[2][0], screen[2][1])
        if area == 0:
            continue
        front = (area < 0) == (draw.front_face == "ccw")
        if (draw.cull == "back" and not front) or (draw.cull == "front" and front):
            continue
        x0 = max(int(min(s[0] for s in screen)), 0)
        x1 = min(int(max(s[0] for s in screen)) + 1, draw.width - 1)
        y0 = max(int(min(s[1] for s in screen)), 0)
        y1 = min(int(max(s[1] for s in screen)) + 1, draw.height - 1)
        for py in range(y0, y1 + 1):
            for px in range(x0, x1 + 1):
                cx, cy = px + 0.5, py + 0.5
                e = [edge(screen[1], screen[2], cx, cy), edge(screen[2], screen[0], cx, cy),
                     edge(screen[0], screen[1], cx, cy)]
                pairs = [(screen[1], screen[2]), (screen[2], screen[0]), (screen[0], screen[1])]
                if not all(owns(a, b, ek, area) for (a, b), ek in zip(pairs, e)):
                    continue
                l = [ek / area for ek in e]
                depth = sum(l[k] * screen[k][2] for k in range(3))
                pw = [l[k] * screen[k][3] for k in range(3)]
                s = sum(pw)
                yield Fragment(px, py, prim, front, depth, tuple(p / s for p in pw), tuple(l))


serve({"name": "my-lab", "snapping": "float", "fill": "top-left",
       "features": "perspective-barycentrics screen-barycentrics"}, rasterize)
