"""Gluing on boundary gaps agrees with walking the glued graph; canonical forms ignore numbering."""

import random

from hypothesis import given, settings, strategies as st

from compiler.canon import canonical_key
from compiler.gluing import (Graph, branch_glue, children, loop_glue, loop_gluable,
                             primitive_graph)
from grammar_lang import boundary as bd
from grammar_lang.graph import Side, face_walk

# Rings (tokens CCW by angle) of three primitive sets: the hollow rectangle of Fig. 5, a box
# with a diagonal (Fig. 4a) and a tree with a T junction. Tokens: x=0/1, y=2/3, d=4/5.
SETS = [
    [(3, 0), (0, 2), (1, 2), (1, 3)],
    [(3, 0), (1, 2), (0, 4, 2), (1, 5, 3)],
    [(1,), (0,), (3,), (2,), (1, 0, 2), (1, 3, 0)],
]


def rotation_equal(a, b) -> bool:
    return len(a) == len(b) and (not a or any(a[i:] + a[:i] == b for i in range(len(a))))


def grow(rings, choices):
    """Glue along a random path through the hierarchy (loop gluings included)."""
    prims = [primitive_graph(p, len(r)) for p, r in enumerate(rings)]
    g = prims[choices[0] % len(prims)]
    out = [g]
    for c in choices[1:]:
        kids = [k for _, k, _ in children(g, prims, rings)]
        if not kids:
            break
        g = kids[c % len(kids)]
        out.append(g)
        if g.is_complete:
            break
    return out


@settings(max_examples=60, deadline=None)
@given(st.integers(0, len(SETS) - 1), st.lists(st.integers(0, 10_000), min_size=1, max_size=9))
def test_rewrite_matches_walk_and_winds_once(which, choices):
    rings = SETS[which]
    for g in grow(rings, choices):
        if g.is_complete:
            assert g.string(rings) == (bd.UP,)
            continue
        assert sum(n for _, n in g.gaps) == 1          # P − N = 1
        walked = tuple(face_walk(Side(g.verts, g.edges, ()), g.gaps[0][0], rings))
        assert rotation_equal(walked, g.gaps)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, len(SETS) - 1), st.lists(st.integers(0, 10_000), min_size=1, max_size=9),
       st.randoms(use_true_random=False))
def test_canonical_key_ignores_vertex_numbering(which, choices, rnd):
    rings = SETS[which]
    ring_len = [len(r) for r in rings]
    g = grow(rings, choices)[-1]
    perm = list(range(len(g.verts)))
    rnd.shuffle(perm)
    verts = [0] * len(perm)
    for old, new in enumerate(perm):
        verts[new] = g.verts[old]
    edges = []
    for v, i, w, j in g.edges:
        a, b = sorted(((perm[v], i), (perm[w], j)))
        edges.append((a[0], a[1], b[0], b[1]))
    gaps = tuple(((perm[v], i), n) for (v, i), n in g.gaps)
    h = Graph(tuple(verts), tuple(sorted(edges)), gaps)
    assert canonical_key(g, ring_len) == canonical_key(h, ring_len)


def test_paper_rewrite_examples():
    rings = SETS[0]
    bl, br, tr = (primitive_graph(p, 2) for p in (1, 2, 3))
    # Branch gluing x̄y∧ to the x of xy∧ replaces x by y∧∨: the U shape yy∧.
    u = branch_glue(bl, (0, 0), br, (0, 0), rings)
    assert bd.canonical(u.string(rings)) == bd.canonical((2, 2, bd.UP))
    # A Z shape has the boundary of a straight y edge: ȳy∧.
    z = branch_glue(bl, (0, 0), tr, (0, 0), rings)
    assert bd.canonical(z.string(rings)) == bd.canonical((3, 2, bd.UP))


def test_loop_gluing_closes_the_rectangle():
    rings = SETS[0]
    prims = [primitive_graph(p, 2) for p in range(4)]
    g = prims[1]
    # BL, then BR on x, TR on BR's y, TL on TR's x̄: a chain of four corners.
    g = branch_glue(g, (0, 0), prims[2], (0, 0), rings)
    g = branch_glue(g, (1, 1), prims[3], (0, 1), rings)
    g = branch_glue(g, (2, 0), prims[0], (0, 1), rings)
    ks = [k for k in range(len(g.gaps)) if loop_gluable(g, k, rings)]
    assert len(ks) == 1
    closed = loop_glue(g, ks[0])
    assert closed.is_complete and len(closed.edges) == 4


def test_random_sequences_keep_edges_consistent():
    rnd = random.Random(7)
    for rings in SETS:
        for _ in range(20):
            g = grow(rings, [rnd.randrange(1000) for _ in range(8)])[-1]
            glued = [(v, i) for v, i, _, _ in g.edges] + [(w, j) for _, _, w, j in g.edges]
            open_ = [s for s, _ in g.gaps]
            assert len(set(glued)) == len(glued)
            assert sorted(glued + open_) == sorted(
                (v, i) for v, p in enumerate(g.verts) for i in range(len(rings[p])))


@settings(max_examples=60, deadline=None)
@given(st.integers(0, len(SETS) - 1), st.lists(st.integers(0, 10**6), min_size=1, max_size=12))
def test_units_record_the_blocks_glued(which, choices):
    """Each graph records its block instances: laid out in order, they cover its vertices, each
    with the block's own primitives (so the turning analysis can find a gap's unit slot)."""
    from compiler.gluing import unit_places
    rings = SETS[which]
    for g in grow(rings, choices):
        places = unit_places(g, [1] * len(rings))
        assert places is not None
        assert [g.verts[base] for _, base in places] == list(g.units)


@given(st.integers(0, len(SETS) - 1), st.lists(st.integers(0, 10_000), min_size=1, max_size=9),
       st.lists(st.integers(0, 10_000), min_size=1, max_size=9))
def test_a_graph_that_holds_another_has_as_many_edges_of_each_kind(which, one, two):
    """The compiler skips a left side whose edge counts a graph does not reach; that is sound
    only if every graph that holds another has at least its edges of each kind."""
    from compiler.occurrence import Host, Pattern, contains
    rings = SETS[which]
    for small in grow(rings, one):
        for big in grow(rings, two):
            if contains(Pattern.of(small), Host(big.verts, big.edges)):
                assert all(big.edge_counts[e] >= n for e, n in small.edge_counts.items())
    # Along one path of the hierarchy each graph holds its parent.
    path = grow(rings, one)
    for a, b in zip(path, path[1:]):
        if len(b.verts) > len(a.verts):
            assert contains(Pattern.of(a), Host(b.verts, b.edges))
