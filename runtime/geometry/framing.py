"""The frame placed in the host before the first step (paper Appendix A).

Its corners are pinned: the solver never frees them and no move may remove them, and every
vertex a move places must lie inside the frame. Between two corners runs one border edge,
the side as it is before anything stands on it; rules split it where structures stand.
"""

from __future__ import annotations

from grammar_lang.diagnostics import error
from grammar_lang.frame import Frame, border_labels, border_primitives

from ..engine.host import Host


def place_frame(host: Host, frame: Frame) -> None:
    t = host.t
    ids = []
    for c in frame.corners:
        v = host.new_id()
        host.add_vertex(v, c.prim, (c.x, c.y))
        ids.append(v)
    n = len(ids)
    for k in range(n):
        a, b = frame.corners[k], frame.corners[(k + 1) % n]
        i = _slot_towards(t, a.prim, b.x - a.x, b.y - a.y)
        j = _slot_towards(t, b.prim, a.x - b.x, a.y - b.y)
        if i is None or j is None or t.rings[a.prim][i] != t.rings[b.prim][j] ^ 1:
            raise error(f"the frame's side from ({a.x:g}, {a.y:g}) to ({b.x:g}, {b.y:g}) cannot "
                        "be drawn as one edge: its two corners carry different border labels",
                        None, "leave some room between the frame's corners and the shapes "
                              "that stand on its sides")
        host.glue((ids[k], i), (ids[(k + 1) % n], j))
        inside = t.left[a.prim][i] if _counter_clockwise(frame) else t.right[a.prim][i]
    host.pinned = frozenset(ids)
    host.frame = frame
    host.frame_face = inside
    h = host.header
    host.border_labels = border_labels(h.labels, h.classes)
    # The frame's own sides (border edges with the inside face beside them) are as long as
    # the frame; other border edges are the feet of what stands on it.
    host.side_labels = frozenset(k for k in host.border_labels
                                 if inside in (h.labels[k].left, h.labels[k].right))
    host.on_border = border_primitives(h.primitives, host.border_labels)


def _counter_clockwise(frame: Frame) -> bool:
    cs, n = frame.corners, len(frame.corners)
    return sum(cs[k].x * cs[(k + 1) % n].y - cs[(k + 1) % n].x * cs[k].y for k in range(n)) > 0


def random_inside(host: Host, rng) -> tuple[float, float]:
    """A point drawn uniformly inside the frame's box, kept a tenth of it from the sides, and
    inside the frame itself when it is not a rectangle (a few tries)."""
    x0, y0, x1, y1 = host.frame.box
    mx, my = 0.1 * (x1 - x0), 0.1 * (y1 - y0)
    for _ in range(8):
        p = (x0 + mx + (x1 - x0 - 2 * mx) * float(rng.random()),
             y0 + my + (y1 - y0 - 2 * my) * float(rng.random()))
        if host.frame.contains(*p):
            return p
    return p


def _slot_towards(t, prim: int, dx: float, dy: float) -> int | None:
    norm = (dx * dx + dy * dy) ** 0.5
    for i, (ux, uy) in enumerate(t.direction[prim]):
        if abs(ux * dx + uy * dy - norm) <= 1e-9 * max(norm, 1.0):
            return i
    return None
