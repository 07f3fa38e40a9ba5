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

Slot = tuple[int, int]
# A boundary item is an open slot, or a turn (bd.UP / bd.DOWN).
Item = Slot | int


@dataclass(frozen=True)
class Side:
    """One side of a rule, or any graph of primitive instances with its boundary.

    `edges` holds each glued pair once as (v, i, w, j) with (v, i) < (w, j). `boundary` is the
    cyclic boundary walk; several components spliced together (paper §4.2, §5.3) are one walk
    whose turns say how they are spliced. The empty graph has boundary () and a complete graph
    (∧) has boundary (bd.UP,).
    """

    vertices: tuple[int, ...]
    edges: tuple[tuple[int, int, int, int], ...]
    boundary: tuple[Item, ...]
    names: tuple[str, ...] = ()       # optional vertex names from a rule file

    @property
    def is_empty(self) -> bool:
        return not self.vertices

    def open_slots(self) -> list[Slot]:
        return [it for it in self.boundary if isinstance(it, tuple)]

    def tokens(self, rings: Sequence[Sequence[int]]) -> bd.Tokens:
        """The boundary string, given each primitive's ring of half-edge tokens."""
        return tuple(it if isinstance(it, int) else rings[self.vertices[it[0]]][it[1]]
                     for it in self.boundary)

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
        parent = list(range(len(self.vertices)))

        def find(x: int) -> int:
            while parent[x] != x:
                parent[x] = parent[parent[x]]
                x = parent[x]
            return x

        for v, _, w, _ in self.edges:
            a, b = find(v), find(w)
            if a != b:
                parent[max(a, b)] = min(a, b)
        groups: dict[int, list[int]] = {}
        for v in range(len(self.vertices)):
            groups.setdefault(find(v), []).append(v)
        return [groups[k] for k in sorted(groups)]


EMPTY = Side((), (), ())
