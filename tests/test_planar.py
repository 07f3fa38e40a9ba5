"""The planar straight-line graph builder: noding, merging, faces and painter's labels."""

from __future__ import annotations

import networkx as nx
import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from grammar_lang.diagnostics import Span, UserError
from grammar_lang.planar import build_planar_graph
from grammar_lang.source import ExampleSource, ExplicitEdge, Options, Region, Stroke


def build(*paint, merge=None, exterior="exterior"):
    source = ExampleSource(path="t.gg", name="t", paint=list(paint), exterior=exterior,
                           options=Options(merge_distance=merge))
    return build_planar_graph(source)


def rect(x0, y0, x1, y1):
    return ((x0, y0), (x1, y0), (x1, y1), (x0, y1))


def edge_map(graph):
    """{(p, q) as coordinate pairs, sorted: (left, right, cls) seen from p to q}."""
    out = {}
    for u, v, left, right, cls in graph.edges:
        p, q = graph.vertices[u], graph.vertices[v]
        if p > q:
            p, q, left, right = q, p, right, left
        out[(p, q)] = (left, right, cls)
    return out


# --- noding and merging --------------------------------------------------------------------

def test_crossing_strokes_are_split_at_the_crossing():
    g = build(Stroke(((0, 0), (10, 10))), Stroke(((0, 10), (10, 0))))
    assert (5.0, 5.0) in g.vertices
    assert len(g.vertices) == 5 and len(g.edges) == 4
    assert all(e[2:] == ("exterior", "exterior", "0") for e in g.edges)


def test_t_junction_and_near_t_junction_split_the_bar():
    exact = build(Stroke(((0, 0), (10, 0))), Stroke(((5, 0), (5, 5))))
    near = build(Stroke(((0, 0), (10, 0))), Stroke(((5, 0.02), (5, 5))), merge=0.1)
    for g in (exact, near):
        assert len(g.vertices) == 4 and len(g.edges) == 3
    assert (5.0, 0.02) in near.vertices          # the bar bends to the drawn point


def test_near_points_merge_into_one_vertex():
    g = build(Stroke(((0, 0), (10, 0))), Stroke(((10.01, 0.01), (10, 10))))
    assert len(g.vertices) == 3 and len(g.edges) == 2


def test_collinear_overlaps_become_one_edge_per_piece():
    g = build(Stroke(((0, 0), (6, 0))), Stroke(((3, 0), (9, 0))), Stroke(((9, 0), (0, 0))))
    assert sorted(g.vertices) == [(0.0, 0.0), (3.0, 0.0), (6.0, 0.0), (9.0, 0.0)]
    assert len(g.edges) == 3


def test_output_is_sorted_and_deterministic():
    paint = [Stroke(((0, 0), (10, 10))), Stroke(((0, 10), (10, 0))), Stroke(((3, 0), (3, 9)))]
    g = build(*paint)
    assert list(g.vertices) == sorted(g.vertices)
    assert list(g.edges) == sorted(g.edges)
    assert all(u < v for u, v, *_ in g.edges)
    assert build(*reversed(paint)) == g


# --- labels --------------------------------------------------------------------------------

def test_painters_order_and_hidden_outline():
    g = build(Region((rect(0, 0, 4, 4),), "a"), Region((rect(2, 2, 6, 6),), "b"))
    edges = edge_map(g)
    # a's outline inside b is hidden: (2,4)-(4,4) and (4,2)-(4,4) are gone, as is (4,4).
    assert (4.0, 4.0) not in g.vertices
    assert ((2.0, 2.0), (2.0, 4.0)) in edges
    assert edges[((2.0, 2.0), (2.0, 4.0))][:2] == ("a", "b")
    assert edges[((2.0, 2.0), (4.0, 2.0))][:2] == ("b", "a")
    assert len(g.edges) == 10


def test_region_under_a_larger_later_region_disappears():
    g = build(Region((rect(1, 1, 2, 2),), "a"), Region((rect(0, 0, 4, 4),), "b"))
    assert sorted(g.vertices) == sorted(rect(0, 0, 4, 4))
    assert {frozenset(e[2:4]) for e in g.edges} == {frozenset(("b", "exterior"))}


def test_shared_outline_of_same_label_regions_is_kept():
    g = build(Region((((0, 0), (4, 0), (0, 4)),), "a"), Region((((4, 0), (4, 4), (0, 4)),), "a"))
    edges = edge_map(g)
    assert edges[((0.0, 4.0), (4.0, 0.0))][:2] == ("a", "a")
    assert len(g.edges) == 5


def test_evenodd_hole_and_nonzero_fill():
    outer, inner = rect(0, 0, 10, 10), rect(3, 3, 6, 6)
    holed = edge_map(build(Region((outer, inner), "a", evenodd=True)))
    assert holed[((3.0, 3.0), (6.0, 3.0))][:2] == ("exterior", "a")
    same_way = edge_map(build(Region((outer, inner), "a")))
    assert same_way[((3.0, 3.0), (6.0, 3.0))][:2] == ("a", "a")
    opposite = edge_map(build(Region((outer, tuple(reversed(inner))), "a")))
    assert opposite[((3.0, 3.0), (6.0, 3.0))][:2] == ("exterior", "a")


def test_crossings_with_hidden_lines_leave_no_vertex_behind():
    g = build(Stroke(((2, -1), (2, 1))), Region((rect(1, -2, 3, 2),), "b"),
              Region((rect(0, 0, 4, 4),), "a"))
    assert (2.0, 0.0) not in g.vertices
    assert edge_map(g)[((1.0, 0.0), (3.0, 0.0))][:2] == ("a", "b")
    assert (2.0, -1.0) not in g.vertices


def test_merge_distance_zero_keeps_every_distinct_point():
    g = build(Stroke(((0, 0), (10, 0))), Stroke(((10.001, 0), (20, 0))), merge=0.0)
    assert len(g.vertices) == 4


def test_strokes_inside_regions_and_nested_components():
    g = build(Region((rect(0, 0, 10, 10),), "a"), Stroke(((2, 2), (5, 5))),
              Stroke(rect(6, 6, 8, 8), closed=True))
    edges = edge_map(g)
    assert edges[((2.0, 2.0), (5.0, 5.0))][:2] == ("a", "a")
    assert edges[((6.0, 6.0), (8.0, 6.0))][:2] == ("a", "a")


def test_classed_stroke_classes_the_outline_and_hidden_strokes_vanish():
    g = build(Region((rect(0, 0, 4, 4),), "a"), Stroke(((0, 0), (4, 0)), cls="1"),
              Stroke(((10, 10), (12, 12)), cls="2"), Region((rect(9, 9, 13, 13),), "b"))
    edges = edge_map(g)
    assert edges[((0.0, 0.0), (4.0, 0.0))] == ("a", "exterior", "1")
    assert not any(cls == "2" for _, _, _, _, cls in g.edges)


def test_explicit_edges_label_the_faces_they_bound():
    square = [(0, 0), (4, 0), (4, 4), (0, 4)]
    paint = [ExplicitEdge(p, q, "in", "exterior") for p, q in zip(square, square[1:] + square[:1])]
    g = build(*paint, Stroke(((1, 1), (2, 2))))
    edges = edge_map(g)
    assert edges[((1.0, 1.0), (2.0, 2.0))][:2] == ("in", "in")
    assert edges[((0.0, 0.0), (4.0, 0.0))][:2] == ("in", "exterior")


def test_explicit_edge_conflicting_with_a_painted_face_is_reported():
    span = Span("t.gg", 3, 1)
    with pytest.raises(UserError) as info:
        build(Region((rect(0, 0, 4, 4),), "a"), ExplicitEdge((0, 0), (4, 0), "b", "exterior",
                                                               span=span))
    assert info.value.diagnostics[0].span == span
    assert "'b'" in info.value.diagnostics[0].message


def test_explicit_edges_disagreeing_about_a_face_are_reported():
    with pytest.raises(UserError, match="conflicting labels"):
        build(ExplicitEdge((0, 0), (4, 0), "a", "exterior"),
              ExplicitEdge((4, 0), (2, 3), "b", "exterior"),
              ExplicitEdge((2, 3), (0, 0), "a", "exterior"))
    with pytest.raises(UserError, match="outside the drawing"):
        build(ExplicitEdge((0, 0), (4, 0), "a", "b"))


@pytest.mark.parametrize("far", [1e13, 1e200, float("inf"), float("nan")])
def test_huge_coordinates_are_reported_at_their_shape(far, recwarn):
    span = Span("t.gg", 2, 1)
    with pytest.raises(UserError) as info:
        build(Region((rect(0, 0, 4, 4),), "a"),
              Region((((0, 0), (far, 0), (far, far)),), "b", span=span))
    (d,) = info.value.diagnostics
    assert d.span == span and "beyond" in d.message
    assert not [w for w in recwarn if issubclass(w.category, RuntimeWarning)]


@pytest.mark.parametrize("far, merge", [(1e11, 1.0), (5e9, 1e-3), (1e10, 0.0)])
def test_a_drawing_spanning_too_many_merge_distances_is_reported_at_its_far_shape(far, merge):
    # A village of 1,600 px with one point at 1e11 (merge distance 1) once split and re-merged
    # its pieces until it ran out of memory. (With the default merge distance, a fraction of
    # the span, a far point makes the rest collapse instead, which is reported as such.)
    span = Span("t.gg", 9, 1)
    with pytest.raises(UserError) as info:
        build(Region((rect(0, 0, 1600, 800),), "sky"), Region((rect(0, 0, 1600, 560),), "land"),
              Region((((1440, 575), (1480, 575), (far, 630)),), "crown", span=span),
              merge=merge)
    (d,) = info.value.diagnostics
    assert d.span == span and "spans" in d.message


def test_a_drawing_within_the_span_limit_builds():
    g = build(Region((rect(0, 0, 4, 4),), "a"), Stroke(((0, 0), (3e7, 0))), merge=1.0)
    assert len(g.vertices) >= 4


def test_custom_exterior_name():
    g = build(Region((rect(0, 0, 1, 1),), "land"), exterior="sea")
    assert {frozenset(e[2:4]) for e in g.edges} == {frozenset(("land", "sea"))}


# --- degenerate input ----------------------------------------------------------------------

@pytest.mark.parametrize("paint, message", [
    ([Region((((0, 0), (1, 1), (2, 2)),), "a", span=Span("t.gg", 7, 3))], "zero area"),
    ([Stroke(((0, 0), (0.001, 0)), span=Span("t.gg", 7, 3)), Stroke(((0, 0), (10, 0)))],
     "zero length"),
    ([Region((rect(0, 0, 10, 0.01),), "a", span=Span("t.gg", 7, 3)), Stroke(((0, 5), (10, 5)))],
     "collapses"),
    ([ExplicitEdge((1, 1), (1, 1), "a", "a", span=Span("t.gg", 7, 3)),
      Stroke(((0, 0), (5, 5)))], "zero length"),
])
def test_degenerate_shapes_are_reported_where_they_come_from(paint, message):
    with pytest.raises(UserError) as info:
        build(*paint)
    diagnostic = info.value.diagnostics[0]
    assert message in diagnostic.message
    assert diagnostic.span == Span("t.gg", 7, 3)


def test_absurd_coordinates_are_reported():
    with pytest.raises(UserError, match="beyond"):
        build(Stroke(((0, 0), (1e300, 0))))
    with pytest.raises(UserError, match="beyond"):
        build(Stroke(((0, 0), (float("nan"), 0))))


def test_empty_drawing_is_reported():
    with pytest.raises(UserError, match="no edges"):
        build(Stroke(((1, 1),)))


# --- properties ----------------------------------------------------------------------------

coordinate = st.integers(0, 12)
segment = st.tuples(coordinate, coordinate, coordinate, coordinate).filter(
    lambda s: (s[0], s[1]) != (s[2], s[3]))


def assert_noded(graph, tolerance=1e-7):
    pts = np.asarray(graph.vertices)
    ends = np.asarray([e[:2] for e in graph.edges])
    assert len(ends) and np.all(ends[:, 0] != ends[:, 1])
    length = np.hypot(*(pts[ends[:, 1]] - pts[ends[:, 0]]).T)
    assert np.all(length > tolerance), "zero-length edge"
    lines = shapely.linestrings(pts[ends])
    i, j = shapely.STRtree(lines).query(lines, predicate="intersects")
    for a, b in zip(i.tolist(), j.tolist()):
        if a >= b:
            continue
        shared = set(ends[a].tolist()) & set(ends[b].tolist())
        meet = shapely.intersection(lines[a], lines[b])
        assert meet.length <= tolerance, "overlapping edges"
        assert shared, f"edges {ends[a]} and {ends[b]} cross"
        (v,) = shared
        assert shapely.distance(meet, shapely.Point(pts[v])) <= tolerance


def euler_holds(graph):
    lines = [shapely.LineString([graph.vertices[u], graph.vertices[v]])
             for u, v, *_ in graph.edges]
    bounded = len(shapely.get_parts(shapely.polygonize(lines)))
    g = nx.Graph()
    g.add_nodes_from(range(len(graph.vertices)))
    g.add_edges_from((u, v) for u, v, *_ in graph.edges)
    components = nx.number_connected_components(g)
    return len(graph.vertices) - len(graph.edges) + bounded + 1 == 1 + components


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(segment, min_size=1, max_size=9))
def test_random_segments_become_a_planar_graph(segments):
    merge = 1e-4
    g = build(*(Stroke(((a, b), (c, d))) for a, b, c, d in segments), merge=merge)
    assert_noded(g)
    assert euler_holds(g)
    assert all(e[2:] == ("exterior", "exterior", "0") for e in g.edges)
    output = shapely.MultiLineString([[g.vertices[u], g.vertices[v]] for u, v, *_ in g.edges])
    drawn = shapely.MultiLineString([[(a, b), (c, d)] for a, b, c, d in segments])
    for a, b, c, d in segments:   # every drawn point is on the output, and nothing else is
        for t in np.linspace(0, 1, 7):
            p = shapely.Point(a + t * (c - a), b + t * (d - b))
            assert output.distance(p) <= 4 * merge
    for u, v, *_ in g.edges:
        mid = shapely.Point(np.mean([g.vertices[u], g.vertices[v]], axis=0))
        assert drawn.distance(mid) <= 4 * merge


rectangle = st.tuples(st.integers(0, 7), st.integers(0, 7), st.integers(1, 4), st.integers(1, 4),
                      st.sampled_from("abc"))


def painted(rects, x, y):
    label = "exterior"
    for x0, y0, w, h, name in rects:
        if x0 < x < x0 + w and y0 < y < y0 + h:
            label = name
    return label


def covering(rects, x, y):
    return [k for k, (x0, y0, w, h, _) in enumerate(rects)
            if x0 < x < x0 + w and y0 < y < y0 + h]


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(rectangle, min_size=1, max_size=5))
def test_random_rectangles_follow_painters_order(rects):
    paint = [Region((rect(x, y, x + w, y + h),), name) for x, y, w, h, name in rects]
    g = build(*paint, merge=1e-4)
    assert_noded(g)
    assert euler_holds(g)
    eps = 1e-3
    for u, v, left, right, _ in g.edges:
        (px, py), (qx, qy) = g.vertices[u], g.vertices[v]
        mx, my = (px + qx) / 2, (py + qy) / 2
        nx_, ny_ = -(qy - py), qx - px
        norm = np.hypot(nx_, ny_)
        nx_, ny_ = nx_ / norm * eps, ny_ / norm * eps
        assert painted(rects, mx + nx_, my + ny_) == left
        assert painted(rects, mx - nx_, my - ny_) == right
    # Each unit step of every outline is an edge exactly when some owner of it is not hidden
    # by a later rectangle covering both of its sides.
    output = shapely.MultiLineString([[g.vertices[u], g.vertices[v]] for u, v, *_ in g.edges])
    steps = set()
    for x, y, w, h, _ in rects:
        steps |= {(x + k + 0.5, yy, 0) for k in range(w) for yy in (y, y + h)}
        steps |= {(xx, y + k + 0.5, 1) for k in range(h) for xx in (x, x + w)}
    for sx, sy, vertical in sorted(steps):
        side = (eps, 0) if vertical else (0, eps)
        a = set(covering(rects, sx + side[0], sy + side[1]))
        b = set(covering(rects, sx - side[0], sy - side[1]))
        owners = [k for k, (x, y, w, h, _) in enumerate(rects)
                  if (vertical and sx in (x, x + w) and y < sy < y + h)
                  or (not vertical and sy in (y, y + h) and x < sx < x + w)]
        visible = any(not any(j > k for j in a & b) for k in owners)
        assert (output.distance(shapely.Point(sx, sy)) < 1e-9) == visible


real = st.floats(0, 100, allow_nan=False, allow_infinity=False)


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.tuples(real, real, real, real), min_size=2, max_size=12))
def test_random_hand_drawn_segments_stay_planar_at_the_default_merge_distance(segments):
    """Noisy input (near-misses, near-parallel lines) still gives a planar graph or a diagnostic."""
    try:
        g = build(*(Stroke(((a, b), (c, d))) for a, b, c, d in segments))
    except UserError:
        return
    assert_noded(g, tolerance=1e-9)
    assert euler_holds(g)


def test_a_line_below_the_coordinate_resolution_gets_a_diagnostic():
    """Found by hypothesis: a 1.6e-20 stroke kept two vertices that round to one point."""
    tiny = Stroke(((0.0, 0.0), (0.0, 1.5624340328094826e-20)))
    with pytest.raises(UserError, match="zero length after merging"):
        build(tiny, tiny)
