"""The kernel's canonical forms (grammar_lang.algorithms.canon) on the compiler's hierarchy
`Graph`s, and the split of a complete graph into such graphs, one per connected component."""

from __future__ import annotations

from typing import Sequence

from grammar_lang.algorithms import canon
from grammar_lang.algorithms.components import glued_parts

from .gluing import Edge, Graph

Key = canon.Key


def canonical_key(g: Graph, ring_len: Sequence[int]) -> Key:
    """Key of a connected graph; equal keys mean the same graph up to renumbering vertices."""
    return canon.canonical_key(g.verts, g.edges, ring_len, g.gaps)


def split(verts: Sequence[int], edges: Sequence[Edge]) -> list[Graph]:
    """The connected components of a complete (boundary-free) graph, each renumbered from 0."""
    return [Graph(labels, es, ()) for labels, es in glued_parts(verts, edges)]
