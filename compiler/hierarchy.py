"""The concrete graph hierarchy (§4.3, §5.1): every graph once, with its fate.

Graphs are numbered in insertion order; complexity is (half-edges, insertion number), so a
graph with fewer half-edges is always simpler and ties go to the earlier one. Duplicates are
found by canonical form (companion §2): a graph reached again from another parent is the same
node and gains that parent.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

from .canon import Key, canonical_key
from .gluing import Graph

KEPT = "irreducible"        # in the hierarchy, expanded in the next generation
RULE = "rule"               # reduced by a rule of its own (its left side)
REDUCIBLE = "reducible"     # holds the left side of an earlier rule
PRUNED = "pruned"           # no complete irreducible descendants (§5.6)
OVER = "over-limit"         # beyond the half-edge limit (§5.7)


@dataclass
class Node:
    id: int
    graph: Graph
    gen: int
    status: str = KEPT
    parents: list[int] = field(default_factory=list)
    children: list[int] = field(default_factory=list)
    checked: int = -1        # matcher version when last tried as a left side

    @property
    def rank(self) -> tuple[int, int]:
        return (self.graph.n_half, self.id)


class Hierarchy:
    def __init__(self, ring_len: Sequence[int]):
        self.ring_len = list(ring_len)
        self.nodes: list[Node] = []
        self.index: dict[Key, int] = {}
        self.by_prim: dict[int, list[int]] = {}     # primitive → the graphs holding it

    def lookup_or_add(self, g: Graph, gen: int, parent: int | None) -> tuple[Node, bool]:
        key = canonical_key(g, self.ring_len)
        hit = self.index.get(key)
        if hit is not None:
            node = self.nodes[hit]
            if parent is not None and parent not in node.parents:
                node.parents.append(parent)
                self.nodes[parent].children.append(node.id)
            return node, False
        node = Node(len(self.nodes), g, gen)
        if parent is not None:
            node.parents.append(parent)
            self.nodes[parent].children.append(node.id)
        self.nodes.append(node)
        self.index[key] = node.id
        for p in g.prim_counts:
            self.by_prim.setdefault(p, []).append(node.id)
        return node, True

    def kept(self) -> list[Node]:
        return [n for n in self.nodes if n.status == KEPT]

    def count(self, status: str) -> int:
        return sum(1 for n in self.nodes if n.status == status)
