"""A move's late rounds (after two in a row with no room) are skipped only once its record
says they rarely place, and skipping them only cuts a proposal's placements short."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import CORPUS
from report.ggrun import compile_example
from runtime.engine.costs import SizeCost
from runtime.engine.generate import Engine
from runtime.engine.late import PAYS, PROBE, TRIAL, LateRounds
from runtime.engine.rewrite import plan
from runtime.geometry.solver import Solver
from runtime.run_cmd import load_grammar

KEY = ("r1", True)


def test_late_rounds_go_on_until_tried_and_while_they_pay():
    late = LateRounds()
    assert all(late.go_on(KEY) for _ in range(TRIAL))
    # None placed in TRIAL tries: from now on only one ask in PROBE goes on.
    answers = [late.go_on(KEY) for _ in range(3 * PROBE)]
    assert answers == [k % PROBE == 0 for k in range(3 * PROBE)]
    # Enough placed (PAYS of the tries): every ask goes on again.
    tried = late.record[KEY][0]
    for _ in range(int(PAYS * (tried + PROBE)) + 1):
        late.placed(KEY)
    assert all(late.go_on(KEY) for _ in range(PROBE))
    # Each move keeps its own record.
    assert late.go_on(("r1", False)) and late.record[("r1", False)] == [1, 0, 0]


@pytest.fixture(scope="module")
def crowded():
    """Curl grown to 1,200 vertices (dense enough that rounds run out of room) and proposals
    there: (move, match) pairs as the schedule draws them."""
    grammar = load_grammar(str(CORPUS / "curl.svg"), compile_example)
    eng = Engine(grammar, seed=0, cost=SizeCost(1200))
    eng.run(20000, stop=lambda: len(eng.host) >= 1200)
    rng = np.random.default_rng(1)
    props = []
    while len(props) < 40:
        choice = eng.schedule.choose(eng.host, rng, eng.applied_by_level)
        props.append(choice[1:3])
    return eng, props


def _placements(eng, move, match, seed, go_on):
    """The placements a solver yields for one proposal (the positions in its vertices' order:
    each plan gives the new vertices fresh ids), and how often it asked whether to go on."""
    asked = []

    def ask():
        asked.append(1)
        return go_on()

    # As Engine.apply makes it, the engine's generator seeded afresh.
    change = plan(eng.host, move, match, eng.schedule.spo)
    rng = eng.rng = np.random.default_rng(seed)
    fixed, floating = eng._center(change), eng._floating(change)
    centre = (lambda: eng._center(change)) if floating else (lambda: fixed)
    solver = Solver(eng.host, change, rng, centre, eng.I, eng.J, floating, eng.systems,
                    go_on=ask if go_on is not None else None)
    return [list(p.positions.values()) for p in solver.placements()], len(asked)


@settings(max_examples=60, deadline=None)
@given(k=st.integers(0, 39), seed=st.integers(0, 2 ** 32 - 1))
def test_skipping_late_rounds_only_cuts_the_placements_short(crowded, k, seed):
    """With the late rounds skipped, a proposal yields the first placements it yields with
    them, and no others; going on gives exactly what the solver gave with no one to ask."""
    eng, props = crowded
    move, match = props[k]
    full, _ = _placements(eng, move, match, seed, None)
    cut, asked = _placements(eng, move, match, seed, lambda: False)
    assert full[:len(cut)] == cut
    assert asked <= 1
    same, _ = _placements(eng, move, match, seed, lambda: True)
    assert same == full


def test_the_question_is_asked_in_crowded_places(crowded):
    """Not vacuous: some of the proposals reach two rounds with no room."""
    eng, props = crowded
    asked = sum(_placements(eng, m, x, s, lambda: False)[1]
                for m, x in props for s in range(5))
    assert asked > 0
