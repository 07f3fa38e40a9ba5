"""A ground line without a frame is closed into one (paper Appendix A).

The paper models a line that does not end, such as the ground, as a line that meets the
border of the space; the space needs a border for that. An example that draws a straight
ground in a border class but no frame (`examples/castle.gg`, `platform.gg`) gets one here,
before its drawing becomes a graph: a rectangle whose bottom side runs along the ground, on
the side of the ground where the example's shapes stand. It is `GROUND_WIDTHS` times as wide as
the drawn ground, centred on it (its bottom side replaces the ground line), and
`GROUND_HEIGHTS` times as tall as the tallest shape, so
generation has room for several structures side by side, and the ground's ends are no longer
ends: they run on to the frame's sides. From then on the example is a framed scene like the
paper's (see `frame`), so structures stand on the ground and nothing grows below it.

A border that is not one straight line (steps in the ground, several grounds at different
heights) cannot be a frame's side; it is left as drawn, the example is unframed, and
`ground_note` says so.
"""

from __future__ import annotations

from dataclasses import replace

from .diagnostics import Diagnostic
from .source import ExampleSource, ExplicitEdge, Region, Stroke

GROUND_WIDTHS = 4.0      # the frame's width over the drawn ground's length
GROUND_HEIGHTS = 2.0     # the frame's height over the tallest shape standing on the ground
FLAT = 1e-9              # relative: how far from level a ground may be


def close_ground(source: ExampleSource) -> ExampleSource:
    """The source with a frame added around its ground line, or unchanged when it has a frame
    already, no border at all, or a border that is not one level line."""
    ground, rest = _split(source)
    if not _level(ground):
        return source
    pts = [p for item in ground for p in _points(item)]
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    length = max(xs) - min(xs)
    y = ys[0]
    above, below = _heights(rest, y)
    up = above >= below
    height = GROUND_HEIGHTS * (above if up else below) or length / GROUND_WIDTHS
    mid, half = (max(xs) + min(xs)) / 2, GROUND_WIDTHS * length / 2
    top = y + height if up else y - height
    first = ground[0]
    frame = Stroke(((mid - half, y), (mid - half, top), (mid + half, top), (mid + half, y)),
                   closed=True, cls=first.cls, span=first.span)
    # The frame's bottom side is the ground: drawn once, so the ground's old ends do not stay
    # behind as vertices in the middle of a side.
    return replace(source, paint=rest + [frame],
                   options=_keep_merge_distance(source, pts))


def ground_note(source: ExampleSource) -> Diagnostic | None:
    """A warning when the example's border lines end in the air and cannot be closed into a
    frame (they are not one level line): generation then has no ground to stand things on,
    and the run goes on unframed (ggrun says so as well as ggc)."""
    ground, _ = _split(source)
    if not ground or _level(ground):
        return None
    return Diagnostic("this border line ends in the air and is not one level line, so it "
                      "cannot be closed into a frame: the example is unframed",
                      ground[0].span, "draw the frame around the example: "
                      "`border rect (x0, y0) (x1, y1) class C`, or make the ground level",
                      severity="warning", source=source.text)


def _split(source: ExampleSource):
    """The open border lines (empty when a closed border, a frame, is drawn), and the rest."""
    border = {name for name, c in source.classes.items() if c.border}
    ground, rest = [], []
    for item in source.paint:
        if getattr(item, "cls", None) in border and not isinstance(item, Region):
            if isinstance(item, Stroke) and item.closed:
                return [], source.paint                 # a frame is drawn already
            ground.append(item)
        else:
            rest.append(item)
    if ground and not _open_ends(ground):
        return [], source.paint                         # a frame drawn in pieces (SVG)
    return ground, rest


def _open_ends(ground) -> bool:
    """Whether some end of the border's pieces is an end of no other piece (a piece drawn
    from a side's middle, a T, counts as open too: the frame finder judges those)."""
    ends: dict[tuple[float, float], int] = {}
    for item in ground:
        pts = _points(item)
        for p in (pts[0], pts[-1]):
            key = (round(p[0], 6), round(p[1], 6))
            ends[key] = ends.get(key, 0) + 1
    return any(n % 2 for n in ends.values())


def _level(ground) -> bool:
    """Whether the border lines lie on one horizontal line of some length."""
    if not ground:
        return False
    pts = [p for item in ground for p in _points(item)]
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    length = max(xs) - min(xs)
    return length > 0 and max(ys) - min(ys) <= FLAT * length


def _points(item) -> list[tuple[float, float]]:
    if isinstance(item, Stroke):
        return list(item.points)
    if isinstance(item, ExplicitEdge):
        return [item.p, item.q]
    return [p for ring in item.rings for p in ring]


def _heights(rest, y: float) -> tuple[float, float]:
    """How far the example's other shapes reach above and below the ground's level."""
    above = below = 0.0
    for item in rest:
        for p in _points(item):
            above, below = max(above, p[1] - y), max(below, y - p[1])
    return above, below


def _keep_merge_distance(source: ExampleSource, ground_points):
    """The default merge distance is a fraction of the drawing's size, which the frame makes
    several times larger: fix it at what the drawing as drawn gives, so points of a shape that
    were apart stay apart."""
    if source.options.merge_distance is not None:
        return source.options
    import numpy as np
    from .planar import merge_distance
    pts = [p for item in source.paint for p in _points(item)] or ground_points
    return replace(source.options, merge_distance=merge_distance(source, np.asarray(pts)))
