"""Every corpus SVG imports to the graph its JSON twin describes (up to vertex order and noise)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import cKDTree

from conftest import CORPUS
from grammar_lang.planar import build_planar_graph
from grammar_lang.svg_import import import_svg

SVGS = sorted(CORPUS.glob("*.svg"))


def test_corpus_is_there():
    assert len(SVGS) == 31


def match_graphs(graph, expected: dict, tolerance: float = 1e-6) -> None:
    """Assert `graph` equals the corpus JSON up to vertex order, noise and class renaming."""
    ours = np.asarray(graph.vertices)
    theirs = np.asarray(expected["vertices"], dtype=float)
    assert len(ours) == len(theirs), "vertex count"
    dist, nearest = cKDTree(ours).query(theirs)
    assert np.all(dist <= tolerance), f"unmatched vertices {theirs[dist > tolerance]}"
    assert len(set(nearest.tolist())) == len(theirs), "two corpus vertices match one of ours"

    edges = {}
    for u, v, left, right, cls in graph.edges:
        key = frozenset((u, v))
        assert key not in edges, "duplicate edge"
        edges[key] = (u, left, right, cls)
    assert len(graph.edges) == len(expected["edges"]), "edge count"
    renaming: dict[str, str] = {}
    for u, v, left, right, cls in expected["edges"]:
        a, b = int(nearest[u]), int(nearest[v])
        assert frozenset((a, b)) in edges, f"missing edge {u}-{v}"
        start, our_left, our_right, our_cls = edges[frozenset((a, b))]
        if start != a:
            our_left, our_right = our_right, our_left
        assert (our_left, our_right) == (left, right), f"labels of edge {u}-{v}"
        assert renaming.setdefault(cls, our_cls) == our_cls, f"class of edge {u}-{v}"
    assert len(set(renaming.values())) == len(renaming), "classes merged"


@pytest.mark.parametrize("svg", SVGS, ids=[p.stem for p in SVGS])
def test_corpus_svg_matches_json(svg: Path):
    expected = json.loads(svg.with_suffix(".json").read_text())
    source = import_svg(svg)
    assert source.name == expected["name"]
    graph = build_planar_graph(source)
    match_graphs(graph, expected)
    assert len(graph.spans) == len(graph.edges)
    assert all(span is not None and span.line > 0 for span in graph.spans)


@pytest.mark.parametrize("svg", SVGS[::5], ids=[p.stem for p in SVGS[::5]])
def test_corpus_output_is_deterministic_and_order_free(svg: Path):
    """Same input → identical graph; reversing the drawing order of strokes changes nothing."""
    text = svg.read_text()
    first = build_planar_graph(import_svg(svg, text))
    assert build_planar_graph(import_svg(svg, text)) == first
    lines = text.splitlines()
    body = [k for k, line in enumerate(lines) if line.lstrip().startswith("<line")]
    if body:
        shuffled = lines[:body[0]] + [lines[k] for k in reversed(body)] + lines[body[-1] + 1:]
        again = build_planar_graph(import_svg(svg, "\n".join(shuffled)))
        assert again.vertices == first.vertices
        assert again.edges == first.edges


def test_corpus_transformed_copy_matches(tmp_path):
    """The same drawing inside a translated, scaled group imports to the transformed graph."""
    svg = CORPUS / "house-filled.svg"
    text = svg.read_text()
    start = text.index("<path")
    end = text.index("</svg>")
    wrapped = (text[:start] + '<g transform="translate(10,20)"><g transform="scale(2)">'
               + text[start:end] + "</g></g>" + text[end:])
    graph = build_planar_graph(import_svg(svg, wrapped))
    expected = json.loads(svg.with_suffix(".json").read_text())
    expected["vertices"] = [[2 * x + 10, 2 * y - 20] for x, y in expected["vertices"]]
    match_graphs(graph, expected)


@pytest.mark.parametrize("svg", SVGS, ids=[p.stem for p in SVGS])
def test_corpus_json_as_explicit_edges_rebuilds_itself(svg: Path):
    """The JSON read as explicit edges (left/right stated) goes through the same builder."""
    from grammar_lang.example_json import load_example_json
    path = svg.with_suffix(".json")
    match_graphs(build_planar_graph(load_example_json(path)), json.loads(path.read_text()))
