"""Drawings and rule sides as networkx graphs; GraphML output."""

import networkx as nx
import pytest

from compiler.infer import compile_example
from conftest import CORPUS, corpus_names
from grammar_lang import boundary as bd
from grammar_lang.loader import load_example
from grammar_lang.networkx_view import side_graph
from report.ggrun import main
from runtime.output.drawing import load_drawing
from runtime.output.graphml_out import drawing_graph


def test_graphml_holds_the_same_drawing_as_the_json(tmp_path):
    for suffix in ("json", "graphml"):
        assert main(["examples/house.gg", "--steps", "60", "--seed", "4", "--quiet",
                     "--out", str(tmp_path / f"h.{suffix}")]) == 0
    drawing = load_drawing(tmp_path / "h.json")
    g = nx.read_graphml(tmp_path / "h.graphml", node_type=int)
    assert g.is_directed() and g.graph["seed"] == 4
    assert g.number_of_nodes() == len(drawing.vertices)
    assert g.number_of_edges() == len(drawing.edges)
    for v in drawing.vertices:
        assert (g.nodes[v.id]["x"], g.nodes[v.id]["y"]) == (v.x, v.y)
    for e in drawing.edges:
        a = g.edges[e.u, e.v]
        assert (a["left"], a["right"], a["class"]) == (e.left, e.right, e.cls)
    assert nx.is_isomorphic(g, drawing_graph(drawing))


@pytest.mark.parametrize("name", corpus_names()[:12])
def test_rule_sides_as_graphs_keep_the_labels_of_their_slots(name):
    grammar = compile_example(load_example(CORPUS / f"{name}.svg")).grammar
    rings = grammar.rings
    for rule in grammar.rules:
        for side in (rule.lhs, rule.rhs):
            g = side_graph(side, grammar.header)
            assert g.number_of_nodes() == len(side.vertices)
            assert g.number_of_edges() == len(side.edges)
            for _, _, a in g.edges(data=True):
                (v, i), (w, j) = a["slots"]
                t = rings[side.vertices[v]][i]
                assert rings[side.vertices[w]][j] == t ^ 1
                assert a["label"] == grammar.header.labels[bd.label_of(t)].name


def test_the_documented_python_example_runs(tmp_path):
    """docs/drawing-format.md's networkx example, run as a user would, on a real drawing."""
    import re
    import subprocess
    import sys
    from conftest import ROOT
    doc = (ROOT / "docs" / "drawing-format.md").read_text()
    (snippet,) = [b for b in re.findall(r"```python\n(.*?)```", doc, re.S) if "drawing_graph" in b]
    assert main([str(ROOT / "examples" / "tree.gg"), "--steps", "40", "--seed", "1", "--quiet",
                 "--out", str(tmp_path / "out" / "tree.json")]) == 0
    res = subprocess.run([sys.executable, "-c", snippet], cwd=tmp_path, capture_output=True,
                         text=True, env={"PYTHONPATH": str(ROOT)}, timeout=120)
    assert res.returncode == 0, res.stderr
    assert res.stdout.strip() == "1"          # the tree is connected
