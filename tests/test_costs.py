"""No cost collapses a drawing to nothing (issue "Scenes"): each named cost keeps a run
growing, with or without a frame, and what it draws passes the verifier."""

import functools
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from compiler.infer import compile_example
from grammar_lang.loader import load_example
from runtime.engine.costs import (DensityCost, LabelCost, SceneCost, SizeCost, Stats, default_cost,
                                  ornaments, parse_cost)
from runtime.engine.generate import Engine
from runtime.verifier import check_drawing

from conftest import CORPUS, ILLUSTRATIONS

ROOT = Path(__file__).resolve().parent.parent
# Unframed corpus drawings of loose pieces, shipped examples with and without a frame.
PATHS = {"angle": CORPUS / "angle.svg", "square-filled": CORPUS / "square-filled.svg",
         "house": ROOT / "examples" / "house.gg", "corners": ROOT / "examples" / "corners.gg",
         "castle-scene": ROOT / "examples" / "castle-scene.gg"}


@functools.lru_cache(maxsize=None)
def _compiled(name):
    ex = load_example(PATHS[name])
    return ex, compile_example(ex).grammar


def _a_name(ex) -> str:
    """A face label of the example, or where it has none (loose lines) an edge label."""
    faces = [f for l in ex.labels for f in (l.left, l.right) if f != ex.exterior]
    return faces[0] if faces else ex.labels[0].name


@pytest.mark.parametrize("name", sorted(PATHS))
@pytest.mark.parametrize("spec", ["density:0.3", "density:0.02", "label:NAME:0.5", "scene",
                                  "size"])
def test_no_cost_collapses_the_drawing(name, spec):
    ex, g = _compiled(name)
    cost = parse_cost(spec.replace("NAME", _a_name(ex)), g.header.labels, 150, g.header)
    eng = Engine(g, seed=3, cost=cost)
    eng.run(150)
    framed = g.header.frame is not None
    # More than the frame alone, and, unframed, at least one copy of the example's size.
    least = len(g.header.frame.corners) + 1 if framed else min(
        10, sum(p.count for p in g.header.primitives))
    assert len(eng.host) >= least, f"{spec} left {len(eng.host)} vertices"
    assert check_drawing(ex, eng.host.to_drawing()) == []


def _stats(n: int, area: float, counts=(0,), edges: int = 0) -> Stats:
    return Stats(n, edges, tuple(counts), area)


@given(st.floats(0.001, 10.0), st.integers(1, 5000))
def test_unframed_density_is_not_met_by_the_empty_drawing(d, n):
    """Without a frame the box shrinks with the drawing: the size term is what keeps the
    empty drawing (no vertices, no area) from meeting the density exactly."""
    cost = DensityCost(d, SizeCost(n))
    assert cost.value(_stats(n, n / d)) < cost.value(_stats(0, 0.0))


@given(st.floats(0.0, 1.0), st.integers(2, 5000))
def test_a_label_share_is_not_met_by_the_empty_drawing(f, n):
    cost = LabelCost((0,), f, SizeCost(n))
    held = round(f * n)
    assert cost.value(_stats(n, 1.0, (held,), n)) < cost.value(_stats(0, 0.0))


PREDICTED = ["square-filled", "branches", "a", "h-complex", "curl"]


@pytest.mark.parametrize("name", PREDICTED + ["illustration:village", "illustration:castle"])
def test_the_counts_a_move_predicts_are_the_counts_it_makes(name):
    """The cost's coin is tossed on the counts a move predicts before it is matched
    (Engine._delta); every match with its interface glued must make exactly those counts.
    Counted without the edges that join a part to the ends of the bare edge it replaces, the
    village's dips were predicted one edge where they make five, and the exact test refused
    most of them."""
    from conftest import ILLUSTRATIONS
    from runtime.engine.rewrite import plan
    path = ILLUSTRATIONS / f"{name.split(':')[1]}.gg" if ":" in name else CORPUS / f"{name}.svg"
    if not path.exists():
        pytest.skip(f"{path.name} is not in the corpus")
    g = compile_example(load_example(path)).grammar
    eng = Engine(g, seed=1)
    eng.run(40)
    checked = 0
    for move in eng.moves():
        for match in eng.matches(move, limit=3):
            change = plan(eng.host, move, match, eng.schedule.spo)
            if any(s is None for s in change.partner.values()):
                continue        # an open slot: not every interface slot is glued
            exact, predicted = eng.stats(change), eng._stats_after(eng._delta(move))
            assert (exact.vertices, exact.edges, exact.label_count) == \
                (predicted.vertices, predicted.edges, predicted.label_count), move.name
            checked += 1
    assert checked >= 3


# --- ornaments: classes whose lines meet only lines in the open space --------------------

_HEADERS = {
    **{f"illustration:{n}": ILLUSTRATIONS / f"{n}.gg"
       for n in ("castle", "flowers", "space-station", "village")},
    **{f"example:{p.stem}": p for p in sorted((ROOT / "examples").glob("*.gg"))},
}


@functools.lru_cache(maxsize=None)
def _header(name):
    return compile_example(load_example(_HEADERS[name])).grammar.header


def test_the_ornaments_are_the_stations_panels_and_the_flowers_blossoms():
    def classes(name):
        h = _header(name)
        return sorted({h.labels[k].cls for k in ornaments(h)})
    assert classes("illustration:space-station") == ["7", "9"]     # the two kinds of panel
    assert classes("illustration:flowers") == ["1"]                # the blossoms, on stems
    for name in _HEADERS:
        if name not in ("illustration:space-station", "illustration:flowers"):
            assert classes(name) == [], name


# No deadline: an example's first draw compiles it (a second or so), later ones reuse it.
@settings(deadline=None)
@given(st.sampled_from(sorted(_HEADERS)))
def test_an_ornament_meets_only_lines_in_the_open_space_and_is_outside_every_share(name):
    h = _header(name)
    loose = ornaments(h)
    cost = default_cost(h, 500)
    assert set(cost.loose) == loose
    assert not any(loose.intersection(g) for g in cost.groups)
    labels = h.labels
    space = {f for t in h.primitives[h.frame.corners[0].prim].ring
             for f in (labels[t >> 1].left, labels[t >> 1].right)} if h.frame else set()
    for p in h.primitives:
        if any(t >> 1 in loose for t in p.ring):
            assert all({labels[t >> 1].left, labels[t >> 1].right} <= space
                       and labels[t >> 1].cls not in {c.name for c in h.classes if c.border}
                       for t in p.ring), (name, p.name)


def test_an_ornament_costs_nothing_and_leaves_the_shares_where_they_were():
    # Two groups of a half each, and label 2 loose: its edges change no group's expected count.
    cost = SceneCost(SizeCost(0), ((0,), (1,)), (0.5, 0.5), loose=(2,))
    held = Stats(0, 20, (10, 10, 0), 0.0)
    assert cost.proportions(held) == 0.0
    assert cost.proportions(Stats(0, 120, (10, 10, 100), 0.0)) == 0.0
    # Without the label loose, the same hundred edges put both groups far under their share.
    plain = SceneCost(SizeCost(0), ((0,), (1,)), (0.5, 0.5))
    assert plain.proportions(Stats(0, 120, (10, 10, 100), 0.0)) > 80.0     # 2 × (50 − √60)


def test_the_stations_trusses_fill_with_panels_and_keep_every_part():
    """At its seed the paper's station draws several times the example's share of panels
    once its column of modules is full: they are ornaments of its trusses (before they were,
    the scene cost held them near their share, 0.8-1.4 of it, and the trusses stayed bare)."""
    ex = load_example(_HEADERS["illustration:space-station"])
    grammar = compile_example(ex).grammar
    header = grammar.header
    eng = Engine(grammar, seed=22, cost=default_cost(header, 1500))
    eng.run(None, iterations=1500)
    h = eng.host
    counts = h.label_count
    loose = ornaments(header)
    per = [0.0] * len(header.labels)
    for p in header.primitives:
        for t in p.ring:
            per[t >> 1] += p.count / 2
    share = sum(per[k] for k in loose) / sum(per)
    assert sum(counts[k] for k in loose) / h.n_edges > 2.0 * share
    drawn = {h.t.label_class[h.t.label[h.prim[v]][i]] for v, i, _, _ in h.edges()}
    assert drawn == {l.cls for l in header.labels}
    assert check_drawing(ex, h.to_drawing()) == []


# --- ratios: how far a drawing keeps its example's proportions (benchmarks/paper.py) -------

@settings(deadline=None)
@given(st.lists(st.integers(0, 300), min_size=3, max_size=3),
       st.floats(0.05, 0.9), st.booleans())
def test_a_ratio_is_a_groups_edges_over_what_its_share_asks_for(counts, share, loose):
    cost = SceneCost(SizeCost(0), ((0,), (1,)), (share, 1.0 - share), loose=(2,) if loose else ())
    edges = sum(counts)
    whole = edges - counts[2] if loose else edges
    ratios = cost.ratios(Stats(0, edges, tuple(counts), 0.0))
    if whole == 0:
        assert ratios == (1.0, 1.0)
    else:
        assert ratios[0] * share * whole == pytest.approx(counts[0])
        assert ratios[1] * (1.0 - share) * whole == pytest.approx(counts[1])


@pytest.mark.parametrize("name", ["space-station", "village"])
def test_a_scene_that_starts_from_its_example_starts_in_its_proportions(name):
    grammar = compile_example(load_example(_HEADERS[f"illustration:{name}"])).grammar
    cost = default_cost(grammar.header, 100)
    ratios = cost.ratios(Engine(grammar, seed=0).stats())
    assert ratios == pytest.approx((1.0,) * len(cost.groups))
