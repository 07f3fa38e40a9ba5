"""The `.gg` syntax tree: what one file says, before names are resolved across imports.

`gg_parser` builds these from the lark tree; `gg_resolve` checks them and turns a file and its
imports into an `ExampleSource`. Every node keeps the `Span` it came from, for diagnostics.
"""

from __future__ import annotations

from dataclasses import dataclass

from .diagnostics import Span


@dataclass(frozen=True)
class Num:
    value: float
    unit: str            # '' when the number has no unit suffix
    text: str
    span: Span


@dataclass(frozen=True)
class Word:
    """A name, string, colour or bare number used as a name (e.g. class `0`).

    `kind` is 'name', 'string', 'colour', 'number' or 'star'; `text` is the decoded value.
    """

    text: str
    kind: str
    span: Span


Value = Num | Word


@dataclass(frozen=True)
class XY:
    x: Num
    y: Num
    span: Span


@dataclass(frozen=True)
class Ref:
    name: str
    span: Span


Pt = XY | Ref


@dataclass(frozen=True)
class Ring:
    points: tuple[Pt, ...]
    rect: bool           # True: two opposite corners of an axis-aligned rectangle
    span: Span


@dataclass(frozen=True)
class Prop:
    key: str
    value: Value | None  # None for a bare flag such as `rigid`
    span: Span


@dataclass(frozen=True)
class Side:
    kind: str            # 'left', 'right' or 'class'
    word: Word
    span: Span


# ---- statements -------------------------------------------------------------------------------

@dataclass(frozen=True)
class ExampleName:
    name: str
    span: Span


@dataclass(frozen=True)
class Import:
    target: str
    span: Span


@dataclass(frozen=True)
class Exterior:
    label: Word
    span: Span


@dataclass(frozen=True)
class Face:
    label: Word
    colour: Word | None
    props: tuple[Prop, ...]
    span: Span


@dataclass(frozen=True)
class ColourDef:
    name: str
    colour: Word
    span: Span


@dataclass(frozen=True)
class ClassDef:
    name: Word
    props: tuple[Prop, ...]
    span: Span


@dataclass(frozen=True)
class Settings:
    """An `options { }` or `limits { }` block."""

    block: str
    props: tuple[Prop, ...]
    span: Span


@dataclass(frozen=True)
class PointDef:
    name: str
    at: Pt
    span: Span


@dataclass(frozen=True)
class Polygon:
    label: Word
    outer: Ring
    holes: tuple[Ring, ...]
    cls: Word | None
    span: Span


@dataclass(frozen=True)
class Polyline:
    ring: Ring
    closed: bool
    border: bool         # `border`: a closed line of a border class (paper Appendix A)
    cls: Word | None
    span: Span


@dataclass(frozen=True)
class Edge:
    points: tuple[Pt, ...]
    sides: tuple[Side, ...]
    span: Span


@dataclass(frozen=True)
class HalfEdge:
    angle: Num
    sides: tuple[Side, ...]
    span: Span


@dataclass(frozen=True)
class PrimitiveDef:
    name: str | None
    half_edges: tuple[HalfEdge, ...]
    span: Span


@dataclass(frozen=True)
class Decorate:
    kind: Word
    target: Word
    props: tuple[Prop, ...]
    span: Span


@dataclass(frozen=True)
class ShapeFrom:
    path: str
    span: Span


@dataclass(frozen=True)
class Rename:
    """`rename OLD -> NEW`: a face label or class of the drawings taken with `shape from`."""

    old: Word
    new: Word
    span: Span


Stmt = (ExampleName | Import | Exterior | Face | ColourDef | ClassDef | Settings | PointDef
        | Polygon | Polyline | Edge | PrimitiveDef | Decorate | ShapeFrom | Rename)
