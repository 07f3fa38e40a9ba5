"""The vocabulary a drawing is written in: the edge labels, the primitives (vertex types) made
of them, the face labels, the edge classes and the unit of length (paper §3.3, §4.1).

One value, `Vocabulary`, that the example (grammar_lang.example), the grammar's header
(grammar_lang.rules), the verifier's reference and the runtime's tables all embed; `Vocabular`
lets each of them read its fields directly (`ex.labels` is `ex.vocabulary.labels`).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

from . import boundary as bd
from .source import EdgeClass


@dataclass(frozen=True)
class EdgeLabel:
    """ã = (left, right, θ, class). θ ∈ [0°, 180°) is the direction of half-edge `a`; left and
    right are the faces seen walking in that direction. A rigid label also fixes its length.
    `typical` is the median length of the example's edges of this label (None for an example
    given without geometry): the runtime draws new edges of this label around it, so that a
    structure grown in one move keeps the proportions of its parts. `shortest` is the
    example's shortest edge of this label: new edges may be as short (see Tables.least)."""

    name: str
    left: str
    right: str
    angle: float
    cls: str
    length: float | None = None
    typical: float | None = None
    shortest: float | None = None

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
class Vocabulary:
    exterior: str = "exterior"
    face_labels: tuple[str, ...] = ()
    classes: tuple[EdgeClass, ...] = ()            # resolved against `unit` in an example
    labels: tuple[EdgeLabel, ...] = ()
    primitives: tuple[Primitive, ...] = ()
    unit: float = 1.0

    @functools.cached_property
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


class Vocabular:
    """For a dataclass with a `vocabulary` field: its fields and methods, read through."""

    vocabulary: Vocabulary

    exterior = property(lambda self: self.vocabulary.exterior)
    face_labels = property(lambda self: self.vocabulary.face_labels)
    classes = property(lambda self: self.vocabulary.classes)
    labels = property(lambda self: self.vocabulary.labels)
    primitives = property(lambda self: self.vocabulary.primitives)
    unit = property(lambda self: self.vocabulary.unit)
    label_names = property(lambda self: self.vocabulary.label_names)

    def cls(self, name: str) -> EdgeClass:
        return self.vocabulary.cls(name)

    def token_angle(self, token: int) -> float:
        return self.vocabulary.token_angle(token)

    def format(self, tokens, ascii: bool = False) -> str:
        return self.vocabulary.format(tokens, ascii)
