"""From a drawn example to its types: edge labels, primitives and boundary strings (§3.3, §4.1).

Hand-drawn directions are off by a few degrees, so directions of edges with the same faces and
class are clustered within the angle tolerance and each cluster becomes one label with one exact
angle (snapped to a multiple of `snap_angle` when that is within the tolerance). Undirected
edges need a canonical orientation before clustering: with two different faces we orient so the
lesser face is on the left, which gives a full 360° circle with no cut to fall across; with the
same face on both sides the direction is taken modulo 180°, on a circle of its own.
"""

from __future__ import annotations

import math
from collections import defaultdict
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from . import boundary as bd
from .diagnostics import Diagnostic, Span, UserError, error
from .example import Example
from .vocabulary import EdgeLabel, Primitive, Vocabulary
from .source import DEFAULT_CLASS, EdgeClass, ExampleGraph, ExampleSource


@dataclass(frozen=True)
class _Obs:
    """One half-edge seen at a vertex: pointing `angle` (degrees) away from it."""

    vertex: int
    angle: float
    left: str
    right: str
    cls: str
    edge: int            # index of the undirected edge (or primitive half-edge) it belongs to
    start: bool          # whether the vertex is where the edge was recorded as starting
    span: Span | None


def label_example(source: ExampleSource, graph: ExampleGraph | None) -> Example:
    faces = _face_order(source, graph)
    classes = _classes(source, graph)
    obs, edge_keys, n_vertices, lengths = _observations(source, graph)
    unit = source.options.unit or (float(np.median(lengths)) if lengths else 1.0)
    seen: dict[str, list[float]] = defaultdict(list)
    for (_, _, _, cls, _), length in zip(edge_keys, lengths):
        seen[cls].append(length)
    resolved = tuple(classes[c].resolved(unit, (min(seen[c]), max(seen[c])) if seen[c] else None)
                     for c in sorted(classes))
    rigid = {c.name for c in resolved if c.rigid}

    labels, edge_label, notes = _cluster(source, obs, edge_keys, faces, rigid, lengths)
    notes += _widened(classes, resolved)
    prims, vertex_prim = _primitives(source, obs, edge_label, labels, n_vertices)
    vocabulary = Vocabulary(source.exterior, tuple(faces), resolved, tuple(labels),
                            tuple(prims), unit)
    return Example(
        name=source.name, path=source.path, vocabulary=vocabulary, options=source.options,
        decorations=tuple(source.decorations), graph=graph,
        vertex_primitive=tuple(vertex_prim),
        edge_label=tuple(edge_label[i] for i in range(len(edge_keys))) if graph else (),
        notes=tuple(notes),
    )


def _widened(given: dict[str, EdgeClass], resolved) -> list[Diagnostic]:
    """A note for each limit the user gave that the example's own edges break."""
    out = []
    for c in resolved:
        g = given[c.name]
        for what, mine, theirs in (("min", c.min_length, g.min_length),
                                   ("max", c.max_length, g.max_length)):
            if theirs is not None and abs(mine - theirs) > 1e-9 * max(1.0, abs(theirs)):
                out.append(Diagnostic(
                    f"class {c.name}: {what} {theirs:g}, but the example has an edge "
                    f"{mine:g} long; the class admits it, so that the example is a drawing too",
                    g.span, f"set {what}: {mine:g} (or redraw that edge) to silence this",
                    severity="note"))
    return out


def _face_order(source: ExampleSource, graph: ExampleGraph | None) -> list[str]:
    """The exterior first, then declared labels, then labels in order of appearance."""
    order = [source.exterior]
    seen = {source.exterior}

    def add(name: str) -> None:
        if name not in seen:
            seen.add(name)
            order.append(name)

    for name in source.face_labels:
        add(name)
    if graph is not None:
        for _, _, l, r, _ in graph.edges:
            add(l)
            add(r)
    for p in source.primitives:
        for h in p.half_edges:
            add(h.left)
            add(h.right)
    return order


def _classes(source: ExampleSource, graph: ExampleGraph | None) -> dict[str, EdgeClass]:
    classes = dict(source.classes)
    used = {DEFAULT_CLASS}
    if graph is not None:
        used |= {e[4] for e in graph.edges}
    used |= {h.cls for p in source.primitives for h in p.half_edges}
    for name in sorted(used):
        classes.setdefault(name, EdgeClass(name))
    return classes


def _observations(source: ExampleSource, graph: ExampleGraph | None):
    obs: list[_Obs] = []
    edge_keys: list[tuple[float, str, str, str, Span | None]] = []
    lengths: list[float] = []
    if graph is not None:
        pts = graph.vertices
        for i, (u, v, l, r, c) in enumerate(graph.edges):
            span = graph.spans[i] if i < len(graph.spans) else None
            dx, dy = pts[v][0] - pts[u][0], pts[v][1] - pts[u][1]
            length = math.hypot(dx, dy)
            if length == 0:
                raise error("zero-length edge", span, "remove the edge or move one of its ends")
            lengths.append(length)
            a = math.degrees(math.atan2(dy, dx))
            edge_keys.append((a, l, r, c, span))
            obs.append(_Obs(u, a, l, r, c, i, True, span))
            obs.append(_Obs(v, _wrap(a + 180), r, l, c, i, False, span))
        return obs, edge_keys, len(pts), lengths
    # Primitives given directly: every half-edge is its own (half of an) edge.
    k = 0
    for vi, p in enumerate(source.primitives):
        for h in p.half_edges:
            a = _wrap(h.angle)
            edge_keys.append((a, h.left, h.right, h.cls, p.span))
            obs.append(_Obs(vi, a, h.left, h.right, h.cls, k, True, p.span))
            k += 1
    return obs, edge_keys, len(source.primitives), lengths


def _wrap(a: float) -> float:
    """An angle in degrees, wrapped into [-180, 180)."""
    return (a + 180.0) % 360.0 - 180.0


def _orient(angle: float, left: str, right: str, rank: dict[str, int]):
    """Canonical orientation of an undirected edge: (key, angle on its circle, period)."""
    if left == right:
        return (left, left), angle % 180.0, 180.0
    if rank[left] > rank[right]:
        return (right, left), (angle + 180.0) % 360.0, 360.0
    return (left, right), angle % 360.0, 360.0


def _leader_clusters(angles: list[float], period: float, tol: float) -> list[list[int]]:
    """Leader clustering in drawing order: an edge joins the first label whose first edge is
    within `tol` of it, else it starts a new label. This is the original tool's typing rule, so
    label counts agree with it; its clusters are at most 2·tol wide, unlike single linkage,
    which can chain a whole fan of directions into one label."""
    leaders: list[float] = []
    clusters: list[list[int]] = []
    for i, a in enumerate(angles):
        for k, lead in enumerate(leaders):
            if _circ_dist(a, lead, period) < tol:
                clusters[k].append(i)
                break
        else:
            leaders.append(a)
            clusters.append([i])
    return clusters


def _drawing_order(span: Span | None, index: int) -> tuple[int, int, int]:
    if span is None:
        return (0, 0, index)
    return (span.line, span.column, index)


def _circular_mean(values: list[float], period: float) -> float:
    k = 2 * math.pi / period
    s = sum(math.sin(v * k) for v in values)
    c = sum(math.cos(v * k) for v in values)
    return (math.atan2(s, c) / k) % period


def _circ_dist(a: float, b: float, period: float) -> float:
    d = abs(a - b) % period
    return min(d, period - d)


class _Proto(NamedTuple):
    """An edge label before it is named: its direction, faces, class, rigid length, the
    example's edges it types, whether it is a rigid edge's own label, its typical (median)
    and shortest lengths."""

    angle: float
    left: str
    right: str
    cls: str
    length: float | None
    edges: list[int]
    rigid: bool
    typical: float | None
    shortest: float | None


def _cluster(source, obs, edge_keys, faces, rigid, lengths):
    """Edge labels and, per edge, (label index, whether u→v walks along `a`)."""
    rank = {f: i for i, f in enumerate(faces)}
    groups, periods = _groups(edge_keys, rank, rigid)
    raw, notes = _directions(groups, periods, source.options, edge_keys)
    protos = [_proto(gk, ang, edges, period, rigid, lengths) for gk, ang, edges, period in raw]
    # Readers expect labels in a stable, meaningful order: by class, faces, then direction.
    protos.sort(key=lambda p: (p.cls, rank[p.left], rank[p.right], p.angle, p.edges[0]))
    labels: list[EdgeLabel] = []
    edge_label: dict[int, tuple[int, bool]] = {}
    for idx, (p, name) in enumerate(zip(protos, _names(protos, rank))):
        labels.append(EdgeLabel(name, p.left, p.right, p.angle, p.cls, p.length, p.typical,
                                p.shortest))
        for e in p.edges:
            a, l, r = edge_keys[e][0], edge_keys[e][1], edge_keys[e][2]
            # Whether u→v walks along `a`: told by the faces when they differ, else by direction.
            forward = (l == p.left) if l != r else _circ_dist(a, p.angle, 360.0) < 90.0
            edge_label[e] = (idx, forward)
    return labels, edge_label, notes


def _groups(edge_keys, rank, rigid):
    """The example's edges grouped by class and faces, in drawing order, with their angles."""
    groups: dict[tuple, list[tuple[int, float]]] = defaultdict(list)
    periods: dict[tuple, float] = {}
    for i in sorted(range(len(edge_keys)), key=lambda i: _drawing_order(edge_keys[i][4], i)):
        a, l, r, c, _ = edge_keys[i]
        key, ang, period = _orient(a, l, r, rank)
        # A rigid edge keeps its exact vector, so it is a label of its own.
        gk = (c, key) if c not in rigid else (c, key, "rigid", i)
        groups[gk].append((i, ang))
        periods[gk] = period
    return groups, periods


def _directions(groups, periods, opts, edge_keys):
    """Each group's edges clustered by direction: (group key, angle, edges, period) per label,
    and a note for each label whose edges' directions were evened out."""
    raw: list[tuple[tuple, float, list[int], float]] = []
    notes: list[Diagnostic] = []
    for gk in sorted(groups, key=str):
        members = groups[gk]
        period = periods[gk]
        angs = [a for _, a in members]
        clusters = _leader_clusters(angs, period, opts.angle_tolerance)
        means = [_circular_mean([angs[j] for j in cl], period) for cl in clusters]
        # A rigid edge keeps its exact vector: snapped, the cycles of a rigid part (a
        # blossom, a module) would no longer close, and no placement could exist.
        snap = 0.0 if len(gk) > 2 else opts.snap_angle
        snapped = [_snap(m, snap, opts.angle_tolerance, period) for m in means]
        # Two clusters may not snap onto one angle: keep their means instead.
        if len(set(snapped)) != len(snapped):
            snapped = [round(m, 6) % period for m in means]
        for cl, ang in zip(clusters, snapped):
            edges = [members[j][0] for j in cl]
            raw.append((gk, ang, edges, period))
            spread = [angs[j] for j in cl]
            if max(_circ_dist(s, ang, period) for s in spread) > 1e-6:
                lo = min(spread, key=lambda s: (s - ang + period / 2) % period)
                hi = max(spread, key=lambda s: (s - ang + period / 2) % period)
                notes.append(Diagnostic(
                    f"{len(cl)} edge(s) with directions {lo:.1f}°..{hi:.1f}° "
                    f"({gk[1][0]}|{gk[1][1]}, class {gk[0]}) typed as one label at {ang:g}°",
                    edge_keys[edges[0]][4], severity="note"))
    return raw, notes


def _proto(gk, ang, edges, period, rigid, lengths) -> _Proto:
    cls, (fl, fr) = gk[0], gk[1]
    if period == 180.0 or ang < 180.0:
        a_angle, left, right = ang % 180.0, fl, fr
    else:
        a_angle, left, right = ang - 180.0, fr, fl
    a_angle = round(a_angle, 9) % 180.0
    length = lengths[edges[0]] if (cls in rigid and lengths) else None
    typical = _round_sig(float(np.median([lengths[e] for e in edges]))) if lengths else None
    shortest = _round_sig(min(lengths[e] for e in edges)) if lengths else None
    return _Proto(a_angle, left, right, cls, length, edges, len(gk) > 2, typical, shortest)


def _round_sig(x: float, digits: int = 6) -> float:
    """`x` to `digits` significant digits, so that the .ggr shows a readable length."""
    return float(f"{x:.{digits}g}")


def _snap(mean: float, step: float, tol: float, period: float) -> float:
    if step <= 0:
        return round(mean, 6) % period
    target = round(mean / step) * step
    if _circ_dist(mean, target, period) <= tol / 2:
        return target % period
    return round(mean, 6) % period


def _base_name(angle: float) -> str:
    if abs(angle) < 1e-9:
        return "x"
    if abs(angle - 90.0) < 1e-9:
        return "y"
    text = f"{angle:.2f}".rstrip("0").rstrip(".").replace(".", "_")
    return f"d{text}"


def _names(protos, rank) -> list[str]:
    """Readable, unique label names: x, y, d45; with face indices x01 when an angle is shared."""
    base = [_base_name(p.angle) for p in protos]
    count: dict[str, int] = defaultdict(int)
    for b in base:
        count[b] += 1
    names = []
    for p, b in zip(protos, base):
        name = b
        if count[b] > 1:
            li, ri = rank[p.left], rank[p.right]
            name += f"{li}{ri}" if li < 10 and ri < 10 else f"_{li}_{ri}"
        names.append(name)
    # Still clashing (other classes, rigid edges): append the class, then a counter.
    seen: dict[str, int] = defaultdict(int)
    for n in names:
        seen[n] += 1
    out, used = [], set()
    for p, n in zip(protos, names):
        if seen[n] > 1:
            n = f"{n}_c{p.cls}" if p.cls.isidentifier() or p.cls.isdigit() else f"{n}_c"
        k, cand = 1, n
        while cand in used:
            k += 1
            cand = f"{n}_{k}"
        used.add(cand)
        out.append(cand)
    return out


def _primitives(source, obs, edge_label, labels, n_vertices):
    rings: dict[int, list[tuple[float, float, int, _Obs]]] = defaultdict(list)
    for o in obs:
        idx, forward = edge_label[o.edge]
        lab = labels[idx]
        # The half-edge at the edge's start points along the edge: it is `a` when forward.
        bar = (not forward) if o.start else forward
        tok = bd.half(idx, bar)
        rings[o.vertex].append((lab.direction(bar), o.angle, tok, o))
    errors: list[Diagnostic] = []
    ring_ids: dict[bd.Tokens, int] = {}
    vertex_ring: list[bd.Tokens] = []
    for v in range(n_vertices):
        items = sorted(rings.get(v, []), key=lambda t: t[0])
        toks = tuple(t[2] for t in items)
        if len(set(toks)) != len(toks):
            errors.append(Diagnostic(
                "two edges leave one vertex in the same typed direction (they would overlap)",
                items[0][3].span, "the edges are closer than the angle tolerance; draw them "
                "further apart or lower `angle tolerance`"))
        elif len(items) > 2 and not _same_cyclic_order([t[1] for t in items]):
            errors.append(Diagnostic(
                "typing the directions changes the order of the edges around a vertex",
                items[0][3].span, "the edges are too close in angle; lower `angle tolerance` "
                "or `snap angle`"))
        vertex_ring.append(toks)
        ring_ids.setdefault(toks, 0)
    if errors:
        raise UserError(*errors)
    order = sorted(ring_ids, key=lambda r: (len(r), r))
    index = {r: i for i, r in enumerate(order)}
    counts: dict[bd.Tokens, int] = defaultdict(int)
    for r in vertex_ring:
        counts[r] += 1
    names = [p.name for p in source.primitives] if not source.paint else []
    prims = [Primitive(_prim_name(i, r, names, vertex_ring), r, counts[r]) for i, r in enumerate(order)]
    return prims, [index[r] for r in vertex_ring]


def _prim_name(i: int, ring, names, vertex_ring) -> str:
    if names:
        for given, r in zip(names, vertex_ring):
            if r == ring and given:
                return given
    return f"p{i}"


def _same_cyclic_order(actual: list[float]) -> bool:
    """Whether actual angles, listed in typed order, are also increasing cyclically."""
    n = len(actual)
    steps = sum(((actual[(i + 1) % n] - actual[i]) % 360.0) for i in range(n))
    return abs(steps - 360.0) < 1e-6
