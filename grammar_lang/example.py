"""The typed example: edge labels, primitives and their boundary strings (paper §3.3, §4.1).

This is the model the compiler infers from and the runtime checks against.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from . import boundary as bd
from .diagnostics import Diagnostic
from .source import Decoration, EdgeClass, ExampleGraph, Options


@dataclass(frozen=True)
class EdgeLabel:
    """ã = (left, right, θ, class). θ ∈ [0°, 180°) is the direction of half-edge `a`; left and
    right are the faces seen walking in that direction. A rigid label also fixes its length.
    `typical` is the median length of the example's edges of this label (None for an example
    given without geometry): the runtime draws new edges of this label around it, so that a
    structure grown in one move keeps the proportions of its parts."""

    name: str
    left: str
    right: str
    angle: float
    cls: str
    length: float | None = None
    typical: float | None = None

    def direction(self, bar: bool) -> float:
        """Direction in [-180°, 180°) of the half-edge `a` (bar=False) or `ā` (bar=True)."""
        return self.angle - 180.0 if bar else self.angle


@dataclass(frozen=True)
class Primitive:
    """One vertex type: its ring of half-edge tokens, counter-clockwise from the smallest angle."""

    name: str
    ring: bd.Tokens
    count: int = 1

    @property
    def boundary(self) -> bd.Tokens:
        return self.ring + (bd.UP,)


@dataclass(frozen=True)
class Example:
    name: str
    path: str
    exterior: str
    face_labels: tuple[str, ...]
    classes: tuple[EdgeClass, ...]        # resolved against `unit`
    labels: tuple[EdgeLabel, ...]
    primitives: tuple[Primitive, ...]
    options: Options
    unit: float
    decorations: tuple[Decoration, ...] = ()
    graph: ExampleGraph | None = None     # None when primitives were given directly
    vertex_primitive: tuple[int, ...] = ()   # primitive index of each graph vertex
    edge_label: tuple[tuple[int, bool], ...] = ()  # (label, walks u→v along `a`) per graph edge
    notes: tuple[Diagnostic, ...] = field(default=(), compare=False)

    @property
    def label_names(self) -> tuple[str, ...]:
        return tuple(l.name for l in self.labels)

    def cls(self, name: str) -> EdgeClass:
        for c in self.classes:
            if c.name == name:
                return c
        raise KeyError(name)

    def token_angle(self, token: int) -> float:
        return self.labels[bd.label_of(token)].direction(bd.is_bar(token))

    def format(self, tokens, ascii: bool = False) -> str:
        return bd.format_tokens(tokens, self.label_names, ascii)
