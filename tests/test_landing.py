"""Free-standing components land in a face of their outer label (runtime/geometry/landing.py)."""

from __future__ import annotations

import pytest

from compiler.infer import compile_example
from grammar_lang.loader import load_example
from runtime.engine.costs import SizeCost
from runtime.engine.generate import Engine
from runtime.geometry.landing import outer_label
from runtime.engine.rewrite import plan
from runtime.engine.matching import Match
from runtime.verifier import check_drawing

WALL = """\
face stone
face glass
polygon stone rect (0, 0) (100, 60)
polygon glass rect (20, 20) (40, 40)
polygon glass rect (60, 20) (80, 40)
"""


@pytest.fixture(scope="module")
def wall(tmp_path_factory):
    path = tmp_path_factory.mktemp("landing") / "wall.gg"
    path.write_text(WALL, encoding="utf-8")
    return compile_example(load_example(path)).grammar


def _created(engine, move):
    """The outer label of what a starter creates, from its planned change."""
    change = plan(engine.host, move, Match(()), engine.schedule.spo)
    prim = dict(change.new)
    return outer_label(engine.host.t, prim,
                       lambda v, i: change.partner_after(engine.host, v, i))


def test_outer_label_of_each_starter(wall):
    grammar = wall
    engine = Engine(grammar, seed=0)
    creators = [m for m in engine.moves() if m.creates_component]
    got = sorted(_created(engine, m) for m in creators)
    # The wall stands in the exterior; a window (a separate component) lies inside stone.
    assert got == ["exterior", "stone"]


def test_windows_land_inside_stone(wall):
    # Windows are components of their own whose outside is stone: only the window starter
    # makes them, and the face test refuses one placed anywhere but inside a wall. Aimed into
    # stone corners, nearly every proposal lands (a random place near a random vertex: about
    # one in eight). Every drawing passes the verifier.
    grammar = wall
    tried = landed = 0
    for seed in range(5):
        engine = Engine(grammar, seed=seed, cost=SizeCost(80))
        for _ in range(300):
            out = engine.step()
            if out.reason == "cost" or out.move is None or not out.move.creates_component:
                continue
            if _created(engine, out.move) == "stone":
                tried += 1
                landed += out.applied is not None
        assert check_drawing(grammar, engine.host.to_drawing()) == []
    assert tried >= 50 and landed >= 0.8 * tried
