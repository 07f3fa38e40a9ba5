"""Scenes in a frame (paper Appendix A): the frame is the border of the space."""

import functools
import math
import statistics
from collections import Counter
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from compiler.cli import main as ggc
from compiler.infer import compile_example
from grammar_lang.diagnostics import UserError
from grammar_lang.frame import border_labels, border_primitives, corner_primitives, find_frame
from grammar_lang.ggr_emit import emit_ggr
from grammar_lang.ggr_parser import parse_ggr
from grammar_lang.loader import load_example
from runtime.engine.generate import Engine
from runtime.geometry.tables import PROPORTION
from report.ggrun import main as ggrun
from runtime.verifier import check_drawing

from conftest import ILLUSTRATIONS  # noqa: E402
NAMES = ["castle", "village", "flowers", "space-station"]


EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
SCENES = {"castle": ILLUSTRATIONS / "castle.gg", "castle-scene": EXAMPLES / "castle-scene.gg"}


@pytest.fixture(scope="module", params=sorted(SCENES))
def scene(request):
    ex = load_example(SCENES[request.param])
    return ex, compile_example(ex)


@pytest.fixture(scope="module")
def castle():
    ex = load_example(ILLUSTRATIONS / "castle.gg")
    return ex, compile_example(ex)


@pytest.mark.parametrize("name", NAMES)
def test_every_illustration_has_one_rectangular_frame(name):
    ex = load_example(ILLUSTRATIONS / f"{name}.gg")
    frame = find_frame(ex)
    assert frame is not None and len(frame.corners) == 4 and frame.axis_aligned
    assert frame.box == (20.0, -800.0, 1560.0, -20.0)      # SVG (20, 20)–(1560, 800), y up
    assert frame.contains(800, -400) and not frame.contains(10, -400)


def test_examples_without_a_frame_keep_todays_behaviour():
    for path in ("examples/house.gg", "examples/tree.gg", "examples/square-filled.gg"):
        ex = load_example(Path(__file__).resolve().parent.parent / path)
        assert find_frame(ex) is None


@pytest.mark.parametrize("path", ["examples/castle.gg", "examples/platform.gg"])
def test_a_ground_without_a_frame_is_closed_into_one(path):
    """A level ground line is the bottom side of a frame 4 grounds wide, on the side where
    the example stands, and 2 of its tallest shapes high; the ground's ends run on to the
    frame's sides, not vertices in the middle of a side."""
    from grammar_lang.grounding import GROUND_HEIGHTS, GROUND_WIDTHS
    from grammar_lang.loader import load_source
    src = load_source(Path(__file__).resolve().parent.parent / path)
    border = {n for n, c in src.classes.items() if c.border}
    ground = [p for item in src.paint if getattr(item, "cls", None) in border for p in item.points]
    drawn = [p for item in src.paint if getattr(item, "cls", None) not in border
             for p in (item.points if hasattr(item, "points") else
                       [q for ring in item.rings for q in ring])]
    ex = load_example(Path(__file__).resolve().parent.parent / path)
    frame = find_frame(ex)
    assert frame is not None and len(frame.corners) == 4 and frame.axis_aligned
    x0, y0, x1, y1 = frame.box
    gx = [p[0] for p in ground]
    assert x1 - x0 == pytest.approx(GROUND_WIDTHS * (max(gx) - min(gx)))
    assert y0 == ground[0][1]
    assert y1 - y0 == pytest.approx(GROUND_HEIGHTS * (max(p[1] for p in drawn) - y0))
    vertices = set(ex.graph.vertices)
    assert (min(gx), y0) not in vertices and (max(gx), y0) not in vertices


def assert_only_starters_float(host, g):
    """One component holds the frame; every other is one a starter makes (a window)."""
    free = {tuple(sorted(Counter(s.lhs.vertices).items())) for s in g.rules if s.is_starter}
    comps = host.components()
    framed = [c for c in comps if host.pinned & set(c)]
    assert len(framed) == 1
    for c in comps:
        if c is not framed[0]:
            assert tuple(sorted(Counter(host.prim[v] for v in c).items())) in free


def assert_inside_its_frame(host, frame):
    """The frame's corners are pinned where it has them, and every vertex lies inside it."""
    corners = sorted((host.pos[v], host.prim[v]) for v in host.pinned)
    assert corners == sorted(((c.x, c.y), c.prim) for c in frame.corners)
    x0, y0, x1, y1 = frame.box
    for v in host.vertices():
        x, y = host.pos[v]
        assert x0 - 1e-6 <= x <= x1 + 1e-6 and y0 - 1e-6 <= y <= y1 + 1e-6


FRAMED = sorted(p.name for p in EXAMPLES.glob("*.gg") if find_frame(load_example(p)) is not None)


@functools.lru_cache(maxsize=None)
def _framed(name):
    ex = load_example(EXAMPLES / name)
    return ex, compile_example(ex).grammar


def test_the_framed_examples_are_the_scenes():
    assert {"castle.gg", "castle-scene.gg", "flowers.gg", "platform.gg", "village.gg",
            "space-station.gg"} <= set(FRAMED)


# This project's versions of the paper's four illustrations (Fig. 1, Fig. 9b, 9f, 9g).
PAPER_SCENES = ["castle-scene.gg", "flowers.gg", "space-station.gg", "village.gg"]


@pytest.mark.parametrize("name", PAPER_SCENES)
def test_the_paper_scenes_grow_every_part_inside_one_frame(name):
    """Run as shipped (the default cost in a frame), each grows past its start: one frame,
    its corners where the example has them, every vertex inside it, every face label of the
    example in the drawing, and the verifier passes."""
    ex, g = _framed(name)
    from runtime.engine.costs import default_cost
    eng = Engine(g, seed=1, cost=default_cost(g.header, 120))
    start = len(g.header.frame.start.vertices) if g.header.frame.start else 4
    eng.run(120)
    host = eng.host
    assert len(host) > start + 20, f"{len(host)} vertices from a start of {start}"
    assert_inside_its_frame(host, g.header.frame)
    drawing = host.to_drawing()
    faces = {f for e in drawing.edges for f in (e.left, e.right)}
    assert faces == {f for l in g.header.labels for f in (l.left, l.right)}
    failures = check_drawing(ex, drawing)
    assert failures == [], "\n".join(f.render() for f in failures[:3])


@pytest.mark.parametrize("name", FRAMED)
@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4])
def test_framed_examples_grow_standing_on_their_ground(name, seed):
    """Every structure stands on the ground: one component holds the frame and all that
    touches it, and anything else is what the example has free-standing (a window)."""
    ex, g = _framed(name)
    from runtime.engine.costs import default_cost
    eng = Engine(g, seed=seed, cost=default_cost(g.header, 40))     # as ggrun runs it
    eng.run(40)
    host = eng.host
    assert len(host) > 4 + 4          # something stands on the frame
    assert_only_starters_float(host, g)
    failures = check_drawing(ex, host.to_drawing())
    assert failures == [], "\n".join(f.render() for f in failures[:3])


def test_a_ground_that_is_not_level_is_left_unframed(tmp_path, capsys):
    gg = tmp_path / "steps.gg"
    gg.write_text('example "steps"\nimport "ground"\n'
                  "polyline (0, 0) (100, 0) (100, 20) (200, 20) class ground\n"
                  "polyline (50, 0) (50, 40)\n")
    ex = load_example(gg)
    assert find_frame(ex) is None
    note = next(n for n in ex.notes if "ends in the air" in n.message)
    assert note.severity == "warning" and "steps.gg:3:1" in note.render()
    # ggrun, which compiles the example itself, says it too, before its summary.
    out = tmp_path / "steps.svg"
    capsys.readouterr()
    assert ggrun([str(gg), "--steps", "3", "--out", str(out)]) == 0
    assert "steps.gg:3:1: warning: this border line ends in the air" in capsys.readouterr().err
    assert ggrun([str(gg), "--steps", "3", "--out", str(out), "--quiet"]) == 0
    assert capsys.readouterr().err == ""
    for name in NAMES:          # a frame drawn in pieces (the SVGs) is not an open ground
        assert not any("ends in the air" in n.message
                       for n in load_example(ILLUSTRATIONS / f"{name}.gg").notes)


def test_a_border_that_ends_in_the_air_beside_a_frame_is_located(tmp_path):
    gg = tmp_path / "bad.gg"
    gg.write_text('example "bad"\nface room #ccc\nclass edge { border }\n'
                  "polygon room rect (0, 0) (10, 10)\n"
                  "border rect (-5, -5) (20, 20) class edge\n"
                  "polyline (30, 5) (40, 5) class edge\n")
    with pytest.raises(UserError, match="ends in the air") as err:
        find_frame(load_example(gg))
    assert "bad.gg:6" in err.value.render()
    gg.write_text(gg.read_text().replace("(30, 5) (40, 5)", "(20, 5) (30, 5)"))
    with pytest.raises(UserError, match="branches"):
        find_frame(load_example(gg))


def test_a_shape_outside_the_frame_is_a_located_error(tmp_path):
    """The frame is the border of the space: a shape drawn beyond it (here a room to its
    right) could never be drawn, and the run went on without a word."""
    gg = tmp_path / "out.gg"
    gg.write_text('example "out"\nface room #ccc\nclass edge { border }\n'
                  "polygon room rect (10, 0) (20, 10)\n"
                  "polygon room rect (50, 0) (60, 10)\n"
                  "border rect (0, 0) (40, 30) class edge\n")
    with pytest.raises(UserError, match=r"outside the frame, at \(50, 0\)") as err:
        find_frame(load_example(gg))
    assert "out.gg:5" in err.value.render()
    # On a side is inside: a room standing on the frame's bottom, up to its right side.
    gg.write_text(gg.read_text().replace("(50, 0) (60, 10)", "(30, 0) (40, 10)"))
    assert find_frame(load_example(gg)) is not None


def test_a_frame_side_bent_by_a_point_routed_through_it_is_a_located_error(tmp_path):
    # Found by the fuzzer: a village's tree trunk run out past the frame's left side ended
    # within the merge distance of it, the side was routed through that end, and generation
    # failed on a frame whose side runs along none of its edges' (snapped) directions.
    village = (Path(__file__).resolve().parent.parent / "examples" / "village.gg").read_text()
    trunk = "polyline (1100, 0) (1100, 15) class house"
    assert trunk in village
    gg = tmp_path / "bent.gg"
    gg.write_text(village.replace(trunk, trunk.replace("(1100, 15)", "(-1, 15)")))
    with pytest.raises(UserError, match="does not run along") as err:
        find_frame(load_example(gg))
    assert "bent.gg:" in err.value.render()
    assert ggc(["check", str(gg)]) == 2
    # A rule file whose frame is bent so (edited by hand) is refused when it is placed.
    good = tmp_path / "good.gg"
    good.write_text(village)
    ggr = tmp_path / "good.ggr"
    assert ggc(["compile", str(good), "-o", str(ggr)]) == 0
    text = ggr.read_text()
    frame = next(line for line in text.splitlines() if line.startswith("frame "))
    words = frame.split()
    words[2], words[3] = "-1", str(float(words[3]) + 15)
    ggr.write_text(text.replace(frame, " ".join(words)))
    assert ggrun([str(ggr), "--steps", "2", "--out", str(tmp_path / "o.svg")]) == 2


def test_inference_never_creates_or_touches_the_frame(scene):
    ex, res = scene
    g = res.grammar
    border = border_labels(ex.labels, ex.classes)
    corners = corner_primitives(ex.primitives, ex.labels, border)
    on_border = border_primitives(ex.primitives, border)
    assert g.header.frame == find_frame(ex)
    stands = [r for r in g.rules if r.name.startswith("stand")]
    assert stands, "structures standing on the frame's sides become rules"
    for r in g.rules:
        verts = set(r.lhs.vertices) | set(r.rhs.vertices)
        assert not verts & corners, r.name
        if r.is_starter:
            assert not verts & on_border, r.name
    # The frame survives the rule file.
    assert parse_ggr(emit_ggr(g), "castle.ggr").header.frame == g.header.frame


@pytest.mark.parametrize("seed", [1, 2])
def test_a_scene_grows_inside_its_frame(scene, seed):
    ex, res = scene
    eng = Engine(res.grammar, seed=seed)
    eng.run(30)
    host = eng.host
    frame = res.grammar.header.frame
    assert_inside_its_frame(host, frame)
    # Exactly one frame: each corner primitive once, and something stands on it.
    for c in frame.corners:
        assert len(host.by_prim[c.prim]) == 1
    assert len(host) > 4
    failures = check_drawing(ex, host.to_drawing())
    assert failures == [], "\n".join(f.render() for f in failures[:3])
    assert host.check_consistency() == []


@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4])
def test_connected_grows_one_structure(seed):
    """examples/tree.gg imports `branching`, which asks for `connected`."""
    import networkx as nx
    ex = load_example(Path(__file__).resolve().parent.parent / "examples" / "tree.gg")
    assert ex.options.connected
    from runtime.engine.costs import SizeCost
    eng = Engine(compile_example(ex).grammar, seed=seed, cost=SizeCost(80))
    eng.run(80)
    g = nx.Graph()
    g.add_nodes_from(eng.host.vertices())
    g.add_edges_from((v, w) for v, _, w, _ in eng.host.edges())
    assert len(eng.host) > 20 and nx.number_connected_components(g) == 1
    assert check_drawing(ex, eng.host.to_drawing()) == []


@pytest.mark.parametrize("extent,message", [
    ("0x9", "positive"), ("axb", "not W×H"), ("1e99x5", "positive")])
def test_bad_extents_are_user_errors(castle, extent, message):
    from runtime.run_cmd import parse_extent
    with pytest.raises(UserError, match=message):
        parse_extent(extent, castle[1].grammar)
    with pytest.raises(UserError, match="rigid part"):
        Engine(castle[1].grammar, extent=(5.0, 5.0))


def test_an_extent_must_hold_every_rigid_part(scene):
    """A rigid part keeps its shape, so an extent narrower or lower than its box is refused
    (the flowers' blossoms, 160 × 140 px, stalled a run at 100 × 100 with no word of why);
    the example's own frame holds every part, and so does any extent as large as the box."""
    from runtime.geometry.stands import rigid_box
    from runtime.geometry.tables import Tables
    grammar = scene[1].grammar
    bw, bh = rigid_box(Tables.build(grammar.header),
                       [s for r in grammar.rules for s in (r.lhs, r.rhs)])
    fw, fh = grammar.header.frame.size
    assert bw <= fw and bh <= fh
    assert Engine(grammar, extent=(fw, fh)).frame.size == (fw, fh)
    if not grammar.header.frame.axis_aligned:
        return
    for w, h in ((0.9 * bw, fh), (fw, 0.9 * bh)):
        if w and h:
            with pytest.raises(UserError, match="cannot hold the example's largest rigid"):
                Engine(grammar, extent=(w, h))


def test_the_flowers_blossoms_do_not_fit_a_small_extent(tmp_path, capsys):
    flowers = str(ILLUSTRATIONS / "flowers.gg")
    out = str(tmp_path / "f.svg")
    assert ggrun([flowers, "--extent", "100x100", "--steps", "2", "--out", out]) == 2
    err = capsys.readouterr().err
    assert "160 units wide, 140 high" in err and "--extent of at least 160x140" in err


def test_an_extent_stretches_the_frame(castle):
    eng = Engine(castle[1].grammar, seed=4, extent=(2400.0, 900.0))
    assert eng.host.frame.size == (2400.0, 900.0)
    eng.run(20)
    x0, y0, x1, y1 = eng.host.frame.box
    assert all(x0 - 1e-6 <= eng.host.pos[v][0] <= x1 + 1e-6 for v in eng.host.vertices())
    # Its top side is 2,400 long, beyond the example's longest border edge (1,540).
    assert check_drawing(castle[0], eng.host.to_drawing()) == []


# The original settings' extents (the illustrations' README), wider and taller than the
# examples' own 1,540 × 780 frames.
PAPER_EXTENTS = {"castle": (1600.0, 800.0), "village": (2720.0, 1600.0),
                 "flowers": (2040.0, 1200.0), "space-station": (2040.0, 800.0)}


@pytest.mark.parametrize("name", NAMES)
def test_every_illustration_grows_verified_at_the_papers_extent(name):
    """A border class has no longest length unless the user gives one: the frame's sides are
    as long as the extent asks, and the village's start, whose strips run from side to side,
    is placed at 2,720 × 1,600 (bounded by its example's longest border edge, it was not)."""
    ex, g = _illustration(name)
    eng = Engine(g, seed=0, extent=PAPER_EXTENTS[name])
    assert eng.host.frame.size == PAPER_EXTENTS[name]
    eng.run(60)
    assert_inside_its_frame(eng.host, eng.host.frame)
    assert check_drawing(ex, eng.host.to_drawing()) == []


def test_a_border_class_has_no_longest_length_unless_given_one():
    from grammar_lang.source import EdgeClass
    assert EdgeClass("frame", border=True).max_length == math.inf
    assert EdgeClass("frame", max_length=900.0, border=True).max_length == 900.0
    assert EdgeClass("0").resolved(40.0).max_length == 160.0
    assert EdgeClass("frame", border=True).resolved(40.0, (4.0, 1540.0)).max_length == math.inf
    # The rule file leaves an infinite max out, and reads it back the same.
    ex, g = _illustration("village")
    text = emit_ggr(g)
    assert "max=inf" not in text
    assert parse_ggr(text).header.classes == g.header.classes


def test_costs_take_the_names_of_the_example():
    """`--cost label:NAME` takes a face label, an edge class or an edge label."""
    from runtime.engine.costs import LabelCost, parse_cost
    labels = load_example(EXAMPLES / "castle.gg").labels
    window = parse_cost("label:window:0.2", labels, 10)
    assert isinstance(window, LabelCost) and window.labels
    assert all("window" in (labels[k].left, labels[k].right) for k in window.labels)
    ground = parse_cost("label:ground", labels, 10)
    assert all(labels[k].cls == "ground" for k in ground.labels)
    with pytest.raises(UserError, match="no face label, edge class or edge label"):
        parse_cost("label:windo", labels, 10)


@pytest.mark.parametrize("cost", ["scene", "scene:300"])
def test_the_scene_cost_can_be_asked_for_by_name(cost, tmp_path, capsys):
    # The default, named explicitly, with a frame or without (the space is then the exterior).
    from report.ggrun import main
    for name in ("castle-scene.gg", "tree.gg"):
        out = tmp_path / f"{name}.json"
        assert main([str(EXAMPLES / name), "--steps", "5", "--seed", "1",
                     "--cost", cost, "--out", str(out), "--quiet"]) == 0
        assert out.exists()


@pytest.mark.parametrize("t", ["nan", "inf", "-1"])
def test_a_temperature_that_makes_no_sense_is_refused(t, capsys):
    from report.ggrun import main
    assert main([str(EXAMPLES / "square-walls.ggr"), "--temperature", t, "--out",
                 "/dev/null/x.svg"]) == 2
    assert "makes no sense" in capsys.readouterr().err


def test_an_extent_keeps_the_proportions_of_a_slanted_frame(castle):
    from dataclasses import replace

    from grammar_lang.frame import Corner, Frame
    from runtime.run_cmd import parse_extent
    g = castle[1].grammar
    slanted = Frame((Corner(0, 0.0, 0.0), Corner(0, 400.0, 0.0), Corner(0, 200.0, 300.0)))
    g = replace(g, header=replace(g.header, frame=slanted))
    assert parse_extent("800x600", g) == (800.0, 600.0)
    with pytest.raises(UserError, match="slanted"):
        parse_extent("800x300", g)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_in_a_frame_nothing_floats_but_what_the_example_has_free_standing(seed):
    """Every component apart from the frame's own is one a starter makes (a window in a
    tower), never a part cut off a structure (a roof lifted off its tower)."""
    res = compile_example(load_example(SCENES["castle-scene"]))
    g = res.grammar
    eng = Engine(g, seed=seed)
    eng.run(120)
    host = eng.host
    assert_only_starters_float(host, g)


# Two items, so that the suite's two workers share their 16 runs.
@pytest.mark.parametrize("kind", ["scene", "size"])
def test_the_default_scene_cost_keeps_every_part_in_proportion(kind):
    """In a frame the default cost holds each face label's share of the edges near the
    example's: windows do not crowd out keeps and gates as the run grows, and none fades.
    By size alone roofs reach 1.8-2.4 times their share (median 2.1 over seeds 0-7) and
    towers 1.4-1.65 times; with the scene cost every part's median stays within 0.82-1.23,
    and no part of any drawing falls below 0.6 (gates are the lowest: towers are the easiest
    part to place). Read over eight seeds: a single drawing's gates stray (0.64 of their
    share at seed 5 before the late-rounds record of late.py, 0.62 at seed 3 after it, with
    medians 0.89 and 0.87). (With every merlon of a fixed length, walls fitted only where
    their teeth did and the gates of seeds 2 and 3 fell to 0.3-0.5 of their share: the
    example's end teeth are free.)"""
    from runtime.engine.costs import SceneCost, SizeCost, default_cost
    g = compile_example(load_example(SCENES["castle-scene"])).grammar
    cost = default_cost(g.header, 400)
    assert isinstance(cost, SceneCost)

    def ratios(c, seed) -> list[float]:
        eng = Engine(g, seed=seed, cost=c)
        eng.run(400)
        counts, edges = eng.host.label_count, eng.host.n_edges
        assert len(eng.host) > 100
        return [sum(counts[k] for k in ks) / edges / share
                for ks, share in zip(cost.groups, cost.shares)]

    def in_proportion(c) -> bool:
        per_group = list(zip(*(ratios(c, seed) for seed in range(8))))
        return all(0.75 <= statistics.median(rs) <= 1.35 and min(rs) >= 0.55
                   for rs in per_group)

    if kind == "scene":
        assert in_proportion(cost)
    else:
        assert not in_proportion(SizeCost(400))


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_bare_lines_in_the_space_keep_near_their_share(castle, seed):
    """The paper's castle has stubs and slopes drawn in the sky, with the sky on both sides.
    The default cost holds their share too: before it did, 1,000 iterations gave them 31–42 %
    of the edges (the example: 8 %), combs of stubs up every tower; now 2.1-3.0 times the
    example's share over seeds 0-5 (stubs are the cheapest part to place)."""
    from runtime.engine.costs import default_cost
    _, res = castle
    h = res.grammar.header
    space = {"exterior", "#cde1ff"}
    bare = [k for k, l in enumerate(h.labels)
            if l.left in space and l.right in space and k not in border_labels(h.labels, h.classes)]
    per = Counter()
    for p in h.primitives:
        for t in p.ring:
            per[t >> 1] += p.count
    share = sum(per[k] for k in bare) / sum(per.values())
    eng = Engine(res.grammar, seed=seed, cost=default_cost(h, 1000))
    eng.run(None, iterations=1000)
    got = sum(eng.host.label_count[k] for k in bare) / eng.host.n_edges
    assert len(eng.host) > 100
    assert got <= 3.2 * share, (got, share)


def test_a_scene_at_its_start_graph_does_not_stall():
    """The village starts from its frame's start graph, at the example's own proportions: the
    scene cost's slack lets its first moves through on every seed."""
    ex, g = _framed("village.gg")
    from runtime.engine.costs import default_cost
    for seed in range(5):
        eng = Engine(g, seed=seed, cost=default_cost(g.header, 60))
        summary = eng.run(60)
        assert summary.applied == 60, (seed, summary.stop)


@pytest.fixture(scope="module")
def village():
    ex = load_example(ILLUSTRATIONS / "village.gg")
    return ex, compile_example(ex)


def test_a_frame_whose_sides_change_label_starts_from_its_frame_component(village):
    """The village's strips run from the left side to the right: its frame cannot be drawn
    bare, so it starts from the example's frame with everything touching it, which the .ggr
    keeps through a round trip."""
    from grammar_lang.frame import bare_sides
    ex, res = village
    frame = res.grammar.header.frame
    assert None in bare_sides(frame, ex.primitives, ex.labels)
    start = frame.start
    assert start is not None and not start.boundary
    assert sorted(c.prim for c in frame.corners) == sorted(
        p for p in start.vertices if p in {c.prim for c in frame.corners})
    again = parse_ggr(emit_ggr(res.grammar)).header.frame
    assert again.start == start
    castle = load_example(ILLUSTRATIONS / "castle.gg")
    assert compile_example(castle).grammar.header.frame.start is None    # bare sides


# The scenes whose structures stand on the frame or on lines across it (the paper's station
# floats).
@pytest.mark.parametrize("path", [ILLUSTRATIONS / f"{n}.gg" for n in ("castle", "village",
                                                                      "flowers")]
                         + [EXAMPLES / "castle-scene.gg", EXAMPLES / "village.gg"])
def test_a_structure_stood_on_the_frame_or_a_line_keeps_the_edge_it_replaces(path):
    """framing.frame_starters and line_starters: each rule takes one bare edge to a
    structure of the example (the same boundary); a line rule holds nothing of the frame and
    has a left side no other rule of the grammar has. (A stand rule may repeat one the
    hierarchy found: `examples/village.gg`'s `stand0` and `stand1` are its `r3` and `r5`.
    Dropped, the copies cost that scene 13 % of its vertices over seeds 0-3 and 65 at 4,200
    iterations, 468 → 409, as a move drawn half as often.)"""
    from compiler.apply import side_graph
    from compiler.canon import canonical_key
    ex = load_example(path)
    g = compile_example(ex).grammar
    rings = [p.ring for p in ex.primitives]
    ring_len = [len(r) for r in rings]
    on_border = border_primitives(ex.primitives, border_labels(ex.labels, ex.classes))
    keys = Counter(canonical_key(side_graph(r.lhs), ring_len) for r in g.rules)
    assert any(not r.rhs.vertices and r.rhs.wires for r in g.rules)
    for r in (r for r in g.rules if r.name.startswith(("stand", "line"))):
        assert not r.rhs.vertices and len(r.rhs.wires) == 1, r.name
        assert r.lhs.tokens(rings) == r.rhs.tokens(rings), r.name
        if r.name.startswith("line"):
            assert keys[canonical_key(side_graph(r.lhs), ring_len)] == 1, r.name
            assert not set(r.lhs.vertices) & on_border, r.name


def _on_a_line(widths, heights, roof: bool) -> str:
    """A framed example: land under sky, the skyline from side to side, and one structure
    of boxes side by side (faces p0, p1, ...) standing on it, a roof over them or not."""
    x, parts = 300, []
    for k, (w, h) in enumerate(zip(widths, heights)):
        parts.append(f"polygon p{k} rect ({x}, 150) ({x + w}, {150 + h})")
        x += w
    if roof:
        top = 150 + max(heights)
        parts = [f"polygon p{k} rect ({300 + sum(widths[:k])}, 150) "
                 f"({300 + sum(widths[:k + 1])}, {top})" for k in range(len(widths))]
        parts.append(f"polygon roof (300, {top}) ({x}, {top}) ({(300 + x) // 2}, {top + 40})")
    faces = "".join(f"face p{k} #{k + 1:02d}0000\n" for k in range(len(widths)))
    return (f'example "Line"\noptions {{ merge-distance: 1 }}\nface sky #d6ecf7\n'
            f"face land #a8d080\nface roof #0000ff\n{faces}class frame {{ border }}\n"
            "class line { min: 40; max: 1600 }\npolygon sky rect (0, 0) (1200, 600)\n"
            "polygon land rect (0, 0) (1200, 150)\npolyline (0, 150) (1200, 150) class line\n"
            + "\n".join(parts) + "\n"
            + "".join(f"polyline {a} {b} class frame\n" for a, b in
                      (("(0, 0)", "(1200, 0)"), ("(1200, 0)", "(1200, 600)"),
                       ("(1200, 600)", "(0, 600)"), ("(0, 600)", "(0, 0)"))))


@settings(max_examples=12, deadline=None)
@given(widths=st.lists(st.integers(4, 12), min_size=1, max_size=3),
       heights=st.lists(st.integers(3, 9), min_size=3, max_size=3), roof=st.booleans())
def test_a_structure_on_a_line_across_the_frame_can_be_put_on_a_bare_edge(tmp_path_factory,
                                                                          widths, heights, roof):
    """Whatever the hierarchy reaches, some rule takes one bare edge of the skyline to the
    whole structure standing on it."""
    gg = tmp_path_factory.mktemp("line") / "line.gg"
    gg.write_text(_on_a_line([10 * w for w in widths], [10 * h for h in heights], roof))
    ex = load_example(gg)
    g = compile_example(ex).grammar
    rings = [p.ring for p in ex.primitives]
    wanted = {f"p{k}" for k in range(len(widths))} | ({"roof"} if roof else set())

    def faces(side):
        return {f for p in side.vertices for t in rings[p]
                for f in (ex.labels[t >> 1].left, ex.labels[t >> 1].right)}
    assert any(wanted <= faces(r.lhs) for r in g.rules
               if not r.rhs.vertices and len(r.rhs.wires) == 1)


def test_every_house_of_the_village_can_be_put_on_a_bare_line(village):
    """The village's grammar, limited at 1,000 graphs, found a rule that puts its
    flat-roofed house on a line, but none for its two houses of two parts and a roof, which
    it added only beside one of their kind. With the line rules every face label of the
    example is put on a bare edge by some rule."""
    ex, res = village
    rings = [p.ring for p in ex.primitives]
    labels = ex.labels

    def faces(side):
        return {f for p in side.vertices for t in rings[p]
                for f in (labels[t >> 1].left, labels[t >> 1].right)}
    put = set().union(*(faces(r.lhs) for r in res.grammar.rules if not r.rhs.vertices))
    assert set(ex.face_labels) - {ex.exterior} <= put
    # The compile's summary counts them.
    assert res.report.rules_stood == sum(r.name.startswith("line") for r in res.grammar.rules)
    assert res.report.rules_stood > 0


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_frame_start_is_placed_and_grown_inside_its_frame(village, seed):
    ex, res = village
    from runtime.engine.costs import default_cost
    g = res.grammar
    eng = Engine(g, seed=seed, cost=default_cost(g.header, 30))
    host = eng.host
    assert len(host) == len(g.header.frame.start.vertices) and host.n_open == 0
    eng.run(30)
    x0, y0, x1, y1 = g.header.frame.box
    for v in host.vertices():
        x, y = host.pos[v]
        assert x0 - 1e-6 <= x <= x1 + 1e-6 and y0 - 1e-6 <= y <= y1 + 1e-6
    assert sorted(host.pos[v] for v in host.pinned) == sorted((c.x, c.y) for c in g.header.frame.corners)
    failures = check_drawing(ex, host.to_drawing())
    assert failures == [], "\n".join(f.render() for f in failures[:3])


def test_every_seed_starts_its_frame_at_the_examples_own_extent(village):
    """The seeds whose start was not placed in 8 solver runs (one in 70 of the paper's
    village, one in 28 of examples/space-station.gg) start now, and give a whole start."""
    station = compile_example(load_example(EXAMPLES / "space-station.gg")).grammar
    for g, seeds in ((village[1].grammar, (198, 286, 294, 295, 306)),
                     (station, (15, 20, 21, 59, 62, 966))):
        for seed in seeds:
            host = Engine(g, seed=seed).host
            assert len(host) >= len(g.header.frame.start.vertices) and host.n_open == 0


@pytest.mark.parametrize("edit, message", [
    (lambda t: "\n".join(line for line in t.splitlines() if not line.startswith("frame ")),
     "'frame-start' without a 'frame' line"),
    (lambda t: t.replace("frame-start {\n  v0:", "frame-start {\n  extra: p0   v0:", 1),
     "is not complete"),
])
def test_a_broken_frame_start_is_a_located_error(village, edit, message):
    text = edit(emit_ggr(village[1].grammar))
    with pytest.raises(UserError, match=message) as err:
        parse_ggr(text, "v.ggr")
    assert "v.ggr:" in err.value.render()


def test_the_documented_frame_start_is_the_villages(village):
    """docs/ggr-language.md quotes the village's start graph: its lines are the compiler's."""
    import re
    doc = (Path(__file__).resolve().parent.parent / "docs" / "ggr-language.md").read_text()
    block = re.search(r"```ggr fragment\n(frame-start.*?)```", doc, re.S).group(1)
    written = emit_ggr(village[1].grammar).splitlines()
    lines = [line for line in block.splitlines() if line.strip() != "…"]
    assert len(lines) >= 4 and all(line in written for line in lines)


@functools.lru_cache(maxsize=None)
def _illustration(name):
    ex = load_example(ILLUSTRATIONS / f"{name}.gg")
    return ex, compile_example(ex).grammar


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4])
def test_every_illustration_grows_verified_inside_its_frame(name, seed):
    """The paper's four illustrations, five seeds each, run as ggrun runs them (default
    scene cost): the drawing passes the verifier, the corners stay where the frame puts
    them, and every vertex stays inside it."""
    from runtime.engine.costs import default_cost
    ex, g = _illustration(name)
    eng = Engine(g, seed=seed, cost=default_cost(g.header, 12))
    eng.run(12)
    host = eng.host
    frame = g.header.frame
    assert sorted(host.pos[v] for v in host.pinned) == sorted((c.x, c.y) for c in frame.corners)
    x0, y0, x1, y1 = frame.box
    assert all(x0 - 1e-6 <= host.pos[v][0] <= x1 + 1e-6 and y0 - 1e-6 <= host.pos[v][1] <= y1 + 1e-6
               for v in host.vertices())
    failures = check_drawing(ex, host.to_drawing())
    assert failures == [], "\n".join(f.render() for f in failures[:3])
    assert host.check_consistency() == []


# The paper's N and seed for each illustration (Table 1; the illustrations' README).
PAPER_RUNS = {"castle": (4000, 80), "flowers": (2000, 42), "space-station": (4000, 22),
              "village": (4000, 65)}


# Each run takes 8-18 s on the 2-core machine, and at six seeds per scene these runs were
# two fifths of the suite's time. The suite keeps the paper's seed and seed 0 for each scene,
# and the castle's seeds that once lost a part (docstring below); seeds 0-4 of every scene
# are `benchmarks/paper.py --seeds 0-4`, which counts the drawings that hold every part.
PAPER_N_SEEDS = [(name, seed) for name in NAMES for seed in (PAPER_RUNS[name][1], 0)] \
    + [("castle", 2), ("castle", 9), ("castle", 18)]


@pytest.mark.parametrize("name, seed", PAPER_N_SEEDS)
def test_at_the_papers_n_every_label_and_class_is_drawn(name, seed):
    """At the paper's N iterations, at the seeds above, with the default cost, the drawing
    holds every face label and every edge class of the example, inside its frame, and
    passes the verifier. (The castle at seed 0 had no keep until a wanted change's
    lengths were repaired by pinning, system.repair: alternating projections stalled on a
    keep squeezed onto a block top, and the keep's tiles, rounded after, broke what they
    had fitted. A change that let framed moves split once took the castle's keeps, windows
    and roofs away at seed 80: half its face labels; the shorter runs above still passed.
    At seed 2 the castle had no keep until the scene cost charged more for a part left out
    altogether: its first structures were all keepless, and later the ground was full. At
    seed 9 it had none until a structure stood on a stretch of ground was aimed where its
    footprint fits: the keep's, about 400 px wide, placed beside the first structure 3
    times in 30 when aimed anywhere along the stretch. At seed 18 it had none when
    every first-round sample had its lengths repaired, a version of system.repair tried and
    not kept: its 145 tries at a keep on a block top failed on lengths.)"""
    from runtime.engine.costs import default_cost
    n = PAPER_RUNS[name][0]
    ex = load_example(ILLUSTRATIONS / f"{name}.gg")
    g = compile_example(ex).grammar
    eng = Engine(g, seed=seed, cost=default_cost(g.header, n))
    eng.run(None, iterations=n)
    drawing = eng.host.to_drawing()
    faces = {f for e in drawing.edges for f in (e.left, e.right)}
    assert faces == {f for l in g.header.labels for f in (l.left, l.right)}
    assert {e.cls for e in drawing.edges} == {l.cls for l in g.header.labels}
    assert_inside_its_frame(eng.host, g.header.frame)
    failures = check_drawing(ex, drawing)
    assert failures == [], "\n".join(f.render() for f in failures[:3])
    assert _median_stretch(eng.host) >= MEDIAN_STRETCH
    assert _squeezed_strips(eng.host) == []


def _squeezed_strips(host) -> list[float]:
    """The pieces of the frame's sides where lines across it end (Tables.gaps: a strip's
    height at the frame) that are shorter than their label's floor. Without that floor the
    village at its seed, 65, had 29 such pieces at its N, most 4 px (its class's minimum)."""
    t, tol = host.t, 1e-6 * host.t.unit
    return [d for v, i, w, _ in host.edges() for lab in (t.label[host.prim[v]][i],)
            if lab in t.gaps
            for d in (math.dist(host.pos[v], host.pos[w]),) if d < t.least[lab] - tol]


def test_only_the_sides_where_lines_across_the_frame_end_keep_a_floor():
    """`Tables.gaps` holds the village's left and right sides, where its strip lines end,
    and nothing of the other illustrations, whose sides are the ground things stand on or
    the frame alone: there a side is as long as the frame, or the gap between two
    structures, and has no floor."""
    from runtime.geometry.tables import Tables
    for name in NAMES:
        g = compile_example(load_example(ILLUSTRATIONS / f"{name}.gg")).grammar
        t, labels = Tables.build(g.header), g.header.labels
        eng = Engine(g, seed=0)
        assert t.gaps <= eng.host.side_labels
        if name != "village":
            assert t.gaps == frozenset(), name
            continue
        # Its left and right sides, with a floor from the example's strips.
        assert len(t.gaps) == 2
        assert all(t.least[k] == min(PROPORTION * labels[k].typical, labels[k].shortest) > 0
                   for k in t.gaps)
        assert {labels[k].angle for k in t.gaps} == {90.0}


# The parts of a scene keep the example's proportions: the median edge (the frame's sides
# aside) is at least this share of its label's typical length. With drawn edges floored at
# 0.2 of it the castle grew combs of 8 px poles and its median was 0.43-0.50 (seeds 0-3,
# 80); at 0.4 (tables.PROPORTION) it is 0.60-0.82, and the other illustrations 0.86-1.
MEDIAN_STRETCH = 0.55


def _median_stretch(host) -> float:
    t = host.t
    return statistics.median(
        math.dist(host.pos[v], host.pos[w]) / t.typical[lab]
        for v, i, w, _ in host.edges()
        for lab in (t.rings[host.prim[v]][i] >> 1,)
        if lab not in host.side_labels and t.typical[lab] == t.typical[lab])


def test_in_a_frame_a_part_left_out_costs_more_than_one_that_strays(castle):
    """The scene cost of a framed example charges ABSENT per expected edge of a group with no
    edge at all, and only the deviation beyond the slack of one that has some; without a
    frame (a run from nothing, a house before its door) a missing group costs as any."""
    from runtime.engine.costs import ABSENT, SceneCost, SizeCost, Stats, default_cost
    assert default_cost(castle[1].grammar.header, 100).absent == ABSENT > 1
    house = load_example(Path(__file__).resolve().parent.parent / "examples" / "house.gg")
    assert default_cost(compile_example(house).grammar.header, 100).absent == 0.0
    size = SizeCost(100)
    for absent in (ABSENT, 0.0):
        cost = SceneCost(size, ((0,),), (0.25,), absent)      # a quarter of 400 edges: 100

        def off(n):
            s = Stats(100, 400, (n, 0), 0.0)
            return cost.value(s) - size.value(s)
        assert off(100) == 0.0 and off(95) == 0.0              # within the slack of 10
        assert off(1) == pytest.approx(100 - 1 - 10)
        assert off(0) == pytest.approx(absent * 100 if absent else 100 - 10)


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_a_structure_stood_on_a_stretch_is_aimed_where_it_fits(castle_stands, seed):
    """A structure stood on a bare stretch of the frame's side is aimed at least half its
    footprint (its new border edges at typical lengths) from either end of the stretch, and a
    tenth of the stretch at least; in the middle when the stretch is shorter than it is."""
    import math

    import numpy as np

    from runtime.engine.rewrite import plan
    eng, stands = castle_stands
    eng.rng = np.random.default_rng(seed)
    host = eng.host
    aimed = 0
    for move in stands:
        for m in eng.matches(move, limit=3):
            change = plan(host, move, m, False)
            if len(change.cut) != 1 or change.removed:
                continue
            (v, i), = change.cut
            p, q = host.pos[v], host.pos[host.link[v][i][0]]
            length, foot = math.dist(p, q), eng._footprint(change)
            assert foot > 0
            margin = max(0.1 * length, min(0.5 * length, 0.5 * foot))
            for _ in range(5):
                c = eng._center(change)
                assert min(math.dist(c, p), math.dist(c, q)) >= margin - 1e-6
                assert abs(math.dist(c, p) + math.dist(c, q) - length) < 1e-6
                aimed += 1
    assert aimed


@pytest.fixture(scope="module")
def castle_stands(castle):
    """The paper's castle grown a little, and its moves that stand a structure on the
    ground (a wire along the frame's side matched, nothing removed)."""
    from runtime.engine.costs import default_cost
    g = castle[1].grammar
    eng = Engine(g, seed=3, cost=default_cost(g.header, 4000))
    eng.run(None, iterations=300)
    stands = [mv for mv in eng.moves() if mv.rule.name.startswith("stand") and not mv.forward]
    assert stands
    return eng, stands


def test_an_extent_a_bounded_border_class_cannot_span_names_that_class():
    """examples/space-station.gg bounds the frame sides between its trusses (class `side`,
    240 to 400): a frame half as tall again cannot be placed, and the error points at the
    class that refuses it, in the file that declares it."""
    ex, g = _framed("space-station.gg")
    w, h = g.header.frame.size
    with pytest.raises(UserError) as info:
        Engine(g, seed=1, extent=(w, 1.5 * h))
    d = info.value.diagnostics[0]
    assert "class side (240 to 400 long)" in d.message
    assert d.span is not None and d.span.file.endswith("space-station.gg")
    assert "class side" in d.render() and "^" in d.render()


def test_a_line_across_the_frame_is_cut_as_short_as_its_class_allows():
    """examples/space-station.gg's trusses run from the frame's left side to its right, and
    modules and panels stand on them. Their pieces are what lies between those parts, not a
    part's outline, so they keep no proportion of the example's (240-500 px), only their
    class's 40 px: held to 0.4 of their typical 370 px, every piece needed 148 px, and the
    run stopped at 17 parts (15 by 300 iterations). Lines that do not cross the frame keep
    their floor: the castles' walls stand on the ground, but end in the air."""
    from runtime.engine.costs import default_cost
    from runtime.geometry.tables import Tables, through_labels
    ex, g = _framed("space-station.gg")
    trusses = {k for k, l in enumerate(g.header.labels) if l.cls == "truss"}
    assert through_labels(g.header) == trusses
    assert all(Tables.build(g.header).least[k] == 0.0 for k in trusses)
    for name in ("castle", "flowers", "space-station"):
        assert not through_labels(compile_example(load_example(ILLUSTRATIONS / f"{name}.gg"))
                                  .grammar.header)
    eng = Engine(g, seed=22, cost=default_cost(g.header, 300))
    stats = eng.run(None, iterations=300)
    assert stats.applied >= 25
    host = eng.host
    pieces = [math.dist(host.pos[v], host.pos[w]) for v, i, w, _ in host.edges()
              if host.t.label[host.prim[v]][i] in trusses]
    assert min(pieces) < 148 and min(pieces) >= 40 - 1e-6
    assert check_drawing(ex, host.to_drawing()) == []


def _pieces(host, change=None) -> int:
    """Connected components of the drawing, before `change` or (given) after it."""
    import networkx as nx
    g = nx.Graph()
    new = dict(change.new) if change else {}
    gone = set(change.removed) if change else set()
    for v in [v for v in host.vertices() if v not in gone] + list(new):
        g.add_node(v)
        p = new.get(v, host.prim.get(v))
        adj = change.adjacency(host, v, p) if change else \
            [(i, s) for i, s in enumerate(host.link[v]) if s is not None]
        g.add_edges_from((v, s[0]) for _, s in adj)
    return nx.number_connected_components(g)


@pytest.mark.parametrize("path", [ILLUSTRATIONS / "village.gg", ILLUSTRATIONS / "castle.gg",
                                  EXAMPLES / "platform.gg"], ids=lambda p: p.stem)
def test_a_step_is_refused_exactly_where_it_would_cut_the_drawing(path):
    """In a frame, or with `connected`, the moves that could cut the drawing in two are tested
    on it: refused where the drawing would fall into more pieces (a platform top taken off its
    last leg), let through where what they leave is still held (the village's dip taken out
    of a strip line leaves two pieces of line on the frame)."""
    from runtime.engine.rewrite import plan
    g = compile_example(load_example(path)).grammar
    eng = Engine(g, seed=3)
    eng.run(30)
    seen = Counter()
    for move in eng.moves():
        if (move.rule.name, move.forward) not in eng.schedule.guarded:
            continue
        for match in eng.matches(move):        # all of them: a cut is at few places
            change = plan(eng.host, move, match, eng.schedule.spo)
            cuts = _pieces(eng.host, change) > _pieces(eng.host)
            assert eng._cuts(change) == cuts, move.name
            seen[cuts] += 1
    assert seen[False] >= 1 and (path.stem != "platform" or seen[True] >= 1), seen


def test_the_village_lays_a_strip_from_side_to_side():
    """A strip of land is one edge from the frame's left side to its right: a chord of the
    space, as long as the frame is wide, which its class's maximum (440 px) does not bound.
    With no cost to hold the run back, the village's walk takes a dip away and lays one."""
    from grammar_lang.frame import spans_the_space
    from runtime.engine.costs import NoCost
    ex, g = _framed("village.gg")
    eng = Engine(g, seed=65, cost=NoCost())
    host = eng.host
    on, prim = host.on_border, host.prim
    longest = 0.0
    for _ in range(40):
        eng.run(None, iterations=25)
        for v in host.vertices():
            for i, s in enumerate(host.link[v]):
                if s is not None and spans_the_space(host.t.label[prim[v]][i] in host.border_labels,
                                                     prim[v] in on, prim[s[0]] in on):
                    longest = max(longest, abs(host.pos[v][0] - host.pos[s[0]][0]))
    assert longest > 1000, longest      # the frame is 1,540 wide; class 0 stops at 440
    failures = check_drawing(ex, host.to_drawing())
    assert failures == [], "\n".join(f.render() for f in failures[:3])
