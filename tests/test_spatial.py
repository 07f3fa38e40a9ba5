"""The spatial grid's exact queries against brute force: the ray cast to the left (which jumps
over empty cells) and the coincidence test (on its fine point cells), on sparse and dense
random drawings, with segments and points added, moved and removed."""

from __future__ import annotations

from hypothesis import example, given, settings
from hypothesis import strategies as st

from runtime.geometry.spatial import Grid

coord = st.one_of(st.integers(-40, 40).map(float),                  # shared heights and ends
                  st.floats(-40, 40, allow_nan=False, allow_infinity=False))
point = st.tuples(coord, coord)


def ray_reference(segs: dict, p, skip=(), tol=0.0):
    """The documented rule over every segment: the hit (within the segment's box) furthest
    right of those left of p, ties by the lean, then by the smaller id."""
    px, py = p
    top = py + tol
    best = None
    for sid, ((ax, ay), (bx, by)) in segs.items():
        if sid in skip or (ay > top) == (by > top):
            continue
        if ay > by:
            ax, ay, bx, by = bx, by, ax, ay
        lean = (bx - ax) / (by - ay)
        x = ax if ay >= py - tol else ax + (py - ay) * lean
        x = min(max(x, min(ax, bx)), max(ax, bx))         # within the segment's box
        if x >= px:
            continue
        if best is None or (x, lean) > best[:2] or ((x, lean) == best[:2] and sid < best[2]):
            best = (x, lean, sid)
    return None if best is None else (best[2], best[0])


def build(cell, pieces, removed, seg=None):
    g, segs = Grid(cell, fine=0.5, seg=seg), {}
    for k, (a, b) in enumerate(pieces):
        g.add_segment(k, a, b)
        g.add_point(("a", k), a)
        g.add_point(("b", k), b)
        segs[k] = (a, b)
    for k in sorted(removed):
        if k in segs:
            g.remove_segment(k)
            del segs[k]
    return g, segs


@settings(max_examples=300, deadline=None)
@given(cell=st.sampled_from([0.5, 1.0, 3.0]), seg=st.sampled_from([None, 0.4, 1.5]),
       pieces=st.lists(st.tuples(point, point).filter(lambda s: s[0] != s[1]), max_size=25),
       removed=st.sets(st.integers(0, 24)), rays=st.lists(point, min_size=1, max_size=6),
       tol=st.sampled_from([0.0, 1e-7]))
# A hit computed right of its segment's box (x = 0.0, a column's edge, for a segment ending at
# -2e-240): unclamped, it beat the hit that ended the walk at that column.
@example(cell=0.5, seg=None, removed=set(), rays=[(1.0, 0.0)], tol=0.0,
         pieces=[((0.0, 0.0), (0.0, 1.0)),
                 ((-1.0, -1.0), (-2.1194722933806824e-240, 2.0725227544860056e-129))])
def test_ray_left_finds_what_brute_force_finds(cell, seg, pieces, removed, rays, tol):
    """Segment cells of their own size (smaller or larger than the point cells) too."""
    g, segs = build(cell, pieces, removed, seg)
    skip = {k for k in segs if k % 7 == 3}
    for p in rays:
        assert g.ray_left(p, skip, tol) == ray_reference(segs, p, skip, tol)


@settings(max_examples=200, deadline=None)
@given(pts=st.lists(point, max_size=30), moves=st.lists(st.tuples(st.integers(0, 29), point),
                                                        max_size=10),
       probes=st.lists(point, min_size=1, max_size=8),
       r=st.sampled_from([0.1, 0.25, 0.5, 2.0]))   # up to fine/2: one cell read
def test_point_within_agrees_with_brute_force(pts, moves, probes, r):
    g = Grid(1.0, fine=0.5)
    where = {}
    for k, p in enumerate(pts):
        g.add_point(k, p)
        where[k] = p
    for k, p in moves:
        if k in where:
            g.remove_point(k)
            g.add_point(k, p)
            where[k] = p
    skip = {k for k in where if k % 5 == 1}
    for p in probes:
        want = any(((p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2) ** 0.5 < r
                   for k, q in where.items() if k not in skip)
        assert g.point_within(p, r, skip) == want


def test_a_ray_across_a_wide_empty_drawing_still_finds_the_far_wall():
    g = Grid(1.0)
    g.add_segment("wall", (-500.0, -1.0), (-500.0, 1.0))
    g.add_point("w0", (-500.0, -1.0))
    g.add_point("w1", (-500.0, 1.0))
    g.add_point("here", (500.0, 0.0))
    assert g.ray_left((500.0, 0.0)) == ("wall", -500.0)


@settings(max_examples=200, deadline=None)
@given(pts=st.lists(st.tuples(point, st.integers(0, 2)), max_size=30),
       moves=st.lists(st.tuples(st.integers(0, 29), point), max_size=10),
       removed=st.sets(st.integers(0, 29)), box=st.tuples(point, point))
def test_points_near_by_tag_is_the_untagged_answer_of_that_tag(pts, moves, removed, box):
    """Points filed under a tag (the host's primitive), moved and removed as the host does."""
    g = Grid(3.0, fine=0.5)
    where = {}
    for k, (p, tag) in enumerate(pts):
        g.add_point(k, p, tag)
        where[k] = tag
    for k, p in moves:
        if k in where:
            g.remove_point(k)
            g.add_point(k, p, where[k])
    for k in removed & set(where):
        g.remove_point(k)
        del where[k]
    (x0, y0), (x1, y1) = box
    every = g.points_near(x0, y0, x1, y1)
    for tag in range(3):
        assert sorted(g.points_near(x0, y0, x1, y1, False, tag)) == \
            [k for k in every if where[k] == tag]


@settings(max_examples=200, deadline=None)
@given(pts=st.lists(st.tuples(point, st.integers(0, 2)), max_size=40),
       box=st.tuples(point, point), centre=point,
       tags=st.sets(st.integers(0, 2), min_size=1), cell=st.sampled_from([0.5, 3.0]))
def test_nearest_first_orders_points_near_by_distance_then_id(pts, box, centre, tags, cell):
    """The lazy nearest-first walk gives the tagged points_near answer, sorted as the matcher
    sorted it before: (squared distance from the centre, id). Shared coordinates make ties."""
    g = Grid(cell, fine=0.5)
    where = {}
    for k, (p, tag) in enumerate(pts):
        g.add_point(k, p, tag)
        where[k] = p
    (x0, y0), (x1, y1) = box
    cx, cy = centre
    near = [k for t in sorted(tags) for k in g.points_near(x0, y0, x1, y1, False, t)]
    want = [k for _, k in sorted(((where[k][0] - cx) ** 2 + (where[k][1] - cy) ** 2, k)
                                 for k in near)]
    assert list(g.nearest_first(x0, y0, x1, y1, centre, tags)) == want
