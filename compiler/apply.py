"""Applying a rule destructively (L → R) to a graph, for `ggc verify` (§5.2, Fig. 7).

The i-th open slot of L and of R are the same interface point. Cutting L out leaves, at each
interface point, whatever L's slot was glued to: a slot of the context, or another of L's own
open slots (an edge between two interface points). R is glued in by joining each interface
point's R end to that. R's bare edges (wires) join their two interface points straight through.
The chains so formed are the kernel's (grammar_lang.algorithms.dpo).
"""

from __future__ import annotations

from grammar_lang import boundary as bd
from grammar_lang.algorithms.dpo import join_interface
from grammar_lang.graph import Side

from .gluing import Graph
from .occurrence import Host


def side_graph(side: Side) -> Graph:
    """The side as a `Graph` (vertices, edges, boundary gaps).

    A `Graph` has no bare edges: its boundary holds vertex slots only. A side with wires (a
    rule's simpler side, §4.3) has none to map them to, so it raises ValueError rather than
    drop them; a wired right side enters matching as `wired_pairs` instead.
    """
    if side.wires:
        raise ValueError(f"a side with {len(side.wires)} bare edge(s) (wires) has no Graph form;"
                         " pass its wires as wired_pairs(side)")
    return Graph(tuple(side.vertices), tuple(sorted(side.edges)), bd.gaps(side.boundary))


def wired_pairs(rhs: Side) -> tuple[tuple[int, int], ...]:
    """Pairs of interface points (open-slot indices) that R joins by a bare wire."""
    ends: dict[int, list[int]] = {}
    for k, (v, _) in enumerate(rhs.open_slots()):
        if v < 0:
            ends.setdefault(-1 - v, []).append(k)
    return tuple(sorted(tuple(ks) for ks in ends.values() if len(ks) == 2))


def apply(lhs: Side, rhs: Side, img: list[int], host: Host) -> None:
    """Replace the match `img` of lhs in host by rhs, in place."""
    l_open = lhs.open_slots()
    where = {(v, i): k for k, (v, i) in enumerate(l_open)}
    inv = {h: v for v, h in enumerate(img)}
    contexts: list = []            # per interface point: open, a context slot, or another point
    for v, i in l_open:
        q = host.part[img[v]][i]
        inside = q is not None and q[0] in inv and (inv[q[0]], q[1]) in where
        contexts.append(where[(inv[q[0]], q[1])] if inside else q)
    for h in img:
        host.remove_vertex(h)
    new = [host.add_vertex(p) for p in rhs.vertices]
    for v, i, w, j in rhs.edges:
        host.glue((new[v], i), (new[w], j))
    ends = [(v, i) if v < 0 else (new[v], i) for v, i in rhs.open_slots()]
    for a, b in join_interface(contexts, ends)[0]:
        host.glue(a, b)
