"""The five hand-written example grammars (examples/*.ggr with productions), each checked for
the property that defines it, and the runtime's handling of bad productions."""

from __future__ import annotations

import math

import pytest
from shapely.geometry import LinearRing, Polygon
from shapely.ops import unary_union

from conftest import ROOT
from grammar_lang.diagnostics import UserError
from grammar_lang.ggr_emit import emit_ggr
from grammar_lang.ggr_parser import load_ggr, parse_ggr
from runtime.engine.free_engine import FreeEngine
from runtime.output.free_svg import render_free_svg
from runtime.geometry.rejections import Rejection

EXAMPLES = ["koch", "honda-tree", "facade", "tiles", "rosette"]


def run(name: str, steps: int, seed: int = 0) -> FreeEngine:
    engine = FreeEngine(load_ggr(ROOT / "examples" / f"{name}.ggr"), seed)
    engine.run(steps)
    return engine


def of_kind(host, kind, label=None):
    return [e for e in host.elements.values() if e.kind == kind and label in (None, e.label)]


@pytest.mark.parametrize("name", EXAMPLES)
def test_examples_load_round_trip_and_draw_deterministically(name):
    g = load_ggr(ROOT / "examples" / f"{name}.ggr")
    assert parse_ggr(emit_ggr(g)) == g
    a, b = run(name, 60, seed=5), run(name, 60, seed=5)
    assert render_free_svg(a.host, g.header) == render_free_svg(b.host, g.header)


@pytest.mark.parametrize("k", [1, 2, 3, 4])
def test_koch_after_k_rounds(k):
    host = run("koch", 4 ** k - 1).host     # round j rewrites 3·4^(j-1) edges
    edges = of_kind(host, "edge")
    assert len(edges) == 3 * 4 ** k
    for e in edges:
        assert math.isclose(host.derived(e, "length"), 3.0 ** -k, rel_tol=1e-9)
    succ = {e.ends[0]: e.ends[1] for e in edges}
    assert len(succ) == len(edges) and sorted(succ.values()) == sorted(succ)
    v, ring = edges[0].ends[0], []
    for _ in edges:                          # one closed walk through every edge
        ring.append(host.pos(v))
        v = succ[v]
    assert v == edges[0].ends[0]
    assert LinearRing(ring).is_simple


def test_koch_apex_is_equilateral():
    host = run("koch", 1).host
    lengths = sorted(host.derived(e, "length") for e in of_kind(host, "edge"))
    assert all(math.isclose(x, 1 / 3) for x in lengths[:4])


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_honda_tree_is_a_tree_with_honda_ratios(seed):
    host = run("honda-tree", 200, seed).host
    vs, es = of_kind(host, "vertex"), of_kind(host, "edge")
    assert len(es) == len(vs) - 1 == 401
    parent = {e.ends[1]: e for e in es}
    assert len(parent) == len(es)            # every vertex has at most one branch into it
    for e in es:
        up = parent.get(e.ends[0])
        if up is None:
            assert host.elements[e.ends[0]].label == "root"
            continue
        ratio = host.derived(e, "length") / host.derived(up, "length")
        assert min(abs(ratio - 0.9), abs(ratio - 0.6)) < 1e-9
        assert math.isclose(host.value(e, "width"), host.value(up, "width") * 0.7)


def test_facade_windows_and_blinds():
    heights = set()
    for seed in range(4):
        host = run("facade", 116, seed).host
        windows, blinds = of_kind(host, "face", "window"), of_kind(host, "face", "blind")
        assert len(windows) == 8 and len(of_kind(host, "face", "wall")) == 8
        tops = {w.ends[2:]: w for w in windows}
        for bl in blinds:
            w = tops[bl.ends[2:]]                # a blind hangs from its window's top edge
            wy = [host.pos(v)[1] for v in w.ends]
            by = [host.pos(v)[1] for v in bl.ends]
            frac = (max(by) - min(by)) / (max(wy) - min(wy))
            assert 0.1 <= frac <= 0.9
            heights.add(round(frac, 6))
        assert Polygon([host.pos(v) for v in w.ends]).within(Polygon([(0, 0), (12, 0), (12, 7), (0, 7)]))
    assert len(heights) > 4


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_tiles_tile_the_square(seed):
    host = run("tiles", 400, seed).host
    faces = of_kind(host, "face")
    assert faces and all(f.label == "done" for f in faces)
    polys = [Polygon([host.pos(v) for v in f.ends]) for f in faces]
    for p in polys:         # axis-parallel rectangles
        x0, y0, x1, y1 = p.bounds
        assert math.isclose(p.area, (x1 - x0) * (y1 - y0))
    assert math.isclose(sum(p.area for p in polys), 1.0)
    assert math.isclose(unary_union(polys).area, 1.0)     # no overlaps


def test_tiles_vary_with_the_seed():
    counts = {len(of_kind(run("tiles", 400, s).host, "face")) for s in range(6)}
    assert len(counts) > 1


@pytest.mark.parametrize("seed", range(6))
def test_rosette_petals_evenly_round_the_hub(seed):
    host = run("rosette", 28, seed).host
    hub = of_kind(host, "vertex", "hub")[0]
    petals = of_kind(host, "vertex", "petal")
    n = int(host.value(hub, "total"))
    assert n in (5, 6, 8, 12) and len(petals) == n
    cx, cy = host.pos(hub.id)
    radii = [math.dist((cx, cy), host.pos(p.id)) for p in petals]
    assert max(radii) - min(radii) < 1e-9 and 0.8 <= radii[0] <= 1.2
    angles = sorted(math.degrees(math.atan2(host.pos(p.id)[1] - cy, host.pos(p.id)[0] - cx)) % 360
                    for p in petals)
    gaps = [(b - a) for a, b in zip(angles, angles[1:] + [angles[0] + 360])]
    assert all(math.isclose(g, 360 / n, abs_tol=1e-6) for g in gaps)
    assert all(host.value(p, "d").startswith("M ") and host.value(p, "d").endswith(" Z")
               for p in petals)


def test_decorations_beat_declared_defaults_and_set_values_beat_both():
    g = load_ggr(ROOT / "examples" / "facade.ggr")
    svg = render_free_svg(run("facade", 116, 1).host, g.header)
    windows = [line for line in svg.splitlines() if 'data-label="window"' in line]
    walls = [line for line in svg.splitlines() if 'data-label="wall"' in line]
    assert windows and all('fill="#28415e"' in line for line in windows)     # decorated
    assert walls and all('fill="#d8c8a8"' in line for line in walls)         # the default
    tiles = render_free_svg(run("tiles", 400, 2).host, load_ggr(ROOT / "examples" / "tiles.ggr").header)
    assert len({line.split('fill="')[1][:7] for line in tiles.splitlines() if "<path" in line}) > 2


# --- bad productions ---------------------------------------------------------------------------

HEAD = "ggr 1\nmode spo\nvertices pt\nedges seg\nattribute vertex h = 1\n"
START = "start {\n  a: pt  b: pt\n  a -> b seg\n  set a.pos = (0, 0)\n  set b.pos = (1, 0)\n}\n"


def prod(body: str, rhs: str = "a  b  c: pt\n    a -> c seg", sets: str = "  set c.pos = (2, 0)\n") -> str:
    return (HEAD + START + "production p {\n  lhs {\n    a: pt  b: pt\n    a -> b seg\n  }\n"
            + body + f"  rhs {{\n    {rhs}\n  }}\n" + sets + "}\n")


@pytest.mark.parametrize("text,message,where", [
    (prod("  where a.h + true\n"), "'+' does not apply to a number and a boolean", (17, 13)),
    (prod("  where a.height > 1\n"), "'a' has no attribute 'height'", (17, 9)),
    (prod("  where a.h\n"), "a condition must be a boolean", (17, 9)),
    (prod("  let v = " + "sqrt(" * 50 + "1" + ")" * 50 + "\n"), "nested too deeply", None),
    (prod("", "a  c: pt\n    a -> c seg"), "recreates its own match", None),
    (prod("", "a  b\n    a -> b seg", ""), "leaves its match exactly as it was", None),
    (prod("", sets=""), "the new vertex 'c' has no position", None),
    (prod("", sets="  set c.pos = 1\n"), "c.pos must be a vector", None),
    (prod("", sets="  set c.pos = (1 / 0, 0)\n"), "division by zero", (21, 18)),
    (prod("", sets="  set c.pos = (0, 0)\n  set c.degree = 1\n"), "'degree' is computed", None),
])
def test_bad_productions_are_caught_when_the_file_loads(text, message, where):
    with pytest.raises(UserError) as info:
        parse_ggr(text, "bad.ggr")
    d = info.value.diagnostics[0]
    assert message in d.message and d.span.file == "bad.ggr"
    if where:
        assert (d.span.line, d.span.column) == where


@pytest.mark.parametrize("sets,reason,detail", [
    ("  set c.pos = (1 / (a.h - 1), 0)\n", Rejection.EVALUATION, "division by zero"),
    ("  set c.pos = (10 ^ (300 * a.h) * 10 ^ 300, 0)\n", Rejection.EVALUATION,
     "the result is not a finite number"),
    ("  set c.pos = (1e13, 0)\n", Rejection.COORDINATE, "(1e+13, 0) is not within ±1e12"),
])
def test_errors_at_run_time_reject_the_step_and_are_counted(sets, reason, detail):
    engine = FreeEngine(parse_ggr(prod("", sets=sets)), 0)
    summary = engine.run(10)
    assert summary.applied == 0 and summary.reasons == {reason: summary.rejected}
    assert summary.stop.startswith("500 rejected") and detail in summary.stop
    assert engine.host.counts["vertex"] == 2


def test_a_grammar_that_never_ends_stops_at_its_limits():
    text = prod("", "a  b  c: pt\n    a -> b seg  b -> c seg", "  set c.pos = b.pos + (1, 0)\n")
    engine = FreeEngine(parse_ggr(text), 0, limits={0: 25})
    summary = engine.run(1000)
    assert summary.applied == 25 and summary.vertices == 27
    assert summary.stop.startswith("no production applies")


def test_dpo_refuses_a_dangling_deletion():
    text = (HEAD.replace("spo", "dpo") + START
            + "production p {\n  lhs {\n    a: pt\n  }\n  rhs {\n  }\n}\n")
    summary = FreeEngine(parse_ggr(text), 0).run(5)
    assert summary.applied == 0 and summary.reasons == {Rejection.DANGLING: summary.rejected}
    spo = FreeEngine(parse_ggr(text.replace("dpo", "spo")), 0).run(5)
    assert spo.applied == 2 and spo.vertices == 0 and spo.edges == 0


def test_svg_values_are_escaped():
    text = (HEAD + "attribute vertex d = \"\"\nattribute vertex fill = colour(\"#000\")\n"
            + "start {\n  a: pt\n  set a.pos = (0, 0)\n  set a.d = \"M 0 0\\\" onload=\\\"x<y>\"\n}\n")
    svg = render_free_svg(FreeEngine(parse_ggr(text), 0).host, parse_ggr(text).header)
    import xml.etree.ElementTree as ET
    paths = [el for el in ET.fromstring(svg).iter() if el.tag.endswith("path")]
    # The value comes back whole as the path's data, and adds no attribute of its own.
    assert [p.get("d") for p in paths] == ['M 0 0" onload="x<y>']
    assert not any("onload" in el.attrib for el in ET.fromstring(svg).iter())


SPATIAL = (HEAD + "start {\n  a: pt (0, 0)   b: pt (1, 0)   c: pt (0.5, 1)\n}\n"
           "production p SPATIAL {\n  lhs {\n    l: pt (0, 0)   r: pt (1, 1)\n  }\n"
           "  rhs {\n    l   r\n    l -- r seg\n  }\n}\n")


def test_spatial_matching_keeps_the_pattern_order():
    def runs(flag: str) -> set:
        found = set()
        for seed in range(12):
            engine = FreeEngine(parse_ggr(SPATIAL.replace("SPATIAL", flag)), seed)
            engine.step()
            e = next(el for el in engine.host.elements.values() if el.kind == "edge")
            found.add(tuple(engine.host.pos(v) for v in e.ends))
        return found
    # r is right of l and above it: of the three vertices only a, c are placed so
    assert runs("spatial") == {((0.0, 0.0), (0.5, 1.0))}
    assert len(runs("")) > 1


def test_spatial_needs_pattern_positions():
    text = SPATIAL.replace("SPATIAL", "spatial").replace(" (0, 0)   r: pt (1, 1)", "   r: pt")
    with pytest.raises(UserError, match="'spatial' compares pattern positions"):
        parse_ggr(text)


def test_an_empty_mother_graph_matches_every_step():
    text = HEAD + "production seed {\n  lhs {\n  }\n  rhs {\n    p: pt\n  }\n  set p.pos = (uniform(0, 1), 0)\n}\n"
    summary = FreeEngine(parse_ggr(text), 0).run(7)
    assert summary.applied == 7 and summary.vertices == 7


def test_the_repl_refuses_productions_with_a_message():
    import io

    from runtime.repl.session import Output, Session
    s = Session(Output(io.StringIO(), io.StringIO(), colour=False))
    with pytest.raises(UserError, match="the REPL explores angle-graph rules"):
        s.use(load_ggr(ROOT / "examples" / "koch.ggr"), "koch.ggr")


def test_ggc_verify_refuses_productions():
    import argparse

    from compiler.compile_cmd import run_verify
    args = argparse.Namespace(file=str(ROOT / "examples" / "koch.ggr"), max_primitives=8,
                              seconds=None)
    with pytest.raises(UserError, match="holds hand-written productions"):
        run_verify(args)


def test_a_side_has_a_bounded_number_of_elements():
    many = "  ".join(f"v{k}: pt" for k in range(120))
    text = HEAD + "production big {\n  lhs {\n    " + many + "\n  }\n  rhs {\n  }\n}\n"
    with pytest.raises(UserError, match="at most 100"):
        parse_ggr(text)


def test_ggrun_writes_productions_as_svg_json_and_graphml(tmp_path):
    import json

    import networkx as nx

    from report.ggrun import main
    for suffix in ("svg", "json", "graphml"):
        out = tmp_path / f"tree.{suffix}"
        assert main([str(ROOT / "examples" / "honda-tree.ggr"), "--steps", "20", "--out",
                     str(out), "--quiet"]) == 0
    assert (tmp_path / "tree.svg").read_text().startswith("<svg")
    doc = json.loads((tmp_path / "tree.json").read_text())
    assert len(doc["vertices"]) == 42 and doc["vertex_labels"][0] == "root"
    g = nx.read_graphml(tmp_path / "tree.graphml")
    assert g.number_of_nodes() == 42 and g.number_of_edges() == 41
