"""Slides (runtime.geometry.slides): a part found for a failed edge moves along that edge's
direction without bending or breaking any edge but its seams, and generation places with
them."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import ILLUSTRATIONS
from report.ggrun import compile_example
from runtime.engine.costs import default_cost
from runtime.engine.generate import Engine
from runtime.geometry import solver as solver_module
from runtime.geometry.slides import LIMIT, PARALLEL, NoPart, Slide, sliding_part
from runtime.run_cmd import load_grammar


@pytest.fixture(scope="module")
def castle():
    """The paper's castle after 600 iterations: blocks, towers and walls on the ground."""
    grammar = load_grammar(str(ILLUSTRATIONS / "castle.gg"), compile_example)
    eng = Engine(grammar, seed=3, cost=default_cost(grammar.header, 600))
    for _ in range(600):
        eng.step()
    return eng.host


def _adjacency(host):
    return lambda v: [(i, s) for i, s in enumerate(host.link[v]) if s is not None]


def _bounds(host):
    def bounds(v, i, w, j):
        lo, hi = host.t.lengths[host.t.label[host.prim[v]][i]][:2]
        d = host.t.direction[host.prim[v]][i]
        now = d[0] * (host.pos[w][0] - host.pos[v][0]) + d[1] * (host.pos[w][1] - host.pos[v][1])
        return lo, hi, now
    return bounds


@settings(max_examples=150, deadline=None)
@given(pick=st.integers(0, 10 ** 6), sign=st.sampled_from((1, -1)),
       need=st.floats(-80.0, 80.0), far=st.booleans())
def test_a_part_moves_along_its_edge_bending_nothing(castle, pick, sign, need, far):
    """Whatever edge failed and by how much, with seams at the cut or further beyond (FAR):
    every edge from the part to the rest of the drawing is a seam, parallel to the failed
    edge and of free length, so a translation along it keeps every direction; the part holds
    neither end it must leave, no pinned vertex, no more than LIMIT vertices, and each
    member's offset is where it lies; a part is too large only where the limit stopped it."""
    host = castle
    slots = sorted((v, i) for v in host.link for i, s in enumerate(host.link[v]) if s is not None)
    v, i = slots[pick % len(slots)]
    w, _ = host.link[v][i]
    t = host.t
    d = t.direction[host.prim[v]][i]
    held, other = (w, v) if sign == 1 else (v, w)
    def search(limit=LIMIT):
        return sliding_part(host, _adjacency(host), host.prim.__getitem__, _bounds(host), held,
                            {other}, d, sign, need, frozenset(), limit=limit, far=far)
    part = search()
    if part is NoPart.LARGE:
        # Too large only where the limit stopped the search: without it, something else does,
        # or the part is found, larger than the limit.
        unbounded = search(limit=10 ** 9)
        assert unbounded is not NoPart.LARGE
        assert not isinstance(unbounded, Slide) or len(unbounded.offsets) + 1 > LIMIT
        return
    if not isinstance(part, Slide):
        assert part in (NoPart.HELD, NoPart.OTHER)
        return
    members = {part.anchor, *part.offsets}
    assert other not in members and not members & host.pinned and len(members) <= LIMIT
    seams = 0
    for x in members:
        px = host.prim[x]
        for k, s in enumerate(host.link[x]):
            if s is None or s[0] in members:
                continue
            dx = t.direction[px][k]
            assert abs(dx[0] * d[1] - dx[1] * d[0]) < PARALLEL
            assert t.lengths[t.label[px][k]][2] is None
            seams += 1
    assert seams
    a = host.pos[part.anchor]
    for m, (ox, oy) in part.offsets.items():
        assert math.isclose(host.pos[m][0], a[0] + ox) and math.isclose(host.pos[m][1], a[1] + oy)
    own = [(x, s[0]) for x in members for k, s in enumerate(host.link[x])
           if s is not None and s[0] in members and (x, k) < s]
    assert sorted(part.edges) == sorted(own)


def _slid_placements(monkeypatch, name: str, seed: int, n: int, slid) -> list:
    """The placements found in `n` iterations of the paper's `name` by solvers that
    `slid(solver)` says slid a part."""
    placed = []
    real = solver_module.Solver.placements

    def placements(self):
        for p in real(self):
            if slid(self):
                placed.append(p)
            yield p

    monkeypatch.setattr(solver_module.Solver, "placements", placements)
    grammar = load_grammar(str(ILLUSTRATIONS / f"{name}.gg"), compile_example)
    eng = Engine(grammar, seed=seed, cost=default_cost(grammar.header, n))
    for _ in range(n):
        eng.step()
    return placed


def test_castle_steps_place_by_sliding(monkeypatch):
    """On the paper's castle some placements come from rounds that slid a part, and every
    drawing made so stays valid (the corpus and scene tests check the drawings)."""
    assert _slid_placements(monkeypatch, "castle", 1, 800, lambda solver: bool(solver.slides))


def test_the_village_places_by_sliding_a_house_along_a_surface(monkeypatch):
    """The paper's village: its strip lines and surfaces run from one side of the frame to
    the other, so every part beyond a cut along them is held by the frame, and none has its
    seams at the cut alone. With seams further beyond (slides.FAR) a house and the stretch
    past it give the room, and some of the village's placements come from such slides."""
    from runtime.geometry import freeing
    far_parts = {}      # id → part: held, so that no later part gets a far part's id
    real = freeing.sliding_part

    def sliding_part(*args, far=False, **kw):
        part = real(*args, far=far, **kw)
        if far and isinstance(part, Slide):
            far_parts[id(part)] = part
        return part

    monkeypatch.setattr(freeing, "sliding_part", sliding_part)
    assert _slid_placements(monkeypatch, "village", 65, 1500, lambda solver: any(
        far_parts.get(id(part)) is part for part in solver.slides.values()))
