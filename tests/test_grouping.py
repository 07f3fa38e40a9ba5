"""Blocks (companion §3.3) and rigid parts merged into single units (paper §8, Table 1)."""

from pathlib import Path

import pytest

from conftest import CORPUS, ROOT, corpus_names
from compiler import grouping
from compiler.gluing import loop_gluable
from compiler.infer import compile_example
from grammar_lang import boundary as bd
from grammar_lang.loader import load_example

ILLUSTRATIONS = CORPUS.parent / "illustrations"
SOURCES = ([CORPUS / f"{n}.svg" for n in corpus_names()]
           + sorted(ILLUSTRATIONS.glob("*.gg")) + sorted((ROOT / "examples").glob("*.gg")))


def _rigid(ex) -> set[int]:
    return {k for k, lab in enumerate(ex.labels) if ex.cls(lab.cls).rigid}


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: p.name)
def test_a_block_leaves_no_rigid_edge_of_its_own_open(path: Path):
    # A rigid label types one edge of the example, so its two ends are in one block; the
    # block must glue them, or the hierarchy glues the slot to another copy of the block.
    ex = load_example(path)
    rings = [p.ring for p in ex.primitives]
    rigid = _rigid(ex)
    blocks = grouping.blocks(rings)
    for b in blocks:
        open_tokens = [rings[b.verts[v]][i] for (v, i), _ in b.gaps]
        for t in open_tokens:
            if bd.label_of(t) in rigid:
                assert bd.opposite(t) not in open_tokens, (path.name, ex.label_names[bd.label_of(t)])
    # Every primitive is in exactly one block.
    assert sorted(p for b in blocks for p in b.verts) == list(range(len(rings)))


@pytest.mark.parametrize("path", SOURCES, ids=lambda p: p.name)
def test_a_block_leaves_no_forced_cycle_it_could_close_open(path: Path):
    # A forced cycle comes back to the same instance (it turns once, so one round), rigid or
    # not: two open slots of a block that are a forced pair and could be loop glued are not.
    ex = load_example(path)
    rings = [p.ring for p in ex.primitives]
    forced = {frozenset(((p, i), (q, j))) for p, i, q, j in grouping.forced_pairs(rings)}
    for b in grouping.blocks(rings):
        m = len(b.gaps)
        for k in range(m):
            (v, i), (w, j) = b.gaps[k][0], b.gaps[(k + 1) % m][0]
            pair = frozenset(((b.verts[v], i), (b.verts[w], j)))
            assert not (pair in forced and loop_gluable(b, k, rings)), path.name


def test_the_station_connector_closes():
    # Its four corners pair off with plain (not rigid) edges; the block is one closed square
    # hanging from a module's bottom line over the next module's top.
    ex = load_example(ILLUSTRATIONS / "space-station.gg")
    rings = [p.ring for p in ex.primitives]
    square = [b for b in grouping.blocks(rings) if len(b.verts) == 4 and len(b.edges) == 4]
    assert any(ex.format(b.string(rings)) == "x13∧x̄13d̄53_1331d̄126_8713" for b in square)


def test_the_papers_flowers_are_complete_with_rigid_units():
    # Table 1: Flowers' grammar is complete (8 rules, 20 hierarchy graphs). With each blossom
    # one unit, ours closes too, well inside the default limits.
    res = compile_example(load_example(ILLUSTRATIONS / "flowers.gg"))
    assert res.report.complete, res.report.verdict
    assert res.report.hierarchy_graphs < 200


def test_the_papers_station_is_complete_with_its_modules_as_units():
    # Table 1: the station is complete (25 rules, 240 hierarchy graphs). The closed top and the
    # connector each close a face with the module body below them and only that one, so they
    # become two units; a module's bottom line shut on itself is a left side (the leaf module,
    # or the lone module's starter), so no face can walk back up from a connector.
    from compiler.verify import verify
    res = compile_example(load_example(ILLUSTRATIONS / "space-station.gg"))
    assert res.report.complete, res.report.verdict
    assert res.report.blocks == 3 and res.report.hierarchy_graphs < 240
    assert res.report.rules - res.report.rules_beside + res.report.starters <= 25
    # The hierarchy the faces left, grown on beside the complete rules, adds ways to grow
    # (a module above another) without touching the verdict.
    assert res.report.rules_beside > 0
    # The lone module is a starter (its example component reduces to it), so it reduces too.
    assert verify(res.grammar, 8).ok


def test_the_station_opens_with_its_example_not_the_lone_module():
    # The lone module stays for reduction with weight 0; runs open with the example's station,
    # which its one growing rule (a module hung under another) could not grow from one module.
    from compiler.apply import side_graph
    from compiler.canon import canonical_key
    from compiler.infer import example_graphs
    from runtime.engine.schedule import Schedule
    ex = load_example(ILLUSTRATIONS / "space-station.gg")
    res = compile_example(ex)
    ring_len = [len(p.ring) for p in ex.primitives]
    own = {canonical_key(g, ring_len) for g in example_graphs(ex)}
    starters = [r for r in res.grammar.rules if r.is_starter]
    assert {canonical_key(side_graph(r.lhs), ring_len) in own for r in starters} == {True, False}
    for r in starters:
        assert (r.weight > 0) == (canonical_key(side_graph(r.lhs), ring_len) in own)
    opening = Schedule.build(res.grammar).opening
    assert [m.rule.name for m, _ in opening] == [r.name for r in starters if r.weight > 0]
