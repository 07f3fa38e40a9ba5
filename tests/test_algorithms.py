"""The kernel in grammar_lang/algorithms, checked against networkx on random graphs."""

import networkx as nx
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from grammar_lang.algorithms.components import (DisjointSet, component_labels, components,
                                                glued_components)

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
