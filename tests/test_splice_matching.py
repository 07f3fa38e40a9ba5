"""Spliced sides are matched across the host face they face (runtime.engine.matching).

Two independent readings of a drawing's faces are compared: the walk over the rings' slot
order (`grammar_lang.algorithms.faces.FaceWalk`, what the matcher walks) and the faces found
from the geometry (`boundary_cycles`, edges sorted by angle). Then every step of a spliced
side's boundary from one part to another, between parts of one structure, must cross one
geometric face: before, the nearest place within 2 units was taken, often the next edge along
the same line, whose other side faces away.
"""

from functools import lru_cache

import networkx as nx
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from compiler.infer import compile_example
from grammar_lang.algorithms.faces import FaceWalk, boundary_cycles
from grammar_lang.loader import load_example
from runtime.engine.costs import default_cost
from runtime.engine.generate import Engine
from runtime.engine.matching import _corner, iter_matches

from conftest import CORPUS, ILLUSTRATIONS  # noqa: E402
SOURCES = {
    "village": ILLUSTRATIONS / "village.gg",
    "castle": ILLUSTRATIONS / "castle.gg",
    "h-complex": CORPUS / "h-complex.svg",
    "triangle-curl": CORPUS / "triangle-curl.svg",
}


@lru_cache(maxsize=None)
def _grammar(name: str):
    return compile_example(load_example(SOURCES[name])).grammar


def _grown(name: str, seed: int, steps: int) -> Engine:
    g = _grammar(name)
    engine = Engine(g, seed=seed, cost=default_cost(g.header, 4 * steps + 40))
    engine.run(steps, iterations=6 * steps)
    return engine


def _geometric_faces(host):
    """Slot (v, i) → the geometric face on the left of the edge arriving at v through slot i
    (the face of corner (v, i - 1))."""
    verts = sorted(host.link)
    index = {v: k for k, v in enumerate(verts)}
    edges = host.edges()
    xy = np.array([host.pos[v] for v in verts], dtype=float)
    ends = np.array([(index[v], index[w]) for v, _, w, _ in edges], dtype=np.int64).reshape(-1, 2)
    cycle_of, _ = boundary_cycles(xy, ends)
    face = {}
    for e, (v, i, w, j) in enumerate(edges):
        face[(v, i)] = cycle_of[2 * e + 1]        # w → v, arriving at v through slot i
        face[(w, j)] = cycle_of[2 * e]
    return face


def _corner_face(host, face, corner):
    """The geometric face a corner (v, c) lies in: the sector after slot c, which is on the
    left of the edge that arrives at v through slot c + 1."""
    v, c = corner
    return face[(v, (c + 1) % len(host.link[v]))]


@given(st.sampled_from(sorted(SOURCES)), st.integers(0, 3), st.integers(0, 60))
@settings(max_examples=12, deadline=None)
def test_the_ring_walks_are_the_drawings_faces(name, seed, steps):
    host = _grown(name, seed, steps).host
    face = _geometric_faces(host)
    walks = {}
    for v in sorted(host.link):
        for c in range(len(host.link[v])):
            if (v, c) not in walks:
                walk = FaceWalk(host.link, host.pos, (v, c), 10 ** 6)
                assert walk.closed
                for k in walk.corners:
                    walks[k] = walk.start
    # Each structure has one walk round its outside; every other walk bounds its face.
    starts = set(walks.values())
    outside = [w for w in starts if not FaceWalk(host.link, host.pos, w, 10 ** 6).encloses]
    n_parts = nx.number_connected_components(nx.Graph(
        [(v, w) for v, _, w, _ in host.edges()]))
    assert len(outside) == n_parts
    by_walk, by_geometry = {}, {}
    for k, w in walks.items():
        by_walk.setdefault(w, set()).add(k)
        by_geometry.setdefault(_corner_face(host, face, k), set()).add(k)
    assert sorted(map(sorted, by_walk.values())) == sorted(map(sorted, by_geometry.values()))


@pytest.mark.parametrize("name,seed,steps", [("village", 65, 0), ("village", 1, 30),
                                             ("castle", 2, 40)])
def test_spliced_parts_of_one_structure_face_each_other(name, seed, steps):
    engine = _grown(name, seed, steps)
    host = engine.host
    face = _geometric_faces(host)
    comp = {v: k for k, c in enumerate(nx.connected_components(nx.Graph(
        [(v, w) for v, _, w, _ in host.edges()]))) for v in c}
    checked = 0
    for move in engine.moves():
        pat = move.pattern
        if len(pat.order) < 2:
            continue
        for m in iter_matches(host, pat, engine.schedule.spo):
            vmap = dict(enumerate(m.vmap))
            wmap = dict(enumerate(m.wmap))
            for a, b in list(pat.jumps) + [e for e in pat.entries if e is not None]:
                ca, cb = _corner(host, a, vmap, wmap, True), _corner(host, b, vmap, wmap, False)
                if comp[ca[0]] == comp[cb[0]]:
                    assert _corner_face(host, face, ca) == _corner_face(host, face, cb), \
                        f"{move.rule.name}: {a} and {b} face different faces"
                    checked += 1
    assert checked > 0
