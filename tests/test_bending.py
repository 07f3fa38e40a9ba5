"""Bending (paper Appendix B): bent pictures keep every cycle closed, stay planar, keep the
frame where it is and are deterministic; the drawing itself stays unbent."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
import shapely
from hypothesis import given, settings, strategies as st

from conftest import corpus_names
from compiler.infer import compile_example
from grammar_lang.loader import load_example
from runtime.engine.generate import Engine
from runtime.output.bending import Bend, bend_picture
from runtime.output.drawing import parse_drawing
from runtime.output.svg_out import render_svg
from test_verifier import example, own_drawing

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def arrays(d):
    index = {v.id: i for i, v in enumerate(d.vertices)}
    xy = np.array([(v.x, v.y) for v in d.vertices], dtype=float)
    ends = np.array([(index[e.u], index[e.v]) for e in d.edges], dtype=np.int64).reshape(-1, 2)
    return xy, ends


def assert_planar(bent, ends):
    """An independent check: two edges' paths meet only at the vertices they share, and no
    path crosses itself."""
    lines = [shapely.LineString(p) for p in bent.paths]
    assert all(line.is_simple for line in lines)
    i, j = shapely.STRtree(lines).query(lines, predicate="intersects")
    for a, b in zip(i.tolist(), j.tolist()):
        if a >= b:
            continue
        shared = set(ends[a].tolist()) & set(ends[b].tolist())
        meet = shapely.intersection(lines[a], lines[b])
        allowed = shapely.MultiPoint([bent.xy[v] for v in shared]) if shared else None
        assert allowed is not None and meet.difference(allowed).is_empty, (a, b, meet)


def assert_closed(bent, ends):
    for (u, v), p in zip(ends, bent.paths):
        assert np.array_equal(p[0], bent.xy[u]) and np.array_equal(p[-1], bent.xy[v])


def deviation(path) -> float:
    """The farthest a path's points stray from the chord between its ends, over its length."""
    a, b = path[0], path[-1]
    d = b - a
    length = math.hypot(*d)
    rel = path - a
    return float(np.max(np.abs(rel[:, 0] * d[1] - rel[:, 1] * d[0])) / length ** 2)


@pytest.mark.parametrize("name", corpus_names())
def test_every_corpus_drawing_bends_planar_and_closed(name):
    d = own_drawing(name)
    xy, ends = arrays(d)
    unit = example(name).unit
    bends = [Bend(math.radians(20), unit / 4)] * len(ends)
    bent = bend_picture(xy, ends, bends, np.zeros(len(xy), bool), seed=7)
    assert_closed(bent, ends)
    assert_planar(bent, ends)
    again = bend_picture(xy, ends, bends, np.zeros(len(xy), bool), seed=7)
    assert all(np.array_equal(p, q) for p, q in zip(bent.paths, again.paths))
    # It bends: edges longer than a step are no longer straight.
    long = [p for p in bent.paths if len(p) > 2]
    assert long and max(deviation(p) for p in long) > 0.01


@settings(max_examples=25, deadline=None)
@given(name=st.sampled_from(["square-filled", "h-complex", "branches", "plus", "curl"]),
       degrees=st.floats(0, 89), step=st.floats(0.05, 2.0), seed=st.integers(0, 2**31),
       bent_share=st.floats(0, 1))
def test_any_bending_stays_planar_with_straight_edges_kept(name, degrees, step, seed, bent_share):
    d = own_drawing(name)
    xy, ends = arrays(d)
    unit = example(name).unit
    rng = np.random.default_rng(seed)
    choice = rng.random(len(ends)) < bent_share
    bends = [Bend(math.radians(degrees), step * unit) if c else None for c in choice]
    pinned = rng.random(len(xy)) < 0.2
    bent = bend_picture(xy, ends, bends, pinned, seed)
    assert_closed(bent, ends)
    assert_planar(bent, ends)
    assert np.array_equal(bent.xy[pinned], xy[pinned])
    for b, p in zip(bends, bent.paths):
        if b is None:
            assert len(p) == 2


def test_straight_edges_keep_their_direction_beside_bent_ones():
    d = own_drawing("h-complex")           # two classes: one bends, one stays straight
    xy, ends = arrays(d)
    classes = [e.cls for e in d.edges]
    bends = [Bend(math.radians(30), example("h-complex").unit / 5) if c == classes[0] else None
             for c in classes]
    bent = bend_picture(xy, ends, bends, np.zeros(len(xy), bool), seed=3)
    for b, (u, v), p in zip(bends, ends, bent.paths):
        if b is None:
            before = math.atan2(*(xy[v] - xy[u])[::-1])
            after = math.atan2(*(p[-1] - p[0])[::-1])
            assert abs((after - before + math.pi) % (2 * math.pi) - math.pi) < math.radians(3)


def test_a_framed_scene_bends_inside_its_fixed_frame(tmp_path):
    src = (EXAMPLES / "castle-scene.gg").read_text()
    gg = tmp_path / "bent-scene.gg"
    gg.write_text(src + "\ndecorate edge * { bend: 25deg }\n")
    ex = load_example(gg)
    grammar = compile_example(ex).grammar
    border = {c.name for c in ex.classes if c.border}
    bent_svgs = 0
    for seed in range(4):
        eng = Engine(grammar, seed=seed)
        eng.run(60)
        d = parse_drawing(eng.host.to_drawing({"seed": seed}).to_json())
        svg = render_svg(d, ex)
        frame_path = next(line for line in svg.splitlines() if 'data-class="frame"' in line)
        assert frame_path.count(" L ") == frame_path.count("M ")      # the frame stays straight
        edge_paths = [line for line in svg.splitlines() if "data-class" in line]
        # A drawing whose bending finds no picture without a crossing within its rounds falls
        # back to straight edges (as it should): most seeds' drawings bend.
        bent_svgs += sum(p.count(" L ") for p in edge_paths) > len(d.edges)
        xy, ends = arrays(d)
        pinned = np.zeros(len(xy), bool)
        for i, e in enumerate(d.edges):
            if e.cls in border:
                pinned[ends[i]] = True
        # The frame is the border of the space: its own edges never bend.
        bends = [None if e.cls in border else Bend(math.radians(25), ex.unit / 4)
                 for e in d.edges]
        bent = bend_picture(xy, ends, bends, pinned, 2)
        assert np.array_equal(bent.xy[pinned], xy[pinned])
        lo, hi = xy[pinned].min(axis=0), xy[pinned].max(axis=0)
        pts = np.concatenate(bent.paths)
        assert (pts >= lo - 1e-9).all() and (pts <= hi + 1e-9).all()
        assert_planar(bent, ends)
    assert bent_svgs >= 2, bent_svgs


def test_the_svg_bends_and_the_json_does_not(tmp_path):
    from report.ggrun import main as ggrun
    out_svg, out_json = tmp_path / "tree.svg", tmp_path / "tree.json"
    run = [str(EXAMPLES / "tree.gg"), "--steps", "40", "--seed", "3", "--quiet", "--out"]
    assert ggrun(run + [str(out_svg)]) == 0 and ggrun(run + [str(out_json)]) == 0
    doc = json.loads(out_json.read_text())
    svg = out_svg.read_text()
    # Each straight edge is "M x,y L x,y": bent ones run through more points.
    edge_paths = [line for line in svg.splitlines() if "data-class" in line]
    points = sum(p.count(" L ") for p in edge_paths)
    assert points > len(doc["edges"])
    again = tmp_path / "again.svg"
    assert ggrun(run + [str(again)]) == 0
    assert again.read_text() == svg
