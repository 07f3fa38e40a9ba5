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
