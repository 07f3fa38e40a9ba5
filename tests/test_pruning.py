"""Pruning (§5.6) is sound: a graph declared a dead end has no complete descendant.

Without rules the turning analysis claims "no complete descendant at all", which a bounded
brute-force search over descendants can refute; with rules it claims "no complete irreducible
descendant", which the verification tests check end to end.
"""

from hypothesis import given, settings, strategies as st

from conftest import CORPUS
from hand_examples import RECTANGLE, make
from compiler.canon import canonical_key
from compiler.gluing import block_slots, children, primitive_graph
from compiler.pruning import TurnAnalysis
from grammar_lang.loader import load_example

EXAMPLES = {name: load_example(CORPUS / f"{name}.svg")
            for name in ("square-filled", "house-filled", "triangle", "l", "diagonal-row")}
EXAMPLES["rectangle"] = make(RECTANGLE)


def _grow(rings, choices):
    prims = [primitive_graph(p, len(r)) for p, r in enumerate(rings)]
    slots = block_slots(prims, rings)
    g = prims[choices[0] % len(prims)]
    out = [g]
    for c in choices[1:]:
        kids = [k for _, k, _ in children(g, prims, rings, True, slots)]
        if not kids:
            break
        g = kids[c % len(kids)]
        out.append(g)
    return out, prims, slots


def _has_complete_descendant(g, prims, rings, slots, extra: int, cap: int = 600) -> bool:
    ring_len = [len(r) for r in rings]
    limit = len(g.verts) + extra
    seen = {canonical_key(g, ring_len)}
    frontier = [g]
    while frontier and len(seen) < cap:
        nxt = []
        for h in frontier:
            for _, k, _ in children(h, prims, rings, True, slots):
                if len(k.verts) > limit:
                    continue
                if k.is_complete:
                    return True
                key = canonical_key(k, ring_len)
                if key not in seen:
                    seen.add(key)
                    nxt.append(k)
        frontier = nxt
    return False


@settings(max_examples=25, deadline=None)
@given(st.sampled_from(sorted(EXAMPLES)), st.lists(st.integers(0, 10_000), min_size=2, max_size=10))
def test_dead_ends_have_no_complete_descendants(name, choices):
    rings = [p.ring for p in EXAMPLES[name].primitives]
    analysis = TurnAnalysis(rings)
    graphs, prims, slots = _grow(rings, choices)
    for g in graphs:
        if not g.is_complete and analysis.dead_end(g):
            assert not _has_complete_descendant(g, prims, rings, slots, extra=4)


@settings(max_examples=25, deadline=None)
@given(st.sampled_from(sorted(EXAMPLES)), st.lists(st.integers(0, 10_000), min_size=2, max_size=10))
def test_moves_on_no_face_are_on_no_complete_graph(name, choices):
    # Without rules, kill_by_faces kills only moves that lie on no face turning ±1: a graph
    # that glues one of them still has no complete descendant.
    rings = [p.ring for p in EXAMPLES[name].primitives]
    analysis = TurnAnalysis(rings)
    analysis.kill_by_faces()
    graphs, prims, slots = _grow(rings, choices)
    for g in graphs:
        if not g.is_complete and analysis.dead_end(g):
            assert not _has_complete_descendant(g, prims, rings, slots, extra=4)


def test_the_square_closes_and_its_spirals_are_dead_ends():
    ex = EXAMPLES["square-filled"]
    rings = [p.ring for p in ex.primitives]
    analysis = TurnAnalysis(rings)
    # Follow the forced chain of corners: after four the square can close; a chain of five or
    # more corners has turned past a full turn and is a dead end.
    graphs, _, _ = _grow(rings, [0] + [10 ** 6] * 9)
    chains = [g for g in graphs if not g.is_complete]
    assert any(len(g.verts) >= 5 for g in chains)
    for g in chains:
        assert analysis.dead_end(g) == (len(g.verts) >= 5)


def _floyd_whole(w):
    """Shortest walks over the whole move graph, the plain way: Floyd-Warshall, then −inf
    for every walk that can pass through a negative cycle."""
    import numpy as np
    d = w.copy()
    np.fill_diagonal(d, np.minimum(np.diag(d), 0.0))
    for k in range(len(d)):
        np.minimum(d, d[:, k:k + 1] + d[k:k + 1, :], out=d)
    neg = np.diag(d) < 0
    bad = np.isfinite(d[:, neg])[:, :, None] & np.isfinite(d[neg, :])[None, :, :]
    return np.where(bad.any(axis=1), -np.inf, d)


@settings(max_examples=60, deadline=None)
@given(st.integers(2, 14), st.data())
def test_shortest_walks_per_component_equal_the_whole_graphs(n, data):
    # `dead_end` reads walks between moves of one strong component only, and those never
    # leave it: solving each component alone must give the whole graph's answer there,
    # negative and positive cycles included.
    import numpy as np
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import connected_components
    from compiler.pruning import INF, _by_component
    cells = data.draw(st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1),
                                         st.integers(-2, 2)), max_size=3 * n))
    w = np.full((n, n), INF)
    for a, b, t in cells:
        w[a, b] = t
    _, comp = connected_components(csr_matrix(np.isfinite(w)), directed=True,
                                   connection="strong")
    whole, parts = _floyd_whole(w), _by_component(w, comp)
    same = comp[:, None] == comp[None, :]
    assert np.array_equal(whole[same], parts[same])


def _solved(ta: TurnAnalysis):
    """What a solve leaves for readers: the partition into strong components, the walks'
    bounds within each, the steps each move can take."""
    import numpy as np
    ta.solve()
    same = ta.comp[:, None] == ta.comp[None, :]
    return same, np.where(same, ta.low, 0), np.where(same, ta.high, 0), ta._follow


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(sorted(EXAMPLES)), st.data())
def test_solving_again_after_kills_equals_solving_afresh(name, data):
    # `_resolve_walks` solves only the components that lost a move or a step: its answer must
    # be a fresh solve's, whatever dies, in any number of rounds.
    import numpy as np
    rings = [p.ring for p in EXAMPLES[name].primitives]
    ta = TurnAnalysis(rings)
    n = len(ta.moves)
    ta.solve()
    for _ in range(data.draw(st.integers(1, 4))):
        for m in data.draw(st.lists(st.integers(0, n - 1), max_size=3)):
            ta.forbid_edge(*ta.moves[m])
        for a, b in data.draw(st.lists(st.tuples(st.integers(0, n - 1),
                                                 st.integers(0, n - 1)), max_size=4)):
            ta.forbid_pair(ta.moves[a], ta.moves[b])
        fresh = TurnAnalysis(rings)
        fresh.dead, fresh.dead_pairs = set(ta.dead), set(ta.dead_pairs)
        for got, want in zip(_solved(ta), _solved(fresh)):
            assert np.array_equal(np.asarray(got, dtype=object), np.asarray(want, dtype=object))
