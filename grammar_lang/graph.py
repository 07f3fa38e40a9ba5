"""Graphs built from primitives, the shape shared by hierarchy graphs, rule sides and drawings.

A vertex is an instance of a primitive. A primitive fixes the vertex's ring of half-edges
(its rotation system), so a graph is only: the primitive of each vertex, which half-edge slots
are glued into edges, and, for a graph with open half-edges, the boundary string that walks its
open slots counter-clockwise with the turns between them (paper §3.3). A slot is `(vertex,
index in the primitive's ring)`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

from . import boundary as bd
from .algorithms.components import glued_components

Slot = tuple[int, int]
# A boundary item is an open slot, or a turn (bd.UP / bd.DOWN): the string form of
# grammar_lang.boundary, over slots.
Item = Slot | int


@dataclass(frozen=True)
class Side:
    """One side of a rule, or any graph of primitive instances with its boundary.

    `edges` holds each glued pair once as (v, i, w, j) with (v, i) < (w, j). `boundary` is the
    cyclic boundary walk in string form (`tokens` reads it through the rings); several components spliced together (paper §4.2, §5.3) are one walk
    whose turns say how they are spliced. The empty graph has boundary () and a complete graph
    (∧) has boundary (bd.UP,).

    `wires` are bare edges with no vertex (the edge graphs `ā a ∧` of §4.3, generation 0), which
    a rule's simpler side may hold: wire `e` joins its two ends, written as the boundary items
    `(-1 - e, 0)`, carrying the token `wires[e]` (unbarred `a`), and `(-1 - e, 1)`, carrying
    `ā`. Replacing a left side by such a right side glues together whatever was attached at
    the two ends.
    """

    vertices: tuple[int, ...]
    edges: tuple[tuple[int, int, int, int], ...]
    boundary: tuple[Item, ...]
    names: tuple[str, ...] = ()       # optional vertex names from a rule file
    wires: tuple[int, ...] = ()       # bare edges: the unbarred token of each

    @property
    def is_empty(self) -> bool:
        return not self.vertices and not self.wires

    def open_slots(self) -> list[Slot]:
        return [it for it in self.boundary if isinstance(it, tuple)]

    def tokens(self, rings: Sequence[Sequence[int]]) -> bd.Tokens:
        """The boundary string, given each primitive's ring of half-edge tokens."""
        return tuple(it if isinstance(it, int) else self.slot_token(it, rings)
                     for it in self.boundary)

    def slot_token(self, slot: Slot, rings: Sequence[Sequence[int]]) -> int:
        v, i = slot
        if v < 0:
            return self.wires[-1 - v] ^ i
        return rings[self.vertices[v]][i]

    def vertex_name(self, v: int) -> str:
        return self.names[v] if self.names else f"v{v}"

    def partner(self) -> dict[Slot, Slot]:
        """Glued slot → the slot it is glued to, both ways."""
        out: dict[Slot, Slot] = {}
        for v, i, w, j in self.edges:
            out[(v, i)] = (w, j)
            out[(w, j)] = (v, i)
        return out

    def components(self) -> list[list[int]]:
        """Vertex sets of the connected components, in order of their smallest vertex."""
        return glued_components(range(len(self.vertices)), self.edges)


EMPTY = Side((), (), ())


def face_walk(side: Side, start: Slot, rings: Sequence[Sequence[int]]) -> list[tuple[Slot, int]]:
    """The open slots met walking around the face that leaves through open slot `start`.

    Returns the walk in gap form, (open slot, net turns after it) pairs from `start` on,
    following the rotation system: at a vertex the walk goes counter-clockwise to the next slot
    of the ring (a ∧ when it wraps past the last); crossing an edge from a barred half-edge is a
    ∨. A wire (bare edge) is walked as its generation-0 string ā a ∧. Raises ValueError if
    `start` is not open.
    """
    if start[0] < 0:
        bar, a = (start[0], 1), (start[0], 0)
        walk = [(bar, 0), (a, 1)]
        return walk if start == bar else walk[::-1]
    partner = side.partner()
    if start in partner:
        raise ValueError(f"slot {start} is glued, not open")
    out: list[list] = [[start, 0]]
    v, i = start
    for _ in range(sum(len(rings[p]) for p in side.vertices) + 1):
        k = len(rings[side.vertices[v]])
        out[-1][1] += 1 if i == k - 1 else 0
        i = (i + 1) % k
        while (v, i) in partner:
            out[-1][1] -= 1 if bd.is_bar(rings[side.vertices[v]][i]) else 0
            v, i = partner[(v, i)]
            k = len(rings[side.vertices[v]])
            out[-1][1] += 1 if i == k - 1 else 0
            i = (i + 1) % k
        if (v, i) == start:
            return [(s, n) for s, n in out]
        out.append([(v, i), 0])
    raise ValueError("the face walk did not close")
