"""Drawings as networkx graphs, and GraphML output (`ggrun … --out x.graphml`).

A drawing becomes a `networkx.DiGraph`: one node per vertex with its position (`x`, `y`),
one edge per drawing edge, directed from `u` to `v` as in the JSON, since `left` and `right`
(the faces beside it) are seen walking that way; each edge also carries its `class` and, when
known, its grammar `label`. Graph attributes hold the drawing's metadata (grammar, seed,
steps). The engine keeps its own structures for speed; this view is for users' analyses.
"""

from __future__ import annotations

from pathlib import Path

import networkx as nx

from grammar_lang.fileio import atomic_write
from grammar_lang.xml_text import xml_text

from .drawing import Drawing, round_coordinate


def drawing_graph(drawing: Drawing) -> nx.DiGraph:
    g = nx.DiGraph(**{k: v for k, v in sorted(drawing.meta.items())
                      if isinstance(v, (str, int, float, bool))})
    for v in drawing.vertices:
        g.add_node(v.id, x=round_coordinate(v.x), y=round_coordinate(v.y))   # as in the JSON
    for e in drawing.edges:
        attrs = {"left": e.left, "right": e.right, "class": e.cls}
        if e.label is not None:
            attrs["label"] = e.label
        g.add_edge(e.u, e.v, **attrs)
    return g


def write_graphml(drawing: Drawing, path: str | Path) -> None:
    """GraphML, written atomically; networkx escapes every string it writes as XML, and
    what XML cannot hold is replaced first (grammar_lang.xml_text)."""
    g = drawing_graph(drawing)
    for attrs in (g.graph, *(d for _, d in g.nodes(data=True)),
                  *(d for _, _, d in g.edges(data=True))):
        for k, v in attrs.items():
            if isinstance(v, str):
                attrs[k] = xml_text(v)
    atomic_write(path, "\n".join(nx.generate_graphml(g)) + "\n")
