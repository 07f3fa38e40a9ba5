"""The typed example: its vocabulary (grammar_lang.vocabulary: edge labels, primitives and
their boundary strings, paper §3.3, §4.1), options, decorations and the drawing they type.

This is the model the compiler infers from and the runtime checks against.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .diagnostics import Diagnostic
from .source import Decoration, ExampleGraph, Options
from .vocabulary import Vocabular, Vocabulary


@dataclass(frozen=True)
class Example(Vocabular):
    name: str
    path: str
    vocabulary: Vocabulary
    options: Options
    decorations: tuple[Decoration, ...] = ()
    graph: ExampleGraph | None = None     # None when primitives were given directly
    vertex_primitive: tuple[int, ...] = ()   # primitive index of each graph vertex
    edge_label: tuple[tuple[int, bool], ...] = ()  # (label, walks u→v along `a`) per graph edge
    notes: tuple[Diagnostic, ...] = field(default=(), compare=False)
