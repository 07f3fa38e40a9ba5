"""The paper's impossible graphs (Appendix C, §4.4 / Fig. 4b) are found to have no complete
descendants.

The primitive figures are not in the paper's text; the shapes are reconstructed from it.
Appendix C's labels y01, x01, x02 (and x12, in its decision tree) over faces 0, 1, 2 are those of
a narrow block on a wide base, and walking once around the block from its top-left corner,
back to a second top-left corner, builds exactly ȳ01∨x01∧x̄02x02∧. Fig. 4b's platform is a wide
slab on a narrow leg; the same walk around the slab is its impossible graph.
"""

import unicodedata
from pathlib import Path

import pytest

from test_pruning import _has_complete_descendant
from compiler.canon import canonical_key
from compiler.gluing import Graph, block_slots, branch_glue, primitive_graph
from compiler.infer import Inference
from compiler.pruning import TurnAnalysis
from grammar_lang.loader import load_example

DATA = Path(__file__).parent / "data"


def _nfc(s: str) -> str:
    return unicodedata.normalize("NFC", s)


def _chain(ex, steps: list[tuple[str, str]]) -> Graph:
    """Glue primitives one after another: each step names a primitive by its boundary string
    and the half-edge of it that glues to the latest open opposite half-edge."""
    rings = [p.ring for p in ex.primitives]
    by_string = {_nfc(ex.format(p.ring)): k for k, p in enumerate(ex.primitives)}
    g = None
    for prim, half in steps:
        p = by_string[_nfc(prim)]
        h = primitive_graph(p, len(rings[p]))
        if g is None:
            g = h
            continue
        j = next(i for i, t in enumerate(rings[p]) if _nfc(ex.format((t,))) == _nfc(half))
        want = rings[p][j] ^ 1
        s = [s for s, _ in g.gaps if rings[g.verts[s[0]]][s[1]] == want][-1]
        g = branch_glue(g, s, h, (0, j), rings)
    return g


APPENDIX_C = [("ȳ01x01", ""), ("x̄02x12y01", "y01"), ("x̄12x02y10", "x̄12"),
              ("x̄01ȳ10", "ȳ10"), ("ȳ01x01", "x01")]
PLATFORM = [("ȳ01x01", ""), ("x̄01ȳ10", "x̄01"), ("x̄10y10", "y10"), ("x̄12ȳ20x10", "x10"),
            ("x̄10ȳ02x12", "x12"), ("x10y01", "x10"), ("ȳ01x01", "ȳ01")]

CASES = {"appendix-c": (APPENDIX_C, "ȳ01∨x01∧x̄02x02∧"),
         "platform-filled": (PLATFORM, None)}


@pytest.mark.parametrize("name", sorted(CASES))
def test_impossible_graph_has_no_complete_descendants(name):
    steps, expected = CASES[name]
    ex = load_example(DATA / f"{name}.gg")
    rings = [p.ring for p in ex.primitives]
    g = _chain(ex, steps)
    if expected is not None:
        assert _nfc(ex.format(g.string(rings))) == _nfc(expected)
    assert not g.is_complete
    # Without any rule, "dead end" means: no complete descendant at all.
    assert TurnAnalysis(rings).dead_end(g)
    prims = [primitive_graph(p, len(r)) for p, r in enumerate(rings)]
    assert not _has_complete_descendant(g, prims, rings, block_slots(prims, rings), extra=3)
    # One primitive fewer (the walk not yet back at its start) can still be completed.
    shorter = _chain(ex, steps[:-1])
    assert not TurnAnalysis(rings).dead_end(shorter)


@pytest.mark.parametrize("name", sorted(CASES))
def test_impossible_graph_is_pruned_in_the_hierarchy(name):
    steps, _ = CASES[name]
    ex = load_example(DATA / f"{name}.gg")
    inf = Inference(ex, group=False)
    inf.run()
    # Without grouping the hierarchy grows the graph primitive by primitive and prunes it
    # (§5.6) rather than keeping it as a piece: it meets the graph, or prunes an earlier graph
    # of the chain once the faces the rules leave rule that out too (platform-filled).
    fates = []
    for k in range(1, len(steps) + 1):
        hit = inf.hier.index.get(canonical_key(_chain(ex, steps[:k]), inf.ring_len))
        fates.append(None if hit is None else inf.hier.nodes[hit].status)
    first = next(k for k, f in enumerate(fates) if f != "irreducible")
    assert fates[first] == "pruned" and set(fates[first + 1:]) <= {None}, fates
    full = Inference(ex).run()
    assert full.report.complete, full.report.verdict
