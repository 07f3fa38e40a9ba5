"""Rule sides as networkx graphs, for users' analyses in Python.

A side becomes a `networkx.MultiGraph` (two vertices may be joined by more than one edge):
one node per vertex with its primitive's name and its ring of half-edge names, one edge per
glued pair of slots with the edge label's name, its class and the two slots (`slots`: the
(vertex, ring index) of each end, lower first). The side's boundary walk, in the paper's
notation, is the graph attribute `boundary`; bare edges (wires) are listed in `wires`.
Sides have no positions: a rule says how edges meet, and the runtime places them.
"""

from __future__ import annotations

import networkx as nx

from . import boundary as bd
from .graph import Side
from .rules import Header


def side_graph(side: Side, header: Header) -> nx.MultiGraph:
    rings = [p.ring for p in header.primitives]
    names = [l.name for l in header.labels]
    g = nx.MultiGraph(boundary=bd.format_tokens(side.tokens(rings), names),
                      wires=[names[bd.label_of(w)] for w in side.wires])
    for v, prim in enumerate(side.vertices):
        g.add_node(v, name=side.vertex_name(v), primitive=header.primitives[prim].name,
                   ring=[bd.format_tokens((t,), names) for t in rings[prim]])
    for v, i, w, j in side.edges:
        label = header.labels[bd.label_of(rings[side.vertices[v]][i])]
        g.add_edge(v, w, label=label.name, cls=label.cls, slots=((v, i), (w, j)))
    return g
