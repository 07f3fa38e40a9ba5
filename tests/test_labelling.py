"""Typing the corpus: labels and primitives agree with the original tool's figures."""

import json

import pytest

from conftest import CORPUS, corpus_names
from corpus import reference_types
from grammar_lang import boundary as bd
from grammar_lang.example_json import load_example_json
from grammar_lang.labelling import label_example
from grammar_lang.loader import load_example
from grammar_lang.planar import build_planar_graph
from grammar_lang.svg_import import import_svg
from grammar_lang.source import ExampleGraph

REFERENCE = reference_types()


def typed(name):
    """The corpus example through the whole front end, from its gg-example/1 file."""
    return load_example(CORPUS / f"{name}.json")


def counts(ex):
    return (len(ex.primitives), len(ex.labels), len(ex.face_labels))


@pytest.mark.parametrize("name", corpus_names())
def test_type_counts_match_reference(name):
    assert counts(typed(name)) == REFERENCE[name]


@pytest.mark.parametrize("name", corpus_names())
def test_svg_import_types_like_the_reference(name):
    # The SVG does not say which classes are rigid; the corpus's class table does.
    source = import_svg(CORPUS / f"{name}.svg")
    source.classes = load_example_json(CORPUS / f"{name}.json").classes
    ex = label_example(source, build_planar_graph(source))
    assert counts(ex) == REFERENCE[name]


def test_a_bare_graph_is_typed_in_edge_order():
    # Without source positions (no spans), typing follows the graph's edge order.
    path = CORPUS / "square-hollow.json"
    doc = json.loads(path.read_text())
    graph = ExampleGraph(tuple(tuple(p) for p in doc["vertices"]),
                         tuple((u, v, l, r, str(c)) for u, v, l, r, c in doc["edges"]))
    ex = label_example(load_example_json(path), graph)
    assert [l.name for l in ex.labels] == ["x", "y"]


@pytest.mark.parametrize("name", corpus_names())
def test_primitives_are_consistent(name):
    ex = typed(name)
    assert sum(p.count for p in ex.primitives) == len(ex.graph.vertices)
    for p in ex.primitives:
        assert bd.winding(p.boundary) == 1
        angles = [ex.token_angle(t) for t in p.ring]
        assert angles == sorted(angles) and all(-180 <= a < 180 for a in angles)
    # Every edge is glued from one `a` and one `ā` of the same label.
    rings = [ex.primitives[i].ring for i in ex.vertex_primitive]
    for (u, v, *_), (label, forward) in zip(ex.graph.edges, ex.edge_label):
        assert bd.half(label, not forward) in rings[u]
        assert bd.half(label, forward) in rings[v]
    for lab in ex.labels:
        assert lab.left in ex.face_labels and lab.right in ex.face_labels
