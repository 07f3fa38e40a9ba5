"""The kernel in grammar_lang/algorithms, checked against networkx on random graphs."""

import networkx as nx
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from grammar_lang.algorithms.canon import canonical_key
from grammar_lang.algorithms.components import (DisjointSet, component_labels, components,
                                                glued_components, glued_parts, seed_groups)

graphs = st.integers(0, 12).flatmap(lambda n: st.tuples(
    st.just(n), st.lists(st.tuples(st.integers(0, max(n - 1, 0)), st.integers(0, max(n - 1, 0))),
                         max_size=20 if n else 0)))


def nx_components(n, pairs):
    g = nx.Graph()
    g.add_nodes_from(range(n))
    g.add_edges_from(pairs)
    return sorted(sorted(c) for c in nx.connected_components(g))


@given(graphs)
@settings(max_examples=200, deadline=None)
def test_components_agree_with_networkx(graph):
    n, pairs = graph
    comps = components(range(n), pairs)
    assert comps == nx_components(n, pairs)          # sorted, ordered by smallest member
    slots = [(v, 0, w, 1) for v, w in pairs]
    assert glued_components(range(n), slots) == comps


@given(graphs)
@settings(max_examples=200, deadline=None)
def test_component_labels_partition_like_components(graph):
    n, pairs = graph
    count, labels = component_labels(n, np.array(pairs, dtype=np.int64).reshape(-1, 2))
    assert count == len(nx_components(n, pairs))
    groups: dict[int, list[int]] = {}
    for v in range(n):
        groups.setdefault(int(labels[v]), []).append(v)
    assert sorted(groups.values()) == nx_components(n, pairs)


def test_disjoint_set_roots_are_smallest_members_and_items_may_be_any_order():
    ds = DisjointSet([5, 3, 9, 1])
    ds.union(9, 3)
    ds.union(5, 1)
    assert ds.find(9) == 3 and ds.find(5) == 1
    assert ds.groups() == [[5, 1], [3, 9]]           # members in the order they were added


points = st.lists(st.tuples(st.integers(-50, 50), st.integers(-50, 50)), min_size=3, max_size=30,
                  unique=True)


@given(points)
@settings(max_examples=100, deadline=None)
def test_face_walk_on_a_triangulation_obeys_euler(pts):
    from scipy.spatial import Delaunay, QhullError

    from grammar_lang.algorithms.faces import boundary_cycles, half_ends, next_in_face
    xy = np.array(pts, dtype=float)
    try:
        tri = Delaunay(xy)
    except QhullError:                               # all points on a line
        return
    edges = sorted({tuple(sorted((int(s[i]), int(s[(i + 1) % 3])))) for s in tri.simplices
                    for i in range(3)})
    edges = np.array(edges, dtype=np.int64)
    nxt = next_in_face(xy, edges)
    assert sorted(nxt.tolist()) == list(range(2 * len(edges)))      # a permutation
    src, dst = half_ends(edges)
    assert (src[nxt] == dst).all()                   # the walk continues where it arrived
    cycle_of, cycles = boundary_cycles(xy, edges)
    assert sorted(h for c in cycles for h in c) == list(range(2 * len(edges)))
    assert all(cycle_of[h] == k for k, c in enumerate(cycles) for h in c)
    used = len(np.unique(edges))
    # One connected triangulation: V − E + F = 2, the outer face counted.
    assert used - len(edges) + len(cycles) == 2
    assert len(cycles) == len(tri.simplices) + 1


def test_join_interface_glues_each_chain_end_to_end():
    from grammar_lang.algorithms.dpo import join_interface
    a, b, c0, c1, c2 = (10, 0), (11, 1), (20, 0), (21, 1), (22, 0)
    # Point 0: new slot a to context c0. Points 1–2: a wire between contexts c1 and c2.
    # Point 3: new slot b, open outside.
    glue, opened = join_interface([c0, c1, c2, None], [a, (-1, 0), (-1, 1), b])
    assert glue == [(a, c0), (c1, c2)] and opened == [b]
    # A wire with one open end leaves the other context open.
    assert join_interface([None, c1], [(-1, 0), (-1, 1)]) == ([], [c1])
    # A host edge between interface points 0 and 1 (compiler): a's chain runs through it and
    # the wire 1–2 on to context c2; a bare loop (wire 3–4 closed by edge 4–3) vanishes.
    glue, opened = join_interface([1, 0, c2, 4, 3], [a, (-1, 0), (-1, 1), (-2, 0), (-2, 1)])
    assert glue == [(a, c2)] and opened == []


def test_anchored_matches_walk_from_each_root_and_ask_the_hook():
    from grammar_lang.algorithms.matching import anchored_matches, walk_plans
    # Pattern: a path p0 -(slot 0/1)- p1; host: a path of three vertices of alternating kinds.
    partner = {(0, 0): (1, 1), (1, 1): (0, 0)}
    plans = walk_plans([0, 1], partner)
    assert plans == (((0, 0, 1, 1),), ((1, 1, 0, 0),))
    link = {0: [(1, 1), None], 1: [(2, 1), (0, 0)], 2: [None, (1, 0)]}
    prim = {0: 7, 1: 7, 2: 7}
    found = list(anchored_matches(link, prim, [7, 7], plans, [(0, 0), (0, 1), (0, 2)]))
    assert found == [[0, 1], [1, 2]]
    assert list(anchored_matches(link, prim, [7, 7], plans, [(0, 0), (0, 1)],
                                 lambda img: img[0] != 0)) == [[1, 2]]


RING_LEN = (3, 2)       # two primitives: one with three slots, one with two


@st.composite
def glued_graphs(draw):
    """A connected graph of primitive instances: labels, and glued slot pairs (v, i, w, j)."""
    labels = draw(st.lists(st.integers(0, len(RING_LEN) - 1), min_size=1, max_size=6))
    # A spanning tree first, so every draw is connected (filtering disconnected ones out
    # made Hypothesis give up now and then): each vertex glues one of its slots to a free
    # slot of an earlier one. Every primitive has two slots or more, so one is always free.
    free = [(0, i) for i in range(RING_LEN[labels[0]])]
    pairs = []
    for v in range(1, len(labels)):
        mine = [(v, i) for i in range(RING_LEN[labels[v]])]
        a = free.pop(draw(st.integers(0, len(free) - 1)))
        b = mine.pop(draw(st.integers(0, len(mine) - 1)))
        pairs.append((a, b))
        free += mine
    order = draw(st.permutations(free))
    extra = draw(st.integers(0, len(order) // 2))
    pairs += list(zip(order[0:2 * extra:2], order[1:2 * extra:2]))
    edges = tuple(sorted(tuple(min(a, b)) + tuple(max(a, b)) for a, b in pairs))
    assert len(glued_components(range(len(labels)), edges)) == 1
    return tuple(labels), edges


def nx_glued(labels, edges):
    g = nx.MultiDiGraph()
    g.add_nodes_from((v, {"p": p}) for v, p in enumerate(labels))
    for v, i, w, j in edges:                 # both ways, so a slot pair reads from either end
        g.add_edge(v, w, slots=(i, j))
        g.add_edge(w, v, slots=(j, i))
    return g


@given(glued_graphs(), glued_graphs(), st.randoms(use_true_random=False))
@settings(max_examples=300, deadline=None)
def test_canonical_keys_are_equal_exactly_for_isomorphic_graphs(a, b, rnd):
    from networkx.algorithms.isomorphism import categorical_multiedge_match
    perm = list(range(len(a[0])))
    rnd.shuffle(perm)
    moved = [0] * len(perm)
    for old, new in enumerate(perm):
        moved[new] = a[0][old]
    renumbered = tuple(sorted(tuple(min(s, t)) + tuple(max(s, t)) for s, t in
                              (((perm[v], i), (perm[w], j)) for v, i, w, j in a[1])))
    assert canonical_key(*a, RING_LEN) == canonical_key(tuple(moved), renumbered, RING_LEN)
    same = nx.is_isomorphic(nx_glued(*a), nx_glued(*b), node_match=lambda x, y: x["p"] == y["p"],
                            edge_match=categorical_multiedge_match("slots", None))
    assert (canonical_key(*a, RING_LEN) == canonical_key(*b, RING_LEN)) == same


def test_canonical_key_tells_boundaries_apart_and_ignores_their_starting_slot():
    labels, edges = (0, 0), ((0, 0, 1, 0),)
    open_slots = [(0, 1), (0, 2), (1, 1), (1, 2)]
    ring = tuple((s, 0) for s in open_slots[:-1]) + ((open_slots[-1], 1),)
    key = canonical_key(labels, edges, RING_LEN, ring)
    assert canonical_key(labels, edges, RING_LEN, ring[2:] + ring[:2]) == key
    other = tuple((s, 1 if k == 0 else 0) for k, (s, _) in enumerate(ring))
    assert canonical_key(labels, edges, RING_LEN, other) != key


def test_glued_parts_renumber_each_component_from_zero():
    labels = (1, 0, 1, 0)
    edges = [(0, 0, 2, 1), (1, 0, 3, 2), (1, 1, 3, 0)]
    assert glued_parts(labels, edges) == [((1, 1), ((0, 0, 1, 1),)),
                                          ((0, 0), ((0, 0, 1, 2), (0, 1, 1, 0)))]


@given(st.integers(1, 40).flatmap(lambda n: st.tuples(
    st.just(n),
    st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), max_size=2 * n),
    st.lists(st.integers(0, n - 1), max_size=8))))
@settings(max_examples=300, deadline=None)
def test_seed_groups_counts_the_components_the_seeds_lie_in(case):
    n, edges, seeds = case
    g = nx.Graph()
    g.add_nodes_from(range(n))
    g.add_edges_from(edges)
    expected = len({min(nx.node_connected_component(g, s)) for s in seeds})
    assert seed_groups(seeds, lambda v: g.neighbors(v)) == expected
