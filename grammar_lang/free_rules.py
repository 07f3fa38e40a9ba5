"""Hand-written productions over attributed graphs (Pogrzebacz & Ilčík, seed 001).

A `Production` is the seed's (M, {(p, D, w)}): a mother graph `lhs` with conditions, and
weighted daughters. Elements are vertices, edges and faces with labels and attributes; the
morphism p is by name: a vertex of `lhs` that a daughter lists again (by its bare name) is kept,
an lhs edge or face is kept when the daughter has one on the same vertices, and everything else
of `lhs` is deleted. Wildcard vertices (label None) match any vertex and are always kept.

Positions are the vertex attributes `x` and `y`. A daughter's new vertex gets its position
from a `set` line, or else from its pattern position (`p: pt (0.5, 0.3)`) carried onto the
match by the similarity that takes the mother's pattern onto the matched vertices (§4.3).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .diagnostics import Span
from .expr_ast import Expr, Type

KINDS = ("vertex", "edge", "face")
# Values every element has, kept by the runtime; only `x`, `y` (and `pos`) may be set.
DERIVED: dict[str, dict[str, Type]] = {
    "vertex": {"x": Type.NUM, "y": Type.NUM, "pos": Type.VEC, "degree": Type.NUM,
               "generation": Type.NUM, "label": Type.STR},
    "edge": {"length": Type.NUM, "angle": Type.NUM, "vec": Type.VEC, "mid": Type.VEC,
             "generation": Type.NUM, "label": Type.STR},
    "face": {"centre": Type.VEC, "area": Type.NUM, "sides": Type.NUM, "generation": Type.NUM,
             "label": Type.STR},
}
SETTABLE_DERIVED = {"vertex": {"x", "y", "pos"}, "edge": set(), "face": set()}
MATCH_CHOICES = ("random", "oldest")


@dataclass(frozen=True)
class AttrDecl:
    """`attribute KIND NAME = VALUE`: an attribute every element of that kind has."""

    kind: str
    name: str
    type: Type
    default: Expr
    value: object = field(compare=False)     # the default, evaluated once at load


@dataclass(frozen=True)
class FVertex:
    name: str
    label: str | None               # None: a wildcard (lhs only)
    pattern: tuple[float, float] | None = None
    kept: bool = False              # in a daughter: named again from the lhs


@dataclass(frozen=True)
class FEdge:
    name: str | None
    u: str
    v: str
    label: str | None               # None: any label (lhs only)
    directed: bool


@dataclass(frozen=True)
class FFace:
    name: str | None
    label: str | None
    cycle: tuple[str, ...]


@dataclass(frozen=True)
class FSide:
    vertices: tuple[FVertex, ...] = ()
    edges: tuple[FEdge, ...] = ()
    faces: tuple[FFace, ...] = ()

    def vertex(self, name: str) -> FVertex | None:
        return next((v for v in self.vertices if v.name == name), None)


@dataclass(frozen=True)
class Let:
    name: str
    expr: Expr
    type: Type
    span: Span | None = field(default=None, compare=False)


@dataclass(frozen=True)
class Assign:
    """`set ELEMENT.KEY = EXPR` on a daughter's element."""

    element: str
    key: str
    expr: Expr
    span: Span | None = field(default=None, compare=False)


@dataclass(frozen=True)
class Condition:
    expr: Expr
    span: Span | None = field(default=None, compare=False)


@dataclass(frozen=True)
class Daughter:
    side: FSide
    weight: float = 1.0
    lets: tuple[Let, ...] = ()
    sets: tuple[Assign, ...] = ()


@dataclass(frozen=True)
class Production:
    name: str
    lhs: FSide
    daughters: tuple[Daughter, ...]
    conditions: tuple[Condition, ...] = ()
    lets: tuple[Let, ...] = ()              # shared by all daughters, before them
    priority: int = 0
    weight: float = 1.0
    match: str = "random"                   # or 'oldest': breadth-first by generation
    spatial: bool = False                   # matched vertices keep the lhs's x/y order
    span: Span | None = field(default=None, compare=False)

    @property
    def is_start(self) -> bool:
        return not self.lhs.vertices and not self.lhs.edges and not self.lhs.faces
