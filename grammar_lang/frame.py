"""The border of the space (paper Appendix A): a closed loop of edges of a border class.

An example may be drawn inside a frame. The frame is not a shape to copy: generation starts
from it, placed once, and everything grows inside it. Structures stand on its sides (their
bottom edges are border edges) and lines end on it (a T-junction on a side).

The frame's *corners* are the vertices where the border turns; the vertices where something
meets a straight side are ordinary primitives that rules may create and remove, since the side
runs straight on through them. A `Frame` keeps the corners in order round the loop; the edge
from one corner to the next is a single border edge, the frame as it is before anything stands
on it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

from . import boundary as bd
from .diagnostics import Span, error
from .graph import Side


@dataclass(frozen=True)
class Corner:
    prim: int           # primitive index
    x: float
    y: float


@dataclass(frozen=True)
class Frame:
    corners: tuple[Corner, ...]
    start: Side | None = None     # what generation starts from when the sides cannot be bare

    # Cached: asked for every vertex of every sample (a frozen instance never changes).
    @cached_property
    def box(self) -> tuple[float, float, float, float]:
        xs, ys = [c.x for c in self.corners], [c.y for c in self.corners]
        return min(xs), min(ys), max(xs), max(ys)

    @cached_property
    def rectangle(self) -> bool:
        """Four corners on axis-parallel sides: inside its box is inside it."""
        return len(self.corners) == 4 and self.axis_aligned

    @property
    def size(self) -> tuple[float, float]:
        x0, y0, x1, y1 = self.box
        return x1 - x0, y1 - y0

    @property
    def axis_aligned(self) -> bool:
        n = len(self.corners)
        return all(a.x == b.x or a.y == b.y
                   for a, b in ((self.corners[k], self.corners[(k + 1) % n]) for k in range(n)))

    def scaled(self, width: float, height: float) -> "Frame":
        """The same frame stretched to `width` × `height`, its lower-left corner kept."""
        x0, y0, _, _ = self.box
        w, h = self.size
        return Frame(tuple(Corner(c.prim, x0 + (c.x - x0) * width / w,
                                  y0 + (c.y - y0) * height / h) for c in self.corners),
                     self.start)

    def contains(self, x: float, y: float, margin: float = 0.0) -> bool:
        """Inside the loop (even-odd rule), and at least `margin` inside its bounding box."""
        x0, y0, x1, y1 = self.box
        if not (x0 + margin <= x <= x1 - margin and y0 + margin <= y <= y1 - margin):
            return False
        if self.rectangle:
            return True
        inside, n = False, len(self.corners)
        for k in range(n):
            a, b = self.corners[k], self.corners[(k + 1) % n]
            if (a.y > y) != (b.y > y):
                if x < a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y):
                    inside = not inside
        return inside


def bare_sides(frame: Frame, primitives, labels) -> list[tuple[int, int] | None]:
    """Per side (corner k to corner k + 1), the slots of its two corners that point at each
    other when they are one edge's two half-edges, else None: something meets that side, and
    the border label changes along it."""
    out = []
    n = len(frame.corners)
    for k in range(n):
        a, b = frame.corners[k], frame.corners[(k + 1) % n]
        i = slot_towards(primitives[a.prim].ring, labels, b.x - a.x, b.y - a.y)
        j = slot_towards(primitives[b.prim].ring, labels, a.x - b.x, a.y - b.y)
        ok = i is not None and j is not None and \
            primitives[a.prim].ring[i] == bd.opposite(primitives[b.prim].ring[j])
        out.append((i, j) if ok else None)
    return out


def slot_towards(ring, labels, dx: float, dy: float) -> int | None:
    """The slot of a ring whose half-edge points along (dx, dy), within a hair."""
    angle = math.degrees(math.atan2(dy, dx))
    for i, t in enumerate(ring):
        d = labels[bd.label_of(t)].direction(bd.is_bar(t))
        if abs((d - angle + 180.0) % 360.0 - 180.0) <= 1e-3:
            return i
    return None


def border_labels(labels, classes) -> frozenset[int]:
    """Ids of the labels whose class is a border class."""
    border = {c.name for c in classes if c.border}
    return frozenset(k for k, lab in enumerate(labels) if lab.cls in border)


def _turns(ring, labels, border) -> bool:
    """A vertex whose two border half-edges are not opposite: the border turns there."""
    dirs = [labels[bd.label_of(t)].direction(bd.is_bar(t)) for t in ring
            if bd.label_of(t) in border]
    return len(dirs) == 2 and abs(abs(dirs[0] - dirs[1]) - 180.0) > 1e-6


def corner_primitives(primitives, labels, border) -> frozenset[int]:
    return frozenset(k for k, p in enumerate(primitives) if _turns(p.ring, labels, border))


def spans_the_space(border_edge: bool, u_on_border: bool, v_on_border: bool) -> bool:
    """Whether an edge is a chord of the space: not itself a border edge, with both ends on
    the border. Such an edge is a piece of a line that does not end (Appendix A,
    "infinitely-long lines"), cut by the frame: the frame sets its length, and no class
    maximum applies to it (its minimum still does). Without this the village could never lay
    a new strip of land from the frame's left side to its right: its one edge is as long as
    the frame is wide, and its class allows 440 px. For a convex frame the two ends lie on
    different sides, since a straight edge leaving a side cannot come back to it."""
    return not border_edge and u_on_border and v_on_border


def border_primitives(primitives, border) -> frozenset[int]:
    """Primitives with at least one border half-edge: the frame and what stands on it."""
    return frozenset(k for k, p in enumerate(primitives)
                     if any(bd.label_of(t) in border for t in p.ring))


def across_labels(primitives, labels, classes) -> frozenset[int]:
    """The labels of the lines across a frame: a line that meets the frame's border at both
    ends (a border vertex has it pointing in, another pointing back out), whatever stands on
    it in between (the village's skyline runs from side to side, broken by houses and hills).
    The compiler stands the example's structures on them (`line_starters`)."""
    meets = _meeting(primitives, labels, classes)
    return frozenset(t >> 1 for t in meets if t ^ 1 in meets)


def through_labels(primitives, labels, classes) -> frozenset[int]:
    """The lines across a frame that things stand on (`across_labels`) and that run on
    through a vertex, with something standing off it there (a truss with a panel's strut on
    it). The runtime lets their pieces be as short as their class allows: they are the
    stretches between what stands on them, not a part's outline (`examples/space-station.gg`'s
    trusses have 240-500 px pieces, and at 0.4 of them each new piece needed 148 px where
    the class allows 40, so after 17 parts no stretch held another)."""
    across = across_labels(primitives, labels, classes)
    return frozenset(t >> 1 for p in primitives for t in p.ring
                     if t >> 1 in across and t ^ 1 in p.ring)


def _meeting(primitives, labels, classes) -> frozenset[int]:
    """The half-edges of lines, not border, at the border's vertices."""
    border = border_labels(labels, classes)
    return frozenset(t for k in border_primitives(primitives, border)
                     for t in primitives[k].ring if t >> 1 not in border)


def find_frame(ex) -> Frame | None:
    """The example's frame, or None when it has no border edges. A border that does not close
    into one loop is the user's error, located at one of its edges."""
    g = ex.graph
    border = border_labels(ex.labels, ex.classes)
    if g is None or not border:
        return None
    around: dict[int, list[int]] = {}
    for e, (label, _) in enumerate(ex.edge_label):
        if label in border:
            u, v = g.edges[e][:2]
            around.setdefault(u, []).append(e)
            around.setdefault(v, []).append(e)
    if not around:
        return None
    if all(len(es) <= 2 for es in around.values()) and any(len(es) == 1 for es in around.values()) \
            and not _has_loop(around, g.edges):
        return None      # open border lines only (a ground with no frame): no frame to start from
    for v, es in sorted(around.items()):
        if len(es) != 2:
            what = "ends in the air" if len(es) == 1 else f"branches ({len(es)} border edges meet)"
            raise _frame_error(ex, es[0], f"the border {what} at {_at(g.vertices[v])}",
                               "a frame is one closed loop of border edges; draw other lines "
                               "in a class without `border`")
    start = min(around)
    loop, prev, v = [start], None, start
    while True:
        e = next(e for e in around[v] if e != prev)
        u, w = g.edges[e][:2]
        v, prev = (w if u == v else u), e
        if v == start:
            break
        loop.append(v)
    if len(loop) != len(around):
        raise _frame_error(ex, around[min(set(around) - set(loop))][0],
                           "the border is more than one closed loop",
                           "an example has one frame; give other loops a class without `border`")
    rings = [ex.primitives[ex.vertex_primitive[v]].ring for v in loop]
    at = [v for v, ring in zip(loop, rings) if _turns(ring, ex.labels, border)]
    corners = tuple(Corner(ex.vertex_primitive[v], *map(float, g.vertices[v])) for v in at)
    frame = Frame(corners)
    bent = crooked_side(frame, ex.primitives, ex.labels)
    if bent is not None:
        raise _frame_error(ex, around[at[bent]][0], crooked_text(frame, bent),
                           "draw the frame's sides straight, and keep other points off them: "
                           "a point within the merge distance of a side is routed through it")
    outside = _outside(frame, g.vertices, ex.unit)
    if outside is not None:
        edge = next(e for e, ends in enumerate(g.edges) if outside in ends[:2])
        raise _frame_error(ex, edge, f"this lies outside the frame, at {_at(g.vertices[outside])}",
                           "the frame is the border of the space: draw the example inside it")
    return frame


def _outside(frame: Frame, points, unit: float) -> int | None:
    """The first point that lies outside `frame` by more than a millionth of the unit (on
    its sides is inside), or None."""
    tol = 1e-6 * unit
    x0, y0, x1, y1 = frame.box
    for v, (x, y) in enumerate(points):
        if not (x0 - tol <= x <= x1 + tol and y0 - tol <= y <= y1 + tol):
            return v
        if not frame.rectangle and not frame.contains(x, y) and not _on_sides(frame, x, y, tol):
            return v
    return None


def _on_sides(frame: Frame, x: float, y: float, tol: float) -> bool:
    cs = frame.corners
    n = len(cs)
    for k in range(n):
        a, b = cs[k], cs[(k + 1) % n]
        dx, dy = b.x - a.x, b.y - a.y
        t = max(0.0, min(1.0, ((x - a.x) * dx + (y - a.y) * dy) / (dx * dx + dy * dy or 1.0)))
        if math.hypot(a.x + t * dx - x, a.y + t * dy - y) <= tol:
            return True
    return False


def crooked_side(frame: Frame, primitives, labels) -> int | None:
    """The first side (corner k to corner k + 1) that leaves corner k in no direction of its
    half-edges (a side bent by a point routed through it, then snapped): generation could not
    place such a frame."""
    n = len(frame.corners)
    for k in range(n):
        a, b = frame.corners[k], frame.corners[(k + 1) % n]
        if slot_towards(primitives[a.prim].ring, labels, b.x - a.x, b.y - a.y) is None:
            return k
    return None


def crooked_text(frame: Frame, k: int) -> str:
    """What is wrong with side k that `crooked_side` found, for an error message."""
    a, b = frame.corners[k], frame.corners[(k + 1) % len(frame.corners)]
    return (f"the frame's side from {_at((a.x, a.y))} to {_at((b.x, b.y))} does not run along "
            "the direction its edges are labelled with")


def _has_loop(around: dict[int, list[int]], edges) -> bool:
    """Whether some component of the border graph is a cycle (all its vertices of degree 2)."""
    seen: set[int] = set()
    for start in around:
        if start in seen:
            continue
        stack, comp = [start], []
        seen.add(start)
        while stack:
            v = stack.pop()
            comp.append(v)
            for e in around[v]:
                for w in edges[e][:2]:
                    if w not in seen:
                        seen.add(w)
                        stack.append(w)
        if all(len(around[v]) == 2 for v in comp):
            return True
    return False


def _at(p) -> str:
    return f"({p[0]:g}, {p[1]:g})"


def _frame_error(ex, edge: int, message: str, hint: str):
    spans = ex.graph.spans
    span = spans[edge] if edge < len(spans) and spans[edge] is not None else Span(ex.path)
    return error(message, span, hint)
