"""The frame placed in the host before the first step (paper Appendix A).

Its corners are pinned: the solver never frees them and no move may remove them, and every
vertex a move places must lie inside the frame. Between two corners runs one border edge,
the side as it is before anything stands on it; rules split it where structures stand. A
frame whose sides change label starts from its `start` graph instead, placed by the solver
around the corners.
"""

from __future__ import annotations

import math

from grammar_lang import limits
from grammar_lang.diagnostics import Span, UserError, error
from grammar_lang.fileio import read_text
from grammar_lang.frame import (Frame, bare_sides, border_labels, border_primitives,
                                 crooked_side, crooked_text, slot_towards)

from .change import HostView

# Solver runs for a frame's start graph. Each places the start about one time in three (the
# paper's village, `examples/space-station.gg`: 1,500 seeds needed up to 13 and 18 runs), so
# at 8 one seed in 70 and one in 28 could not start at the example's own extent; at 48 the
# chance is under 1e-8, and a frame that cannot hold the start still says so within seconds.
# A seed that started within fewer runs draws what it drew: the runs stop at the first.
START_TRIES = 48


def place_frame(host: HostView, frame: Frame, rng=None) -> None:
    """The frame in the empty host: bare, one border edge per side, when it can be drawn so;
    else its `start` (the example's frame component), the rest solved around its corners."""
    h = host.header
    sides = bare_sides(frame, h.primitives, h.labels)
    if any(s is None for s in sides) and frame.start is None:
        k = sides.index(None)
        a, b = frame.corners[k], frame.corners[(k + 1) % len(frame.corners)]
        raise error(f"the frame's side from ({a.x:g}, {a.y:g}) to ({b.x:g}, {b.y:g}) cannot "
                    "be drawn as one edge: its two corners carry different border labels",
                    None, "leave some room between the frame's corners and the shapes "
                          "that stand on its sides, or compile the example again (a grammar "
                          "compiled today starts such a frame from the example's own)")
    bent = crooked_side(frame, h.primitives, h.labels)
    if bent is not None:
        raise error(crooked_text(frame, bent), None,
                    "draw the frame's sides along their edges' directions, or compile the "
                    "example again")
    _check_size(host, frame)
    ids = []
    for c in frame.corners:
        v = host.new_id()
        host.add_vertex(v, c.prim, (c.x, c.y))
        ids.append(v)
    _mark(host, frame, ids)
    if all(s is not None for s in sides):
        n = len(ids)
        for k, (i, j) in enumerate(sides):
            host.glue((ids[k], i), (ids[(k + 1) % n], j))
    else:
        _place_start(host, frame, ids, rng)


def _check_size(host: HostView, frame: Frame) -> None:
    """Refuse a frame whose sides cross more grid cells than the extent limit allows, before
    anything is filed (limits.EXTENT)."""
    cs, seg = frame.corners, host.grid.seg
    n = len(cs)
    cells = sum(abs(cs[(k + 1) % n].x - cs[k].x) + abs(cs[(k + 1) % n].y - cs[k].y)
                for k in range(n)) / seg
    w, h = frame.size
    limits.EXTENT.check(math.ceil(cells), None, what=f"grid cells of {seg:g} units along the "
                                                     f"sides of a {w:,.10g} × {h:,.10g} frame")


def _mark(host: HostView, frame: Frame, ids: list[int]) -> None:
    """What the host knows of its frame: pinned corners, the inside face, border labels."""
    h = host.header
    c0, c1 = frame.corners[0], frame.corners[1]
    i = slot_towards(h.primitives[c0.prim].ring, h.labels, c1.x - c0.x, c1.y - c0.y)
    ccw = _counter_clockwise(frame)
    inside = host.t.left[c0.prim][i] if ccw else host.t.right[c0.prim][i]
    outside = host.t.right[c0.prim][i] if ccw else host.t.left[c0.prim][i]
    host.pinned = frozenset(ids)
    host.frame = frame
    host.frame_face = inside
    host.border_labels = border_labels(h.labels, h.classes)
    # The frame's own sides (border edges between the space inside and the outside) are as
    # long as the frame; other border edges are the feet of what stands on it, which keep
    # their own lengths. Faces, not the inside face alone: a grounded scene's outside has the
    # sky's label, so a tower's foot has the sky beside it too.
    host.side_labels = frozenset(k for k in host.border_labels
                                 if {h.labels[k].left, h.labels[k].right} <= {inside, outside})
    # Of those, the ones with no length of their own, neither typical nor floor: every side
    # but the gaps where lines across the frame end (a strip's height at the frame).
    host.unsized_sides = host.side_labels - host.t.gaps
    host.on_border = border_primitives(h.primitives, host.border_labels)


def _place_start(host: HostView, frame: Frame, corner_ids: list[int], rng) -> None:
    """The start graph's corners are the placed corners; every other vertex is new, and the
    solver places them all in one move, as a rule's right side is placed."""
    import numpy as np
    from .change import Change
    from .solver import Solver
    start = frame.start
    by_prim = {c.prim: v for c, v in zip(frame.corners, corner_ids)}
    ids, new = [], []
    for p in start.vertices:
        if p in by_prim:
            ids.append(by_prim.pop(p))
        else:
            ids.append(host.new_id())
            new.append((ids[-1], p))
    glue = tuple(((ids[v], i), (ids[w], j)) for v, i, w, j in start.edges)
    partner = {(ids[k], i): None for k, p in enumerate(start.vertices)
               for i in range(len(host.t.rings[p]))}
    for a, b in glue:
        partner[a], partner[b] = b, a
    change = Change(None, None, (), tuple(new), glue, (), partner)
    x0, y0, x1, y1 = frame.box
    rng = rng if rng is not None else np.random.default_rng(0)
    blamed: dict[int, int] = {}
    for _ in range(START_TRIES):
        solver = Solver(host, change, rng, lambda: ((x0 + x1) / 2, (y0 + y1) / 2))
        pos = next((p.positions for p in solver.placements()), None)
        if pos is not None:
            break
        for lab, n in solver.blamed.items():
            blamed[lab] = blamed.get(lab, 0) + n
    else:
        what, span = _what_did_not_fit(host, blamed)
        raise error("the frame's start (the example's frame with what touches it) could not be "
                    f"placed in a {x1 - x0:g} × {y1 - y0:g} frame" + what, span,
                    "give an --extent closer to the example's own frame, or widen that class",
                    source=_text_at(span))
    for v, p in new:
        host.add_vertex(v, p, pos[v])
    for a, b in glue:
        host.glue(a, b)


def _what_did_not_fit(host: HostView, blamed: dict[int, int]) -> tuple[str, Span | None]:
    """The class whose lengths failed most often, with its range, and where it is declared:
    what the extent asks too much of (a frame's side of a class the example bounds)."""
    if not blamed:
        return "", None
    lab = max(sorted(blamed), key=blamed.get)
    lo, hi = host.t.lengths[lab][:2]
    name = host.header.labels[lab].cls
    span = next((c.span for c in host.header.classes if c.name == name), None)
    return (f": edges of class {name} ({lo:g} to {hi:g} long) could not take the lengths "
            "it asks for", span)


def _text_at(span: Span | None) -> str | None:
    """The text of the file a span is in, for the error's excerpt; None when it cannot be
    read (a rule file given as text, a file since moved)."""
    try:
        return read_text(span.file) if span is not None else None
    except UserError:
        return None


def _counter_clockwise(frame: Frame) -> bool:
    cs, n = frame.corners, len(frame.corners)
    return sum(cs[k].x * cs[(k + 1) % n].y - cs[(k + 1) % n].x * cs[k].y for k in range(n)) > 0


def random_inside(host: HostView, rng) -> tuple[float, float]:
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
