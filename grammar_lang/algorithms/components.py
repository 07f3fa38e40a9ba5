"""Union-find and connected components, written once for the whole project.

`glued_parts` cuts a graph of primitive instances into its components, renumbered. Two forms
of the rest, because the callers are of two sizes. `DisjointSet` and `components` are plain
Python over a few dozen items (a rule side, a rewrite's new vertices), where building a scipy
matrix would cost more than the walk; `component_labels` hands whole drawings (thousands of
segments, as numpy arrays) to scipy's compiled `connected_components`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Callable, Hashable, Iterable, Sequence, TypeVar

if TYPE_CHECKING:
    import numpy as np

T = TypeVar("T", bound=Hashable)


class DisjointSet:
    """Union-find with path halving. `union` keeps the smaller root, so with comparable items a
    set's root is its smallest member (callers order their groups by it)."""

    __slots__ = ("parent",)

    def __init__(self, items: Iterable[T] = ()):
        self.parent: dict = {x: x for x in items}

    def find(self, x: T) -> T:
        parent = self.parent
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    def union(self, a: T, b: T) -> None:
        ra, rb = self.find(a), self.find(b)
        if ra != rb:
            if rb < ra:
                ra, rb = rb, ra
            self.parent[rb] = ra

    def groups(self) -> list[list]:
        """The sets, each in the order its members were added, in the order of their roots."""
        out: dict = {}
        for x in self.parent:
            out.setdefault(self.find(x), []).append(x)
        return [out[k] for k in sorted(out)]


def components(items: Iterable[T], pairs: Iterable[tuple[T, T]]) -> list[list[T]]:
    """The connected components of the graph on `items` with edges `pairs`: each component
    sorted, the components in order of their smallest member."""
    ds = DisjointSet(sorted(items))
    for a, b in pairs:
        ds.union(a, b)
    return ds.groups()


def glued_components(items: Iterable[T],
                     edges: Iterable[tuple[T, int, T, int]]) -> list[list[T]]:
    """`components` for graphs whose edges glue slots: (vertex, slot, vertex, slot)."""
    return components(items, ((v, w) for v, _, w, _ in edges))


def glued_parts(labels: Sequence[int], edges: Iterable[tuple[int, int, int, int]]
                ) -> list[tuple[tuple[int, ...], tuple[tuple[int, int, int, int], ...]]]:
    """The connected components of a graph on vertices 0..n-1 with primitive `labels[v]` and
    glued slot pairs `edges`, each renumbered from 0 in vertex order: (labels, sorted edges)."""
    edges = list(edges)
    comps = glued_components(range(len(labels)), edges)
    where: dict[int, tuple[int, int]] = {}      # vertex → (its component, its new number)
    for c, comp in enumerate(comps):
        for k, v in enumerate(comp):
            where[v] = (c, k)
    local: list[list] = [[] for _ in comps]    # each edge filed once: linear, not n × m
    for v, i, w, j in edges:
        c, a = where[v]
        local[c].append((a, i, where[w][1], j))
    return [(tuple(labels[v] for v in comp), tuple(sorted(es))) for comp, es in zip(comps, local)]


def component_labels(n: int, ends: np.ndarray) -> tuple[int, np.ndarray]:
    """How many connected components the graph on `n` vertices with the undirected edges of
    the (m, 2) array `ends` has, and each vertex's component number (scipy's numbering)."""
    # Imported here, not at the top: the small-graph helpers above are on every command's
    # start-up path (rule sides), and numpy + scipy.sparse cost 0.6 s to import.
    import numpy as np
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    ends = np.asarray(ends, dtype=np.int64).reshape(-1, 2)
    graph = coo_matrix((np.ones(len(ends)), (ends[:, 0], ends[:, 1])), shape=(n, n))
    count, labels = connected_components(graph, directed=False)
    return int(count), labels


def seed_groups(seeds: Iterable[T], neighbours: Callable[[T], Iterable[T]]) -> int:
    """How many connected components of a graph (given by `neighbours`) the `seeds` lie in.

    For a rewriting step that may cut a drawing in two (schedule.py): its new parts must still
    hang together through the rest of the drawing, which may be large. So the graph is not
    walked whole: one search grows from each seed, one vertex at a time in turn, searches
    merge where they meet, and a group of searches that runs out of vertices is a component
    of its own. The work is that of the smaller parts, times the seeds: a cut-off piece is
    found in the time it takes to walk it, and seeds that hang together in the time their
    searches take to meet."""
    order = list(dict.fromkeys(seeds))
    owner: dict = {}
    ds = DisjointSet(range(len(order)))
    frontier: list[list] = []
    for k, s in enumerate(order):
        owner[s] = k
        frontier.append([s])
    groups, closed = len(order), 0      # `closed`: groups found to be whole components
    while groups - closed > 1:
        live = [k for k in range(len(order)) if frontier[k]]
        done = {ds.find(k) for k in range(len(order))} - {ds.find(k) for k in live}
        if len(done) > closed:
            closed = len(done)
            continue
        for k in live:
            v = frontier[k].pop()
            for w in neighbours(v):
                o = owner.get(w)
                if o is None:
                    owner[w] = k
                    frontier[k].append(w)
                elif ds.find(o) != ds.find(k):
                    ds.union(o, k)
                    groups -= 1
    return groups
