"""Semantic checks of `.gg` definitions that need no name lookup: edge-class length rules and
the consistency of primitives given directly (paper Fig. 8)."""

from __future__ import annotations

from .diagnostics import Span, error
from .source import EdgeClass, HalfEdgeSpec, PrimitiveSpec

ANGLE_EPS = 1e-6


def edge_class(name: str, v: dict, spans: dict[str, Span], span: Span,
               source: str | None) -> EdgeClass:
    """An `EdgeClass` from validated `class { }` properties, rejecting contradictions."""

    def fail(msg, key, hint):
        raise error(msg, spans.get(key, span), hint, source=source)

    lo, hi, fixed, tile = v.get("min"), v.get("max"), v.get("fixed"), v.get("tile")
    rigid = bool(v.get("rigid", False))
    if lo is not None and hi is not None and lo > hi:
        fail(f"min {lo:g} is larger than max {hi:g}", "min", "swap them")
    if fixed is not None:
        if rigid:
            fail("a rigid edge keeps its drawn length, so 'fixed' contradicts it", "fixed",
                 "remove 'fixed' or 'rigid'")
        if (lo is not None and fixed < lo) or (hi is not None and fixed > hi):
            fail(f"fixed length {fixed:g} is outside min…max", "fixed",
                 "widen the range or drop min/max (fixed is enough)")
        if tile is not None and abs(fixed / tile - round(fixed / tile)) > 1e-9:
            fail(f"fixed length {fixed:g} is not a multiple of tile {tile:g}", "fixed",
                 "make fixed a whole multiple of tile")
    if tile is not None:
        if rigid:
            fail("a rigid edge keeps its drawn length, so 'tile' contradicts it", "tile",
                 "remove 'tile' or 'rigid'")
        if hi is not None and tile > hi:
            fail(f"tile {tile:g} is longer than max {hi:g}: no length would fit", "tile",
                 "make max at least one tile")
    return EdgeClass(name, lo, hi, fixed, tile, rigid, bool(v.get("border", False)), span=span)


def vertex_ring(halves: list[tuple[HalfEdgeSpec, Span]], source: str | None) -> None:
    """One direction per half-edge, and faces that agree between neighbours: going
    counter-clockwise, each half-edge's left face is the next one's right face.
    `halves` must be sorted by angle."""
    for (a, _), (b, span) in zip(halves, halves[1:]):
        if abs(a.angle - b.angle) < ANGLE_EPS:
            raise error(f"two half-edges point the same way ({a.angle:g}°)", span,
                        "each direction can leave a vertex only once", source=source)
    for i, (a, span_a) in enumerate(halves):
        b, span_b = halves[(i + 1) % len(halves)]
        if a.left != b.right:
            between = (f"between the half-edges at {a.angle:g}° and {b.angle:g}°"
                       if len(halves) > 1 else f"around the half-edge at {a.angle:g}°")
            raise error(f"the face {between} is '{a.left}' on one side and '{b.right}' on the "
                        "other", span_b if len(halves) > 1 else span_a,
                        "going counter-clockwise, each half-edge's left face must be the next "
                        "half-edge's right face", source=source)


def _angle_key(angle: float) -> int:
    return round(((angle + 180.0) % 360.0 - 180.0) / ANGLE_EPS) % round(360.0 / ANGLE_EPS)


def partners(prims: list[tuple[PrimitiveSpec, str | None]]) -> None:
    """Every half-edge needs a partner to glue to (opposite direction, sides swapped, same
    class), or no shape containing its primitive can ever be completed."""
    have = {(_angle_key(h.angle), h.left, h.right, h.cls)
            for p, _ in prims for h in p.half_edges}
    for spec, source in prims:
        for h in spec.half_edges:
            want = (h.angle + 360.0) % 360.0 - 180.0
            if (_angle_key(want), h.right, h.left, h.cls) not in have:
                raise error(f"the half-edge at {h.angle:g}° ({h.left} | {h.right}, class "
                            f"{h.cls}) has no partner", spec.span,
                            f"some primitive needs a half-edge at {want:g}° with left "
                            f"'{h.right}' and right '{h.left}' and the same class, or no shape "
                            "can ever be completed", source=source)
