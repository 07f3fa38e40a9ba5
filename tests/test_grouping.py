"""Blocks (companion §3.3) and rigid parts merged into single units (paper §8, Table 1)."""

from pathlib import Path

import pytest

from conftest import CORPUS, ROOT, corpus_names
from compiler import grouping
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
    blocks = grouping.blocks(rings, rigid=rigid)
    for b in blocks:
        open_tokens = [rings[b.verts[v]][i] for (v, i), _ in b.gaps]
        for t in open_tokens:
            if bd.label_of(t) in rigid:
                assert bd.opposite(t) not in open_tokens, (path.name, ex.label_names[bd.label_of(t)])
    # Every primitive is in exactly one block.
    assert sorted(p for b in blocks for p in b.verts) == list(range(len(rings)))


def test_rigid_cycles_close_only_when_rigid():
    # Without rigid labels the forced pairs outside a block's tree stay open (the same A may
    # meet another B instance in a locally similar graph).
    ex = load_example(ILLUSTRATIONS / "flowers.gg")
    rings = [p.ring for p in ex.primitives]
    open_closed = sum(len(b.gaps) for b in grouping.blocks(rings, rigid=_rigid(ex)))
    open_plain = sum(len(b.gaps) for b in grouping.blocks(rings))
    assert open_closed < open_plain


def test_the_papers_flowers_are_complete_with_rigid_units():
    # Table 1: Flowers' grammar is complete (8 rules, 20 hierarchy graphs). With each blossom
    # one unit, ours closes too, well inside the default limits.
    res = compile_example(load_example(ILLUSTRATIONS / "flowers.gg"))
    assert res.report.complete, res.report.verdict
    assert res.report.hierarchy_graphs < 200
