"""The paper's worked examples (§4-5, companion §6.6) as acceptance tests for inference."""

import pytest

from conftest import CORPUS, ILLUSTRATIONS, ROOT
from hand_examples import CORNERS_AND_T, RECTANGLE, make
from compiler.infer import Inference, compile_example
from compiler.verify import verify
from grammar_lang import boundary as bd
from grammar_lang.loader import load_example

EXAMPLES = ROOT / "examples"


def test_rectangle_fig5_is_complete_with_at_most_five_rules():
    res = compile_example(make(RECTANGLE))
    assert res.report.complete
    assert res.grammar.header.complete is True
    assert res.report.rules + res.report.starters <= 5
    assert res.report.starters == 1
    # Every rule has equal boundary strings on both sides and a simpler right side.
    rings = res.grammar.rings
    for r in res.grammar.rules:
        if r.is_starter:
            assert r.lhs.tokens(rings) == (bd.UP,)
            continue
        assert bd.canonical(r.lhs.tokens(rings)) == bd.canonical(r.rhs.tokens(rings))


def test_rectangle_verifies_up_to_ten_primitives():
    res = compile_example(make(RECTANGLE))
    v = verify(res.grammar, 10)
    assert v.checked > 20 and v.ok and not v.enumeration_capped


@pytest.mark.parametrize("name", ["square-hollow", "square-filled"])
def test_corpus_squares_complete_and_verified(name):
    res = compile_example(load_example(CORPUS / f"{name}.svg"))
    assert res.report.complete
    assert res.report.rules + res.report.starters <= 5
    v = verify(res.grammar, 10)
    assert v.ok and v.checked >= 1


def test_spirals_are_pruned_in_the_rectangle():
    # y∧ⁿ⁺¹ȳ∨ⁿ graphs (§5.6) are found to have no complete irreducible descendants. (Its
    # corners pair off, so grouped they are one closed block, which needs no pruning.)
    inf = Inference(make(RECTANGLE), group=False)
    inf.run()
    pruned = [n.graph for n in inf.hier.nodes if n.status == "pruned"]
    assert pruned
    for g in pruned:
        # Chains of corners that have turned past a full turn: 5 corners or more.
        assert len(g.verts) >= 5 and len(g.edges) == len(g.verts) - 1


def test_stubs_found_though_no_primitive_is_a_stub():
    ex = make(CORNERS_AND_T)
    assert all(len(p.ring) > 1 for p in ex.primitives)
    inf = Inference(ex)
    res = inf.run()
    stubs = {n.graph.tokens(inf.rings) for n in inf.hier.nodes if n.graph.n_half == 1}
    assert {((t, 1),) for t in (0, 1, 2, 3)} <= stubs
    assert res.report.complete
    assert verify(res.grammar, 7).ok


def test_diagonal_box_uses_descendants_on_the_right_side():
    # Fig. 4a / §5.4: a rule whose right side holds graphs that contain its left side.
    from compiler.apply import side_graph
    from compiler.occurrence import Host, Pattern, contains
    res = compile_example(load_example(CORPUS / "diagonal-box.svg"))
    found = False
    for r in res.grammar.rules:
        if r.is_starter or not r.rhs.vertices:
            continue
        lhs = Pattern.of(side_graph(r.lhs))
        if contains(lhs, Host(r.rhs.vertices, tuple(sorted(r.rhs.edges)))):
            found = True
    assert found
    assert verify(res.grammar, 8).ok


_VERIFIED: dict = {}


def _verified(grammar, max_prims: int) -> bool:
    """verify(grammar, max_prims).ok, once per grammar: the answer depends only on the rules,
    the rings and `no_loops`, and the drawing and the .gg of one example give the same ones."""
    key = (tuple(grammar.rules), tuple(grammar.rings), grammar.header.options.no_loops, max_prims)
    if key not in _VERIFIED:
        _VERIFIED[key] = verify(grammar, max_prims).ok
    return _VERIFIED[key]


@pytest.mark.parametrize("path", [CORPUS / "diagonal-box.svg", EXAMPLES / "diagonal-box.gg"])
def test_diagonal_box_complete(path):
    # Fig. 4a: the §5.4 rule restructures the blocks (the diagonal block becomes the two
    # triangles), after which the spirals around the diagonal are pruned.
    res = compile_example(load_example(path))
    assert res.report.complete
    assert res.report.rules <= 6
    assert _verified(res.grammar, 10)


TREES = ["line", "angle", "t", "z", "h", "u", "right-angles", "a", "branches", "curl",
         "double-branch", "h-complex", "h-complex-2", "intersection", "plus", "triangle-curl"]


def _stub_tokens(rings, max_verts=8, cap=20000) -> set[int]:
    """Tokens t for which some graph glued from the primitives has the boundary t∧ (a stub),
    by breadth-first gluing up to `max_verts` vertices (independent of the compiler). It stops
    once every token of the rings has a stub: more cannot be found."""
    from compiler.canon import canonical_key
    from compiler.gluing import block_slots, children, primitive_graph
    prims = [primitive_graph(p, len(r)) for p, r in enumerate(rings)]
    slots = block_slots(prims, rings)
    ring_len = [len(r) for r in rings]
    every = {t for r in rings for t in r}
    seen, frontier, found = set(), list(prims), set()
    while frontier and len(seen) < cap and not every <= found:
        nxt = []
        for g in frontier:
            if g.n_half == 1:
                found.add(g.tokens(rings)[0][0])
            for _, child, _ in children(g, prims, rings, True, slots):
                key = canonical_key(child, ring_len)
                if len(child.verts) <= max_verts and child.gaps and key not in seen:
                    seen.add(key)
                    nxt.append(child)
        frontier = nxt
    return found


@pytest.mark.parametrize("name", TREES)
def test_trees_have_a_pair_of_stubs_for_every_label_and_are_complete(name):
    ex = load_example(CORPUS / f"{name}.svg")
    rings = [p.ring for p in ex.primitives]
    assert {t for r in rings for t in r} <= _stub_tokens(rings)
    assert compile_example(ex).report.complete


def test_no_loops_option_forbids_loop_gluing_and_splicing():
    from dataclasses import replace
    ex = load_example(CORPUS / "square-hollow.svg")
    ex = replace(ex, options=replace(ex.options, no_loops=True))
    inf = Inference(ex)
    res = inf.run()
    assert all(n.graph.n_half > 0 for n in inf.hier.nodes)      # nothing ever closes
    for r in res.grammar.rules:
        assert len(r.rhs.components()) + len(r.rhs.wires) <= 1


def test_connected_option_allows_no_spliced_right_sides():
    from dataclasses import replace
    ex = load_example(CORPUS / "star-hollow.svg")
    res = compile_example(replace(ex, options=replace(ex.options, connected=True)))
    assert res.grammar.header.options.connected
    for r in res.grammar.rules:
        assert len(r.rhs.components()) + len(r.rhs.wires) <= 1


@pytest.mark.parametrize("path", [CORPUS / "house-hollow.json", CORPUS / "triangle-square.json",
                                  ILLUSTRATIONS / "flowers.gg"], ids=lambda p: p.stem)
def test_the_generations_reported_are_those_that_met_graphs(path):
    """A generation is counted only when it expands a graph: a frontier whose graphs all
    became rules since they were met no longer counts as one more (the flowers reported 4)."""
    if not path.exists():
        pytest.skip("corpus not found")
    inference = Inference(load_example(path))
    report = inference.run().report
    assert report.complete
    assert report.generations == max(node.gen for node in inference.hier.nodes)
