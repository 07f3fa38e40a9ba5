"""What the geometry sees of a rewriting step: the `Change` it places, and the host
(`HostView`) it places it in.

The geometry is the lower layer: the engine plans a change (runtime.engine.rewrite.plan), asks
the geometry where its vertices go, and commits it. So the geometry names the engine's host
only through `HostView`, the members it reads and writes, which runtime.engine.host.Host has.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from grammar_lang.frame import Frame
from grammar_lang.graph import Slot
from grammar_lang.rules import Header

from .spatial import Grid, Point
from .tables import Tables


class HostView(Protocol):
    """The host drawing as the geometry uses it (runtime.engine.host.Host is one)."""

    header: Header
    t: Tables
    prim: dict[int, int]                    # vertex → its primitive
    pos: dict[int, Point]
    link: dict[int, list[Slot | None]]      # vertex → what each slot is glued to
    by_prim: list[list[int]]                # primitive → its vertices
    grid: Grid
    # A scene's frame (runtime.geometry.framing sets these).
    pinned: frozenset[int]
    frame: Frame | None
    on_border: frozenset[int]
    border_labels: frozenset[int]
    side_labels: frozenset[int]
    unsized_sides: frozenset[int]           # side_labels but the gaps (Tables.gaps)
    frame_face: str | None

    def __len__(self) -> int: ...

    def new_id(self) -> int: ...

    def add_vertex(self, v: int, prim: int, p: Point) -> None: ...

    def glue(self, a: Slot, b: Slot) -> None: ...


@dataclass(frozen=True)
class Change:
    """What a rule application removes, adds and glues, before positions are known."""

    rule: object        # the engine's DirectedRule and Match; None for a side placed alone
    match: object
    removed: tuple[int, ...]
    new: tuple[tuple[int, int], ...]          # (host id, primitive)
    glue: tuple[tuple[Slot, Slot], ...]       # edges to create, host slots
    cut: tuple[Slot, ...]                     # host edges matched by wires, to unglue
    partner: dict                             # slot → partner after the change, where changed

    def partner_after(self, host: HostView, v: int, i: int) -> Slot | None:
        s = self.partner.get((v, i), 0)
        return host.link[v][i] if s == 0 else s

    def adjacency(self, host: HostView, v: int, prim: int) -> list[tuple[int, Slot]]:
        """(slot, partner) of every glued slot of v after the change."""
        out = []
        for i in range(len(host.t.rings[prim])):
            s = self.partner_after(host, v, i)
            if s is not None:
                out.append((i, s))
        return out
