"""What the front ends (`.gg` parser, SVG importer) hand to the shape model.

An `ExampleSource` is a description, not yet a graph: painted regions and lines in drawing
order, explicit edges, or primitives given directly, plus edge classes, options and
decorations. `planar.build_planar_graph` turns its geometry into an `ExampleGraph`, and
`labelling.label_example` turns that into the typed `Example` (labels, primitives, boundaries).
All coordinates are in the y-up frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .diagnostics import Span

Point = tuple[float, float]

EXTERIOR = "exterior"
DEFAULT_CLASS = "0"
# Beyond this, squared lengths lose every digit the geometry needs: not a drawing. Every front
# end (SVG import, the shape model, free-form rules) refuses coordinates past it.
MAX_COORDINATE = 1e12


@dataclass(frozen=True)
class EdgeClass:
    """Length constraints of a class of edges, in drawing units.

    `None` for min/max means "the default", resolved against the example's unit (its median edge
    length) by `resolved()`. `fixed` pins every length; `tile` requires whole multiples of it;
    `rigid` keeps the exact vector the edge has in the example (and makes each such edge its own
    label).
    """

    name: str
    min_length: float | None = None
    max_length: float | None = None
    fixed: float | None = None
    tile: float | None = None
    rigid: bool = False
    border: bool = False
    span: Span | None = field(default=None, compare=False)

    # Defaults in units of the example's median edge length; the original tool used 0.1-4 grid
    # units, which is the same spirit (scale-free) without its fixed 40 px grid.
    DEFAULT_MIN = 0.1
    DEFAULT_MAX = 4.0

    def __post_init__(self):
        # A border class has no longest length unless the user gives one: its edges are the
        # border of the space, as long as the extent asked for (`ggrun --extent`), and the
        # stretches of ground between structures are as long as the room left. Bounded by
        # the example's longest, a frame wider than the example's had a side the verifier
        # refused, and the village's start could not be placed at the paper's extent.
        # Written here, the class reads the same from a `.gg`, a `.ggr` (which leaves an
        # infinite max out) and code.
        if self.border and self.max_length is None:
            object.__setattr__(self, "max_length", math.inf)

    def resolved(self, unit: float, seen: tuple[float, float] | None = None) -> "EdgeClass":
        """Concrete limits. They also admit `seen`, the shortest and longest edges of this
        class in the example, so the example itself is always a valid drawing: a structure
        copied from it (a starter) can always be placed. `labelling` notes where the example
        widened a limit the user gave."""
        lo = self.min_length if self.min_length is not None else self.DEFAULT_MIN * unit
        hi = self.max_length if self.max_length is not None else self.DEFAULT_MAX * unit
        if seen is not None:
            lo, hi = min(lo, seen[0]), max(hi, seen[1])
        return EdgeClass(self.name, lo, hi, self.fixed, self.tile, self.rigid, self.border, self.span)


@dataclass(frozen=True)
class Limits:
    """Bounds on the concrete hierarchy (paper §5.7).

    They count work, so that a compile gives the same rules on any machine under any load; a
    time limit (`seconds`) is there only when the user asks for one. 1000 graphs is about the
    paper's Castle hierarchy (1,030) and about what 2 s of this compiler met before.
    """

    generations: int = 12
    half_edges: int = 12
    graphs: int = 1000
    seconds: float | None = None


@dataclass(frozen=True)
class Options:
    angle_tolerance: float = 10.0     # degrees; directions closer than this are one label
    snap_angle: float = 15.0          # degrees; cluster directions snap to multiples of this (0: off)
    merge_distance: float | None = None   # drawing units; None: 0.5 % of the drawing's diagonal
    unit: float | None = None         # drawing units; None: the example's median edge length
    connected: bool = False           # Appendix A: one component, no multi-graph splices
    no_loops: bool = False            # Appendix A: trees and streams
    limits: Limits = Limits()


@dataclass(frozen=True)
class Region:
    """A filled shape. Later regions paint over earlier ones. Rings are closed implicitly."""

    rings: tuple[tuple[Point, ...], ...]
    label: str
    evenodd: bool = False
    span: Span | None = field(default=None, compare=False)


@dataclass(frozen=True)
class Stroke:
    """A line drawn over the regions: its surrounding face lies on both sides of it."""

    points: tuple[Point, ...]
    closed: bool = False
    cls: str = DEFAULT_CLASS
    span: Span | None = field(default=None, compare=False)


@dataclass(frozen=True)
class ExplicitEdge:
    """An edge with its face labels stated, walking from p to q."""

    p: Point
    q: Point
    left: str
    right: str
    cls: str = DEFAULT_CLASS
    span: Span | None = field(default=None, compare=False)


@dataclass(frozen=True)
class HalfEdgeSpec:
    angle: float                      # degrees, direction pointing away from the vertex
    left: str
    right: str
    cls: str = DEFAULT_CLASS


@dataclass(frozen=True)
class PrimitiveSpec:
    """A primitive given directly (paper Fig. 8): one vertex and its ring of half-edges."""

    half_edges: tuple[HalfEdgeSpec, ...]
    name: str | None = None
    span: Span | None = field(default=None, compare=False)


@dataclass(frozen=True)
class Decoration:
    """A decoration directive (paper Appendix B), validated by the parser, drawn by the runtime.

    `kind` is 'face', 'edge' or 'vertex'; `target` a face label, edge class or primitive name
    ('*' for all); `props` maps property names to strings or numbers.
    """

    kind: str
    target: str
    props: tuple[tuple[str, object], ...]
    span: Span | None = field(default=None, compare=False)


# The decoration property that colours a face label or an edge class.
COLOUR_PROPERTY = {"face": "fill", "edge": "stroke"}

Paint = Region | Stroke | ExplicitEdge


@dataclass
class ExampleSource:
    path: str
    name: str
    exterior: str = EXTERIOR
    face_labels: dict[str, Span | None] = field(default_factory=dict)
    paint: list[Paint] = field(default_factory=list)
    primitives: list[PrimitiveSpec] = field(default_factory=list)
    classes: dict[str, EdgeClass] = field(default_factory=dict)
    options: Options = Options()
    decorations: list[Decoration] = field(default_factory=list)
    text: str | None = None           # the source text, for caret excerpts


@dataclass(frozen=True)
class ExampleGraph:
    """A planar straight-line graph with labelled sides: the corpus JSON's shape.

    `edges[i] = (u, v, left, right, cls)`, left/right seen walking from u to v. `spans[i]` tells
    where edge i came from, for diagnostics.
    """

    vertices: tuple[Point, ...]
    edges: tuple[tuple[int, int, str, str, str], ...]
    spans: tuple[Span | None, ...] = ()
