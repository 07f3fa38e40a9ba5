"""The `gg-drawing/1` JSON format: what `ggrun` writes and `ggrun check` reads.

Coordinates are in the example's y-up frame and units. `left`/`right` are the face labels on
each side walking from `u` to `v`, named as in the source. Extra fields are allowed and kept.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

from grammar_lang.diagnostics import Span, error
from grammar_lang import limits
from grammar_lang.fileio import atomic_write, read_text
from grammar_lang.json_doc import Reader

FORMAT = "gg-drawing/1"


@dataclass(frozen=True)
class DVertex:
    id: int
    x: float
    y: float


@dataclass(frozen=True)
class DEdge:
    u: int
    v: int
    left: str
    right: str
    cls: str
    label: str | None = None          # the edge label's name in the grammar, when known


@dataclass(frozen=True)
class Drawing:
    vertices: tuple[DVertex, ...]
    edges: tuple[DEdge, ...]
    meta: dict = field(default_factory=dict, compare=False)

    def to_json(self) -> str:
        doc = {
            "format": FORMAT,
            **{k: v for k, v in sorted(self.meta.items()) if k not in ("format", "vertices", "edges")},
            "vertices": [{"id": v.id, "x": round_coordinate(v.x), "y": round_coordinate(v.y)}
                         for v in self.vertices],
            "edges": [
                {"u": e.u, "v": e.v, "left": e.left, "right": e.right, "class": e.cls,
                 **({"label": e.label} if e.label is not None else {})}
                for e in self.edges
            ],
        }
        return json.dumps(doc, indent=1, ensure_ascii=False) + "\n"

    def save(self, path: str | Path) -> None:
        atomic_write(path, self.to_json())


def round_coordinate(x: float) -> float:
    # A fixed precision keeps files byte-identical across platforms and runs.
    r = round(float(x), 6)
    return 0.0 if r == 0 else r


def parse_drawing(text: str, path: str = "<drawing>") -> Drawing:
    r = Reader(path, f"{FORMAT} drawing",
               'vertices are {"id", "x", "y"}; edges are {"u", "v", "left", "right", "class"}')
    doc = r.parse(text)
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise error(f"not a {FORMAT} drawing", Span(path),
                    f'the top-level object needs "format": "{FORMAT}"')
    vs = r.array(r.key(doc, "vertices", "the file"), "vertices", limit=limits.POINTS)
    vertices = tuple(_vertex(r, r.obj(v, f"vertices[{k}]"), f"vertices[{k}]")
                     for k, v in enumerate(vs))
    es = r.array(r.key(doc, "edges", "the file"), "edges")
    edges = tuple(_edge(r, r.obj(e, f"edges[{k}]"), f"edges[{k}]") for k, e in enumerate(es))
    ids = {v.id for v in vertices}
    if len(ids) != len(vertices):
        raise error("two vertices share an id", Span(path))
    for e in edges:
        if e.u not in ids or e.v not in ids:
            raise error(f"edge {e.u}-{e.v} names a vertex that does not exist", Span(path))
    meta = {k: v for k, v in doc.items() if k not in ("format", "vertices", "edges")}
    return Drawing(vertices, edges, meta)


def _vertex(r: Reader, v: dict, at: str) -> DVertex:
    return DVertex(r.integer(r.key(v, "id", at), f"{at}.id", -2 ** 62, 2 ** 62),
                   r.number(r.key(v, "x", at), f"{at}.x"), r.number(r.key(v, "y", at), f"{at}.y"))


def _edge(r: Reader, e: dict, at: str) -> DEdge:
    def end(key: str) -> int:
        return r.integer(r.key(e, key, at), f"{at}.{key}", -2 ** 62, 2 ** 62)

    def text(key: str) -> str:
        return r.string(r.key(e, key, at), f"{at}.{key}")

    label = e.get("label")
    return DEdge(end("u"), end("v"), text("left"), text("right"),
                 r.string(e.get("class", "0"), f"{at}.class"),
                 None if label is None else r.string(label, f"{at}.label"))


def load_drawing(path: str | Path) -> Drawing:
    return parse_drawing(read_text(path), str(path))


def drawing_from_example(example) -> Drawing:
    """The example's own graph as a drawing, with every edge along its label's exact direction.

    Hand-drawn edges are a few degrees off their label. The positions are moved as little as
    possible (least squares) so that each edge is parallel to its label, and rigid edges get
    their exact vector. Edges are written walking along their label's `a` half-edge.
    """
    import numpy as np

    graph = example.graph
    if graph is None:
        raise ValueError("the example was given as primitives, so it has no drawing")
    p0 = np.asarray(graph.vertices, dtype=float).reshape(-1)
    rows, rhs = [], []
    for (u, v, *_), (li, forward) in zip(graph.edges, example.edge_label):
        lab = example.labels[li]
        c, s = np.cos(np.radians(lab.angle)), np.sin(np.radians(lab.angle))
        # n·(p_v − p_u) = 0 keeps the edge parallel to the label's direction.
        for (ax, ay), value in [((-s, c), 0.0)] + (
                [((c, s), lab.length if forward else -lab.length)] if lab.length is not None else []):
            row = np.zeros_like(p0)
            row[2 * v], row[2 * v + 1], row[2 * u], row[2 * u + 1] = ax, ay, -ax, -ay
            rows.append(row)
            rhs.append(value)
    pos = p0
    if rows:
        a = np.array(rows)
        residual = np.array(rhs) - a @ p0
        # Already exact (drawn on a grid, say): keep the coordinates as they are.
        if np.abs(residual).max() > 1e-12 * max(1.0, np.abs(p0).max()):
            pos = p0 + np.linalg.lstsq(a, residual, rcond=None)[0]
    xy = pos.reshape(-1, 2)
    vertices = tuple(DVertex(i, float(x), float(y)) for i, (x, y) in enumerate(xy))
    edges = []
    for (u, v, left, right, cls), (li, forward) in zip(graph.edges, example.edge_label):
        if not forward:
            u, v, left, right = v, u, right, left
        edges.append(DEdge(u, v, left, right, cls, example.labels[li].name))
    return Drawing(vertices, tuple(edges), {"example": example.name})
