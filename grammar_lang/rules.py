"""Grammars: DPO rules over primitive graphs, with the example's header.

A rule's sides have equal boundary strings, matched position by position: the i-th open slot
of `lhs.boundary` and of `rhs.boundary` are the same interface point. Applying a rule
destructively replaces a match of `lhs` by `rhs`; constructively, `rhs` by `lhs` (paper §5.2).
By convention `rhs` is the simpler side. A starter rule has an empty `rhs` and a complete `lhs`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .diagnostics import Span
from .frame import Frame
from .free_rules import AttrDecl, Production
from .graph import Side
from .source import Decoration, Options
from .vocabulary import Vocabular, Vocabulary


@dataclass(frozen=True)
class Rule:
    name: str
    lhs: Side
    rhs: Side
    priority: int = 0
    weight: float = 1.0
    span: Span | None = field(default=None, compare=False)

    @property
    def is_starter(self) -> bool:
        return self.rhs.is_empty


@dataclass(frozen=True)
class Header(Vocabular):
    """What a rule file records about the example it was compiled from: its vocabulary (read
    through, as `header.labels`), options and decorations, and how the rules were made."""

    source: str = ""
    source_hash: str = ""
    compiler_version: str = ""
    vocabulary: Vocabulary = Vocabulary()
    options: Options = Options()
    decorations: tuple[Decoration, ...] = ()
    mode: str = "dpo"                 # 'dpo', or 'spo' (dangling edges are deleted)
    complete: bool | None = None      # None: not known (hand-written)
    frame: Frame | None = None        # the border of the space; generation starts from it
    # Hand-written productions (free_rules): their labels and declared attributes.
    vertex_labels: tuple[str, ...] = ()
    edge_labels: tuple[str, ...] = ()
    attributes: tuple[AttrDecl, ...] = ()


@dataclass(frozen=True)
class Grammar:
    header: Header
    rules: tuple[Rule, ...]
    productions: tuple[Production, ...] = ()
    start: Production | None = None     # the host graph a run of productions starts from

    @property
    def is_free(self) -> bool:
        """Whether this grammar holds hand-written productions (run by runtime.engine.free_engine)."""
        return bool(self.productions) or self.start is not None

    @property
    def rings(self):
        return [p.ring for p in self.header.primitives]
