"""The verifier on the corpus: every example, drawn as itself, passes; each kind of damage is
caught and named; rigid motions that keep local similarity keep a pass."""

import math
from dataclasses import replace
from functools import lru_cache

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.ops import polylabel

from conftest import CORPUS, corpus_names
from grammar_lang.loader import load_example
from grammar_lang.rules import Header
from runtime.output.drawing import DEdge, Drawing, DVertex, drawing_from_example, parse_drawing
from runtime.geometry.faces import compute_faces
from runtime.verifier import as_reference, check_drawing

NAMES = corpus_names()


@lru_cache(maxsize=None)
def example(name):
    return load_example(CORPUS / f"{name}.svg")


@lru_cache(maxsize=None)
def own_drawing(name) -> Drawing:
    # Through the JSON text, so the 6-decimal rounding of real files is part of every test.
    return parse_drawing(drawing_from_example(example(name)).to_json())


def kinds(failures):
    return {f.kind for f in failures}


def xy(d: Drawing) -> dict[int, np.ndarray]:
    return {v.id: np.array([v.x, v.y]) for v in d.vertices}


def moved(d: Drawing, vid: int, p) -> Drawing:
    return replace(d, vertices=tuple(DVertex(v.id, float(p[0]), float(p[1])) if v.id == vid else v
                                     for v in d.vertices))


def transformed(d: Drawing, f) -> Drawing:
    return replace(d, vertices=tuple(DVertex(v.id, *map(float, f(np.array([v.x, v.y]))))
                                     for v in d.vertices))


def union(a: Drawing, b: Drawing) -> Drawing:
    """Both drawings in one, b's ids shifted past a's."""
    off = max(v.id for v in a.vertices) + 1
    return Drawing(a.vertices + tuple(DVertex(v.id + off, v.x, v.y) for v in b.vertices),
                   a.edges + tuple(replace(e, u=e.u + off, v=e.v + off) for e in b.edges))


def degree(d: Drawing) -> dict[int, int]:
    out = {v.id: 0 for v in d.vertices}
    for e in d.edges:
        out[e.u] += 1
        out[e.v] += 1
    return out


def edge_length(d, e):
    p = xy(d)
    return float(np.linalg.norm(p[e.v] - p[e.u]))


# --- the example itself ---------------------------------------------------------------------

@pytest.mark.parametrize("name", NAMES)
def test_example_drawn_as_itself_passes(name):
    failures = check_drawing(example(name), own_drawing(name))
    assert failures == [], "\n".join(f.render() for f in failures)


def test_header_is_accepted_like_the_example():
    ex = example("house-filled")
    header = Header(vocabulary=ex.vocabulary, options=ex.options)
    d = own_drawing("house-filled")
    assert check_drawing(header, d) == []
    assert as_reference(header).labels == as_reference(ex).labels


def test_drawing_without_label_names_passes():
    for name in NAMES:
        d = own_drawing(name)
        bare = replace(d, edges=tuple(replace(e, label=None) for e in d.edges))
        assert check_drawing(example(name), bare) == [], name


# --- damage, one kind at a time -------------------------------------------------------------

def label_sizes(d):
    out = {}
    for e in d.edges:
        out[e.label] = out.get(e.label, 0) + 1
    return out


@pytest.mark.parametrize("name", NAMES)
def test_rotating_an_edge_far_breaks_its_vertex(name):
    d = own_drawing(name)
    k = 0
    e = d.edges[k]
    p = xy(d)
    c, s = math.cos(math.radians(25)), math.sin(math.radians(25))
    r = p[e.v] - p[e.u]
    bad = moved(d, e.v, p[e.u] + np.array([c * r[0] - s * r[1], s * r[0] + c * r[1]]))
    failures = check_drawing(example(name), bad)
    assert any(f.kind in ("ring", "label") and k in f.edges for f in failures), \
        [f.render() for f in failures]


@pytest.mark.parametrize("name", NAMES)
def test_rotating_an_edge_slightly_breaks_its_direction(name):
    d = own_drawing(name)
    sizes = label_sizes(d)
    p = xy(d)
    # An edge whose label also has an edge away from the moved vertex.
    cands = [k for k, e in enumerate(d.edges)
             if any(f.label == e.label and e.v not in (f.u, f.v) for f in d.edges)]
    if not cands:
        assert max(sizes.values()) == 1 or len(d.edges) < 3
        pytest.skip("every label has one edge here")
    k = cands[0]
    e = d.edges[k]
    c, s = math.cos(math.radians(3)), math.sin(math.radians(3))
    r = p[e.v] - p[e.u]
    bad = moved(d, e.v, p[e.u] + np.array([c * r[0] - s * r[1], s * r[0] + c * r[1]]))
    failures = check_drawing(example(name), bad)
    hits = [f for f in failures if f.kind == "direction" and k in f.edges]
    assert hits, [f.render() for f in failures]
    assert e.label in hits[0].message


def nonadjacent_pair(d):
    p = xy(d)
    for i, e in enumerate(d.edges):
        for j, f in enumerate(d.edges):
            if j <= i or {e.u, e.v} & {f.u, f.v}:
                continue
            # u must not be on f's line, or the moved edge would run along f.
            a, b = p[f.u], p[f.v]
            cross = (b - a)[0] * (p[e.u] - a)[1] - (b - a)[1] * (p[e.u] - a)[0]
            if abs(cross) > 1e-3 * np.linalg.norm(b - a) ** 2:
                return i, j
    return None


@pytest.mark.parametrize("name", NAMES)
def test_moving_a_vertex_across_an_edge_is_a_crossing(name):
    d = own_drawing(name)
    pair = nonadjacent_pair(d)
    if pair is None:
        pytest.skip("every two edges share a vertex (see the copy test below)")
    i, j = pair
    e, f = d.edges[i], d.edges[j]
    p = xy(d)
    mid = (p[f.u] + p[f.v]) / 2
    bad = moved(d, e.v, p[e.u] + (mid - p[e.u]) * 1.3)
    failures = check_drawing(example(name), bad)
    assert any(x.kind == "crossing" and i in x.edges and j in x.edges for x in failures), \
        [x.render() for x in failures]


@pytest.mark.parametrize("name", NAMES)
def test_copy_placed_across_an_edge_is_a_crossing(name):
    d = own_drawing(name)
    p = xy(d)
    dirs = [(p[e.v] - p[e.u]) / np.linalg.norm(p[e.v] - p[e.u]) for e in d.edges]
    pair = next(((i, j) for i in range(len(dirs)) for j in range(len(dirs))
                 if abs(dirs[i][0] * dirs[j][1] - dirs[i][1] * dirs[j][0]) > 0.1), None)
    if pair is None:
        assert len({e.label for e in d.edges}) == 1
        pytest.skip("all edges are parallel")
    i, j = pair
    e, f = d.edges[i], d.edges[j]
    shift = (p[f.u] + p[f.v]) / 2 - (p[e.u] + p[e.v]) / 2
    both = union(d, transformed(d, lambda q: q + shift))
    failures = check_drawing(example(name), both)
    copy_i = len(d.edges) + i
    assert any(x.kind == "crossing" and {j, copy_i} <= set(x.edges) for x in failures), \
        [x.render() for x in failures]


@pytest.mark.parametrize("name", NAMES)
def test_shifted_copy_along_an_edge_overlaps(name):
    d = own_drawing(name)
    e = d.edges[0]
    p = xy(d)
    shift = (p[e.v] - p[e.u]) * 0.4
    failures = check_drawing(example(name), union(d, transformed(d, lambda q: q + shift)))
    assert any(f.kind == "overlap" and 0 in f.edges for f in failures), \
        [f.render() for f in failures]


@pytest.mark.parametrize("name", NAMES)
def test_vertex_onto_another_vertex_coincides(name):
    d = own_drawing(name)
    adj = {(e.u, e.v) for e in d.edges} | {(e.v, e.u) for e in d.edges}
    ids = [v.id for v in d.vertices]
    pair = next(((a, b) for a in ids for b in ids if a < b and (a, b) not in adj), None)
    if pair is None:
        pytest.skip("every two vertices are joined")
    a, b = pair
    failures = check_drawing(example(name), moved(d, a, xy(d)[b]))
    assert any(f.kind == "coincident" and set(f.vertices) == {a, b} for f in failures), \
        [f.render() for f in failures]


@pytest.mark.parametrize("name", NAMES)
def test_stick_from_the_middle_of_an_edge_touches(name):
    d = own_drawing(name)
    p = xy(d)
    j = len(d.edges) - 1
    f = d.edges[j]
    r = p[f.v] - p[f.u]
    foot = (p[f.u] + p[f.v]) / 2
    top = foot + np.array([-r[1], r[0]]) / 3      # into the face on f's left
    new = max(p) + 1                              # the id `union` gives the stick's foot
    stick = Drawing((DVertex(0, *map(float, foot)), DVertex(1, *map(float, top))),
                    (DEdge(0, 1, f.left, f.left, f.cls),))
    failures = check_drawing(example(name), union(d, stick))
    assert any(x.kind == "touch" and j in x.edges and new in x.vertices for x in failures), \
        [x.render() for x in failures]


@pytest.mark.parametrize("name", [n for n in NAMES if len(example(n).face_labels) > 1])
def test_swapping_the_face_labels_of_an_edge_is_caught(name):
    d = own_drawing(name)
    k = next(i for i, e in enumerate(d.edges) if e.left != e.right)
    e = d.edges[k]
    for label in (e.label, None):
        bad = replace(d, edges=tuple(replace(x, left=x.right, right=x.left, label=label)
                                     if i == k else x for i, x in enumerate(d.edges)))
        failures = check_drawing(example(name), bad)
        assert any(f.kind == "face" and k in f.edges for f in failures), \
            [f.render() for f in failures]


@pytest.mark.parametrize("name", NAMES)
def test_stretching_beyond_the_maximum_length(name):
    d = own_drawing(name)
    ref = as_reference(example(name))
    classes = {c.name: c for c in ref.classes}
    stretchable = [(k, e) for k, e in enumerate(d.edges)
                   if not classes[e.cls].rigid and classes[e.cls].fixed is None]
    k, e = max(stretchable, key=lambda ke: edge_length(d, ke[1]) / classes[ke[1].cls].max_length)
    factor = 1.05 * classes[e.cls].max_length / edge_length(d, e)
    origin = xy(d)[d.vertices[0].id]
    bad = transformed(d, lambda q: origin + (q - origin) * factor)
    failures = check_drawing(example(name), bad)
    hit = [f for f in failures if f.kind == "length" and k in f.edges]
    assert hit and "longer" in hit[0].message, [f.render() for f in failures]


@pytest.mark.parametrize("name", NAMES)
def test_stretching_a_dangling_edge_fails_only_there(name):
    d = own_drawing(name)
    deg = degree(d)
    ref = as_reference(example(name))
    classes = {c.name: c for c in ref.classes}
    p = xy(d)
    for k, e in enumerate(d.edges):
        if deg[e.v] == 1 and not classes[e.cls].rigid:
            r = p[e.v] - p[e.u]
            target = p[e.u] + r * (1.02 * classes[e.cls].max_length / np.linalg.norm(r))
            failures = check_drawing(example(name), moved(d, e.v, target))
            assert any(f.kind == "length" and f.edges == (k,) for f in failures)
            assert kinds(failures) <= {"length", "crossing", "touch", "overlap"}
            return
    pytest.skip("no dangling free edge")


def inner_faces(d):
    """(label, polygon) of each bounded face, from the edges' stated labels."""
    ids = [v.id for v in d.vertices]
    index = {v: i for i, v in enumerate(ids)}
    pts = np.array([(v.x, v.y) for v in d.vertices])
    ends = np.array([(index[e.u], index[e.v]) for e in d.edges])
    faces = compute_faces(pts, ends)
    out = []
    for face in faces.faces[1:]:
        cyc = faces.cycles[face.outer]
        h = cyc[0]
        label = d.edges[h >> 1].right if h & 1 else d.edges[h >> 1].left
        poly = shapely.Polygon(pts[[ends[x >> 1][x & 1] for x in cyc]]).buffer(0)
        out.append((label, poly))
    return out


def nested_copy(d, poly):
    """A copy of d scaled into the largest circle inside poly."""
    centre = polylabel(poly, tolerance=1e-3)
    radius = poly.exterior.distance(centre)
    p = np.array([(v.x, v.y) for v in d.vertices])
    mid = (p.min(axis=0) + p.max(axis=0)) / 2
    reach = np.linalg.norm(p - mid, axis=1).max()
    s = 0.7 * radius / reach
    c = np.array([centre.x, centre.y])
    return union(d, transformed(d, lambda q: c + (q - mid) * s)), s


@pytest.mark.parametrize("name", NAMES)
def test_nesting_a_copy_inside_a_face(name):
    d = own_drawing(name)
    faces = inner_faces(d)
    ex = example(name)
    if not faces:
        pytest.skip("no bounded face")
    label, poly = max(faces, key=lambda lp: lp[1].area)
    both, s = nested_copy(d, poly)
    failures = check_drawing(ex, both)
    if label != ex.exterior:
        assert any(f.kind == "nesting" for f in failures), [f.render() for f in failures]
    else:
        # An exterior hole takes a copy of the whole shape: locally similar, if lengths allow.
        assert not {"nesting", "face"} & kinds(failures), [f.render() for f in failures]
        if all(not c.rigid for c in ex.classes):
            assert kinds(failures) <= {"length"}, [f.render() for f in failures]


def test_some_copies_nest_cleanly():
    clean = []
    for name in NAMES:
        d = own_drawing(name)
        holes = [poly for label, poly in inner_faces(d) if label == example(name).exterior]
        if holes:
            both, _ = nested_copy(d, max(holes, key=lambda p: p.area))
            if check_drawing(example(name), both) == []:
                clean.append(name)
    assert {"square-hollow", "house-hollow"} <= set(clean), clean


def test_unknown_labels_and_classes_are_named():
    d = own_drawing("square-filled")
    bad = replace(d, edges=(replace(d.edges[0], left="#c0f0fe", label=None),
                            replace(d.edges[1], cls="9", label=None),
                            replace(d.edges[2], label="nope")) + d.edges[3:])
    failures = check_drawing(example("square-filled"), bad)
    text = "\n".join(f.render() for f in failures)
    assert "'#c0f0fe' is not one of the example's" in text and "#c0f0ff" in text
    assert "edge class '9'" in text
    assert "no edge label 'nope'" in text


def test_ring_failure_shows_the_nearest_primitive():
    d = own_drawing("h")
    # Drop one edge: its two ends lose a half-edge each.
    bad = replace(d, edges=d.edges[1:])
    failures = [f for f in check_drawing(example("h"), bad) if f.kind == "ring"]
    assert len(failures) == 2
    f = next(f for f in failures if f.edges)
    assert "nearest is" in f.message and ("missing" in f.message or "unexpected" in f.message)
    assert "∧" in f.expected and "∧" in f.found


def test_loop_and_zero_length_edges_are_degenerate():
    d = own_drawing("square-hollow")
    v0 = d.vertices[0].id
    bad = replace(d, edges=d.edges + (DEdge(v0, v0, "exterior", "exterior", "0"),))
    assert "degenerate" in kinds(check_drawing(example("square-hollow"), bad))


def test_wrong_label_outside_a_lone_component():
    d = own_drawing("square-filled")
    bad = replace(d, edges=tuple(replace(e, left=e.right, right=e.left, label=None)
                                 for e in d.edges))
    failures = check_drawing(example("square-filled"), bad)
    assert "nesting" in kinds(failures)


# --- invariants -----------------------------------------------------------------------------

finite = st.floats(min_value=-1e5, max_value=1e5, allow_nan=False, allow_infinity=False)


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(NAMES), finite, finite)
def test_translation_keeps_a_pass(name, dx, dy):
    d = transformed(own_drawing(name), lambda q: q + np.array([dx, dy]))
    assert check_drawing(example(name), d) == []


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(NAMES), st.floats(min_value=0.0, max_value=1.0))
def test_scaling_within_the_length_limits_keeps_a_pass(name, t):
    d = own_drawing(name)
    ref = as_reference(example(name))
    classes = {c.name: c for c in ref.classes}
    if any(classes[e.cls].rigid or classes[e.cls].fixed or classes[e.cls].tile for e in d.edges):
        return
    lo = max(classes[e.cls].min_length / edge_length(d, e) for e in d.edges)
    hi = min(classes[e.cls].max_length / edge_length(d, e) for e in d.edges)
    assert lo <= 1 <= hi
    s = lo + (hi - lo) * t
    s = min(max(s, lo * (1 + 1e-9)), hi * (1 - 1e-9))
    scaled = transformed(d, lambda q: q * s)
    assert check_drawing(example(name), scaled) == []


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(NAMES), st.randoms(use_true_random=False))
def test_renumbering_and_reversing_edges_keeps_a_pass(name, rnd):
    d = own_drawing(name)
    ids = [v.id for v in d.vertices]
    new = ids[:]
    rnd.shuffle(new)
    ren = {a: 1000 + b * 7 for a, b in zip(ids, new)}
    verts = [DVertex(ren[v.id], v.x, v.y) for v in d.vertices]
    rnd.shuffle(verts)
    edges = []
    for e in d.edges:
        e = replace(e, u=ren[e.u], v=ren[e.v])
        if rnd.random() < 0.5:
            e = replace(e, u=e.v, v=e.u, left=e.right, right=e.left)
        edges.append(e)
    rnd.shuffle(edges)
    assert check_drawing(example(name), Drawing(tuple(verts), tuple(edges))) == []


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(NAMES), st.integers(min_value=0, max_value=3),
       st.integers(min_value=0, max_value=3))
def test_faces_satisfy_euler(name, rows, cols):
    """V − E + F = 1 + C for a grid of copies of an example (C components, F with the outside)."""
    d = own_drawing(name)
    p = np.array([(v.x, v.y) for v in d.vertices])
    span = np.ptp(p, axis=0).max() * 1.5 + 1
    total = d
    for i in range(rows + 1):
        for j in range(cols + 1):
            if i or j:
                total = union(total, transformed(d, lambda q: q + np.array([i * span, j * span])))
    index = {v.id: k for k, v in enumerate(total.vertices)}
    pts = np.array([(v.x, v.y) for v in total.vertices])
    ends = np.array([(index[e.u], index[e.v]) for e in total.edges])
    faces = compute_faces(pts, ends)
    n_comp = int(faces.component.max()) + 1
    assert len(pts) - len(ends) + len(faces.faces) == 1 + n_comp
    # The signed areas of one component's cycles cancel.
    assert abs(faces.area.sum()) <= 1e-6 * max(1.0, np.abs(faces.area).sum())


# --- the command ----------------------------------------------------------------------------

def ggrun(capsys, *args):
    from report.ggrun import main
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    return code, out.out, out.err


def test_ggrun_check(tmp_path, capsys):
    d = own_drawing("house-filled")
    good = tmp_path / "good.json"
    d.save(good)
    svg = CORPUS / "house-filled.svg"
    code, out, _ = ggrun(capsys, "check", svg, good)
    assert code == 0 and out == f"ok: {len(d.vertices)} vertices, {len(d.edges)} edges\n"

    bad = tmp_path / "bad.json"
    p = xy(d)
    e = d.edges[0]
    moved(d, e.v, p[e.v] + (p[e.v] - p[e.u]) * 5).save(bad)
    code, out, _ = ggrun(capsys, "check", svg, bad)
    assert code == 1
    assert "length:" in out and "failed:" in out and "at (" in out

    for broken in ("{not json", '{"format": "gg-drawing/1"}', '{"format": "other"}',
                   '{"format": "gg-drawing/1", "vertices": [{"id": 0, "x": 0, "y": 0}], '
                   '"edges": [{"u": 0, "v": 5, "left": "a", "right": "b"}]}'):
        (tmp_path / "broken.json").write_text(broken)
        code, _, err = ggrun(capsys, "check", svg, tmp_path / "broken.json")
        assert code == 2 and "Traceback" not in err and "error" in err
    code, _, err = ggrun(capsys, "check", tmp_path / "missing.svg", good)
    assert code == 2 and "no such file" in err
    code, _, err = ggrun(capsys, "check", tmp_path / "x.txt", good)
    assert code == 2 and "don't know how to read" in err
    code, _, err = ggrun(capsys, "check", svg, good, "--tolerance", "500")
    assert code == 2 and "Traceback" not in err


def test_ggrun_check_limits_the_listing(tmp_path, capsys):
    d = transformed(own_drawing("star-crossing"), lambda q: q * 50)
    # Four copies far apart, scaled beyond every class's maximum: a length failure per edge.
    big = d
    for k in range(1, 4):
        big = union(big, transformed(d, lambda q: q + np.array([k * 1e6, 0.0])))
    path = tmp_path / "big.json"
    big.save(path)
    svg = CORPUS / "star-crossing.svg"
    code, few, _ = ggrun(capsys, "check", svg, path)
    _, every, _ = ggrun(capsys, "check", svg, path, "--all")
    n = len(check_drawing(example("star-crossing"), parse_drawing(path.read_text())))
    assert code == 1 and n == every.count("length:") == 4 * len(d.edges) > 50
    assert few.count("length:") == 50 and f"{n - 50} not shown" in few
    assert ggrun(capsys, "check", svg, path)[1] == few        # deterministic


def test_half_edges_out_of_their_primitives_order():
    """Two labels 5° apart with different faces: within the tolerance each edge fits its own
    label, yet around the vertex they come in the other order, which no primitive allows."""
    from grammar_lang.vocabulary import EdgeLabel, Primitive, Vocabulary
    from grammar_lang.source import EdgeClass
    from runtime.verifier import Reference
    labels = (EdgeLabel("a", "X", "Y", 0.0, "0"), EdgeLabel("b", "Y", "Z", 5.0, "0"),
              EdgeLabel("c", "Z", "X", 90.0, "0"))
    ring = (0, 2, 4)                                   # a, b, c counter-clockwise
    ref = Reference("swap", Vocabulary("X", ("X", "Y", "Z"), (EdgeClass("0", 0.1, 100.0),),
                                       labels, (Primitive("p", ring),), 1.0), 10.0)

    def star(angles):
        vs = (DVertex(0, 0.0, 0.0),) + tuple(
            DVertex(k + 1, math.cos(math.radians(a)), math.sin(math.radians(a)))
            for k, a in enumerate(angles))
        es = tuple(DEdge(0, k + 1, lab.left, lab.right, "0") for k, lab in enumerate(labels))
        return Drawing(vs, es)

    def centre(failures):      # the leaves are no primitives here; only the centre matters
        return [f for f in failures if f.kind == "ring" and f.vertices == (0,)]

    assert centre(check_drawing(ref, star([1.0, 4.0, 90.0]))) == []
    swapped = centre(check_drawing(ref, star([6.0, 1.0, 90.0])))
    assert len(swapped) == 1 and "not in the order of primitive p" in swapped[0].message


# --- docs/drawing-format.md -----------------------------------------------------------------



def doc_blocks():
    import re
    from conftest import ROOT as repo
    text = (repo / "docs" / "drawing-format.md").read_text()
    return repo, re.findall(r"```(\w+)\n(.*?)```", text, re.S)


def test_doc_example_is_the_house_drawn_as_itself():
    repo, blocks = doc_blocks()
    [doc] = [b for lang, b in blocks if lang == "json"]
    d = parse_drawing(doc)
    house = load_example(repo / "examples" / "house.gg")
    assert check_drawing(house, d) == []
    own = drawing_from_example(house)
    assert (d.vertices, d.edges) == (own.vertices, own.edges)
    assert d.meta == {"example": "House"}


def test_doc_sessions_print_what_they_show(tmp_path, capsys, monkeypatch):
    repo, blocks = doc_blocks()
    [doc] = [b for lang, b in blocks if lang == "json"]
    d = parse_drawing(doc)
    d.save(tmp_path / "house.json")
    wide = replace(d, vertices=tuple(DVertex(v.id, 400.0, v.y) if v.id in (7, 8) else v
                                     for v in d.vertices))
    wide.save(tmp_path / "house-wide.json")
    monkeypatch.chdir(repo)
    ran = 0
    for lang, block in blocks:
        command, *expected = block.splitlines()
        if lang != "console" or not command.startswith("$ ggrun check examples/"):
            continue
        args = command.split()[2:]
        args[-1] = str(tmp_path / args[-1])
        code, out, _ = ggrun(capsys, *args)
        assert out.splitlines() == expected
        assert code == (0 if expected[0].startswith("ok:") else 1)
        ran += 1
    assert ran == 2
    # The checking example (the networkx one is run by test_networkx_view).
    [snippet] = [b for lang, b in blocks if lang == "python" and "drawing_graph" not in b]
    (tmp_path / "examples").symlink_to(repo / "examples")
    monkeypatch.chdir(tmp_path)
    exec(compile(snippet, "drawing-format.md", "exec"), {})
    assert capsys.readouterr().out == ""       # the house passes: nothing to print


@pytest.mark.parametrize("name", ["house-filled", "h-complex", "star-crossing"])
def test_check_against_a_grammar_file(tmp_path, capsys, name):
    """A .ggr records the example's types in its header: checking against it or against the
    example gives the same verdicts."""
    from grammar_lang.ggr_emit import emit_ggr
    from grammar_lang.rules import Grammar
    ex = example(name)
    header = Header(source=str(ex.path), vocabulary=ex.vocabulary, options=ex.options,
                    decorations=ex.decorations)
    ggr = tmp_path / f"{name}.ggr"
    ggr.write_text(emit_ggr(Grammar(header, ())))
    good, bad = tmp_path / "good.json", tmp_path / "bad.json"
    d = own_drawing(name)
    d.save(good)
    transformed(d, lambda q: q * 3).save(bad)
    for path, code in ((good, 0), (bad, 1)):
        got = ggrun(capsys, "check", ggr, path)
        assert got[0] == code
        assert got[1] == ggrun(capsys, "check", CORPUS / f"{name}.svg", path)[1]


# --- robustness ------------------------------------------------------------------------------

coords = st.one_of(st.integers(-3, 3).map(float),
                   st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False),
                   st.sampled_from([float("nan"), float("inf"), 1e300, -0.0]))


@st.composite
def messy_drawings(draw):
    name = draw(st.sampled_from(NAMES))
    ex = example(name)
    n = draw(st.integers(0, 8))
    verts = tuple(DVertex(i * 3, draw(coords), draw(coords)) for i in range(n))
    faces = list(ex.face_labels) + ["junk"]
    classes = [c.name for c in ex.classes] + ["9"]
    labels = [None, "nope"] + [l.name for l in ex.labels]
    edges = []
    if n:
        for _ in range(draw(st.integers(0, 12))):
            edges.append(DEdge(draw(st.integers(0, n - 1)) * 3, draw(st.integers(0, n - 1)) * 3,
                               draw(st.sampled_from(faces)), draw(st.sampled_from(faces)),
                               draw(st.sampled_from(classes)), draw(st.sampled_from(labels))))
    return name, Drawing(verts, tuple(edges))


@settings(max_examples=300, deadline=None)
@given(messy_drawings())
def test_any_drawing_gets_an_answer_not_a_crash(case):
    from runtime.output.svg_out import render_svg
    from runtime.verifier import KINDS
    name, d = case
    failures = check_drawing(example(name), d)
    for f in failures:
        assert f.kind in KINDS
        assert f.render()
    if all(math.isfinite(c) for v in d.vertices for c in (v.x, v.y)):
        parse(render_svg(d, example(name)))


def parse(text):
    import defusedxml.ElementTree as ET
    return ET.fromstring(text)


LENGTHS = """\
face field
class post { fixed: 30 }
class plank { tile: 20 }
polygon field rect (0, 0) (80, 40)
polyline (0, 40) (0, 70) class post
polyline (0, 0) (80, 0) class plank
"""


def test_fixed_and_tile_lengths(tmp_path):
    src = tmp_path / "fence.gg"
    src.write_text(LENGTHS)
    ex = load_example(src)
    d = parse_drawing(drawing_from_example(ex).to_json())
    assert check_drawing(ex, d) == []
    p = xy(d)
    by_cls = {e.cls: (k, e) for k, e in enumerate(d.edges)}

    def stretched(cls, factor):
        """Edge k of the class, its top (post) or right (plank) end moved outwards."""
        k, e = by_cls[cls]
        axis = 1 if cls == "post" else 0
        base, tip = sorted((e.u, e.v), key=lambda v: p[v][axis])
        return k, moved(d, tip, p[base] + (p[tip] - p[base]) * factor)

    k, bad = stretched("post", 1.5)              # 45, not the fixed 30
    hit = [f for f in check_drawing(ex, bad) if f.kind == "length" and f.edges == (k,)]
    assert hit and "fixed length" in hit[0].message and hit[0].expected == "exactly 30"
    # The plank is a whole multiple of 20 (80); 90 is not, 100 is.
    k, bad = stretched("plank", 90 / 80)
    hit = [f for f in check_drawing(ex, bad) if f.kind == "length" and f.edges == (k,)]
    assert hit and "multiple" in hit[0].message
    k, good = stretched("plank", 100 / 80)
    assert not [f for f in check_drawing(ex, good) if f.kind == "length" and f.edges == (k,)]
