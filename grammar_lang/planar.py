"""`ExampleSource` geometry → `ExampleGraph`: the planar straight-line graph with face labels.

Steps: collect the segments of every painted shape; merge points closer than the merge
distance; node (split at crossings and T-junctions, drop zero-length and duplicate pieces);
compute the faces; label each face by painter's order (the last region covering it, else
the labels explicit edges give it, else the exterior); keep every stroke and explicit edge and
every region outline piece not hidden under a later fill.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from scipy.sparse import csr_matrix

from . import limits
from .diagnostics import Diagnostic, Span, UserError, error
from .planar_faces import compute_faces, winding
from .planar_noding import NodingError, TooManyCrossings, cluster, node
from .source import (DEFAULT_CLASS, MAX_COORDINATE, ExampleGraph, ExampleSource, ExplicitEdge,
                     Region, Stroke)

MERGE_FRACTION = 0.005    # default merge distance, as a fraction of the bounding-box diagonal
# Coordinates are written rounded to 9 decimals, so points nearer than this would become one
# point on output while staying two vertices: the merge distance never goes below it.
RESOLUTION = 1e-8
MAX_DIAGNOSTICS = 20
# How many times its shortest edge (or its merge distance, if longer) a drawing may span.
# Noding tests "exactly on a line" to 1e-9 of the drawing's span; past this ratio that test is
# coarser than a hundredth of the drawing's smallest feature, and a drawing that size (a point
# at 1e11 beside a village of 1,600 px) split and re-merged its pieces round after round
# until it ran out of memory. A drawing opened in the REPL is held to the same bound: the
# engine files each edge in every grid cell its box touches, and a point at 1e12 beside a
# house filed one edge in 10^10 cells (24 GB before the kernel stopped it).
MAX_SPAN = 1e7


def span_and_least(points: np.ndarray, segments: np.ndarray, d: float = 0.0):
    """How far the points spread (the larger side of their box) and the shortest segment (or
    `d`, if longer); None when no segment has a length. A drawing is too wide to handle when
    span > MAX_SPAN · least."""
    lengths = np.hypot(*(points[segments[:, 1]] - points[segments[:, 0]]).T)
    lengths = lengths[lengths > 0]
    if not len(lengths):
        return None
    return float((points.max(axis=0) - points.min(axis=0)).max()), max(d, float(lengths.min()))


@dataclass(frozen=True)
class _Source:
    """One painted item, as the builder needs it."""

    order: int              # position in the paint list
    kind: str               # 'region', 'stroke' or 'explicit'
    paint: object


def merge_distance(source: ExampleSource, points: np.ndarray) -> float:
    if source.options.merge_distance is not None:
        return max(RESOLUTION, float(source.options.merge_distance))
    extent = points.max(axis=0) - points.min(axis=0)
    return max(RESOLUTION, MERGE_FRACTION * float(np.hypot(*extent)))


def build_planar_graph(source: ExampleSource) -> ExampleGraph:
    _check_points(source)
    builder = _Builder(source)
    return builder.build()


def _check_points(source: ExampleSource) -> None:
    """The input point limit, checked before noding allocates per-segment arrays; the error
    points at the shape that goes over it."""
    limit, total = limits.POINTS.value(), 0
    for item in source.paint:
        if isinstance(item, Region):
            total += sum(len(r) for r in item.rings)
        elif isinstance(item, Stroke):
            total += len(item.points)
        else:
            total += 2
        if total > limit:
            span = item.span or Span(source.path)
            raise limits.POINTS.exceeded(total, span, source.text if span.file == source.path
                                         else None, what="points so far")


class _Builder:
    def __init__(self, source: ExampleSource):
        self.source = source
        self.diagnostics: list[Diagnostic] = []

    def report(self, message: str, span: Span | None, hint: str | None = None) -> None:
        if len(self.diagnostics) < MAX_DIAGNOSTICS:
            self.diagnostics.append(Diagnostic(message, span or Span(self.source.path), hint,
                                               source=self._text(span)))

    def _text(self, span: Span | None) -> str | None:
        # Spans may point into an SVG a .gg file imports; only excerpt our own text.
        if span is not None and span.file == self.source.path:
            return self.source.text
        return None

    def check(self) -> None:
        if self.diagnostics:
            raise UserError(*self.diagnostics)

    # --- collecting -------------------------------------------------------------------------

    def collect(self):
        points: list[tuple[float, float]] = []
        segments: list[tuple[int, int, int]] = []
        self.items: list[_Source] = []
        self.owner: list[int] = []          # per point, the item it belongs to
        for order, item in enumerate(self.source.paint):
            if isinstance(item, Region):
                kind, chains = "region", [(ring, True) for ring in item.rings]
            elif isinstance(item, Stroke):
                kind, chains = "stroke", [(item.points, item.closed)]
            elif isinstance(item, ExplicitEdge):
                kind, chains = "explicit", [((item.p, item.q), False)]
            else:
                raise TypeError(f"unknown paint item {item!r}")
            if not all(abs(c) <= MAX_COORDINATE for chain, _ in chains for pt in chain for c in pt):
                self.report(f"coordinates beyond ±{MAX_COORDINATE:g}", item.span,
                            "scale the drawing down")
                continue
            if kind == "region" and all(abs(_ring_area(ring)) <= 0.0 for ring in item.rings):
                self.report(f"the region '{item.label}' has zero area", item.span,
                            "a filled shape needs at least three points not on one line")
            sid = len(self.items)
            self.items.append(_Source(order, kind, item))
            for chain, closed in chains:
                base = len(points)
                points.extend(chain)
                n = len(chain)
                self.owner.extend([sid] * n)
                for k in range(n if closed and n > 2 else n - 1):
                    segments.append((base + k, base + (k + 1) % n, sid))
        self.check()
        if not segments:
            raise error("the drawing has no edges", Span(self.source.path),
                        "draw at least one line or filled shape", source=None)
        pts = np.asarray(points, dtype=float)
        return pts, np.asarray(segments, dtype=np.int64)

    # --- building ---------------------------------------------------------------------------

    def build(self) -> ExampleGraph:
        points, segments = self.collect()
        d = merge_distance(self.source, points)
        self.check_span(points, segments, d)
        centres, index = cluster(points, d)
        ends = index[segments[:, :2]]
        self.check_collapse(ends, segments[:, 2], d)
        try:
            pieces = node(centres, ends, segments[:, 2], d, limits.POINTS.value())
        except TooManyCrossings as exc:
            raise limits.POINTS.exceeded(len(centres) + exc.count, Span(self.source.path),
                                         what="points with the crossings found so far") from None
        except NodingError:
            raise error("the drawing has near-coincident crossings that cannot be resolved at "
                        f"merge distance {d:g}", Span(self.source.path),
                        "set a different merge distance, or redraw the crowded spot") from None
        if len(pieces.ends) == 0:
            raise error("every edge of the drawing collapses under merging",
                        Span(self.source.path), f"points closer than {d:g} are merged")
        faces = compute_faces(pieces.vertices, pieces.ends)
        samples = _face_samples(pieces.vertices, pieces.ends, faces)
        regions = [s for s in self.items if s.kind == "region"]
        cover = self.coverage(regions, pieces, samples, faces.count)
        self.check_regions(regions, cover, d)
        labels = self.face_labels(regions, cover, pieces, faces)
        self.check()
        return self.assemble(pieces, faces, labels, regions, cover)

    def check_span(self, points: np.ndarray, segments: np.ndarray, d: float) -> None:
        """Refuse a drawing that spans more than MAX_SPAN times its shortest edge (or merge
        distance); the error points at the item holding the point furthest from the middle."""
        found = span_and_least(points, segments, d)
        if found is None or found[0] <= MAX_SPAN * found[1]:
            return
        span, least = found
        far = int(np.abs(points - np.median(points, axis=0)).max(axis=1).argmax())
        self.report(f"the drawing spans {span:g}, more than {MAX_SPAN:g} times its shortest "
                    f"edge ({least:g}): at that scale its points cannot be placed finely "
                    "enough", self.items[self.owner[far]].paint.span,
                    "move this shape nearer the others, or draw the example at one scale")
        self.check()

    def check_collapse(self, ends: np.ndarray, sids: np.ndarray, d: float) -> None:
        alive = np.zeros(len(self.items), dtype=bool)
        alive[sids[ends[:, 0] != ends[:, 1]]] = True
        for sid in np.flatnonzero(~alive).tolist():
            item = self.items[sid].paint
            what = {"region": "filled shape", "stroke": "line",
                    "explicit": "edge"}[self.items[sid].kind]
            self.report(f"this {what} has zero length after merging points closer than {d:g}",
                        item.span, "draw it larger, or set a smaller merge distance")
        self.check()

    def coverage(self, regions: list[_Source], pieces, samples: np.ndarray,
                 count: int) -> csr_matrix:
        """cover[f, r] is 1 when region r paints face f (sparse: a face lies in few regions).

        Faces are atomic (every ring is an edge), so the sample point of a face decides. The
        rings are taken as noded and merged, as the pieces that came from them, so that the
        test agrees with the faces exactly however far merging moved the drawing.
        """
        count_regions = len(regions)
        region_index = {s.order: r for r, s in enumerate(regions)}
        sid_region = np.array([region_index.get(item.order, -1) for item in self.items])
        piece, sid, forward = (np.array(x, dtype=np.int64) for x in zip(*(
            (e, s, f) for e, srcs in enumerate(pieces.sources) for s, f in srcs)))
        own = sid_region[sid] >= 0
        piece, region, forward = piece[own], sid_region[sid[own]], forward[own].astype(bool)
        order = np.argsort(region, kind="stable")
        piece, region, forward = piece[order], region[order], forward[order]
        ends = pieces.ends[piece]
        start = np.where(forward, ends[:, 0], ends[:, 1])
        stop = np.where(forward, ends[:, 1], ends[:, 0])
        a, b = pieces.vertices[start], pieces.vertices[stop]
        bounds = np.searchsorted(region, np.arange(count_regions + 1))
        face_hits: list[np.ndarray] = []
        region_hits: list[np.ndarray] = []
        if count_regions and len(region):
            lo = np.full((count_regions, 2), np.nan)
            hi = np.full((count_regions, 2), np.nan)
            present = bounds[1:] > bounds[:-1]
            lo[present] = np.minimum.reduceat(np.minimum(a, b), bounds[:-1][present])
            hi[present] = np.maximum.reduceat(np.maximum(a, b), bounds[:-1][present])
            boxes = shapely.box(lo[:, 0], lo[:, 1], hi[:, 0], hi[:, 1])
            # Which face samples fall in which region's bounding box, in one spatial query.
            box_of, sample = shapely.STRtree(shapely.points(samples[1:])).query(
                boxes, predicate="intersects")
            by_box = np.argsort(box_of, kind="stable")
            box_of, sample = box_of[by_box], sample[by_box] + 1
            hit_bounds = np.searchsorted(box_of, np.arange(count_regions + 1))
            for r, item in enumerate(regions):
                hit = sample[hit_bounds[r]:hit_bounds[r + 1]]
                if len(hit) == 0:
                    continue
                seg = slice(bounds[r], bounds[r + 1])
                w = winding(samples[hit], a[seg], b[seg])
                inside = hit[(w % 2 != 0) if item.paint.evenodd else (w != 0)]
                face_hits.append(inside)
                region_hits.append(np.full(len(inside), r))
        f = np.concatenate(face_hits) if face_hits else np.zeros(0, dtype=np.int64)
        r = np.concatenate(region_hits) if region_hits else np.zeros(0, dtype=np.int64)
        return csr_matrix((np.ones(len(f), dtype=np.int8), (f, r)),
                          shape=(count, count_regions))

    def check_regions(self, regions: list[_Source], cover: csr_matrix, d: float) -> None:
        painted = np.bincount(cover.indices, minlength=len(regions))
        for r in np.flatnonzero(painted == 0).tolist():
            item = regions[r].paint
            self.report(f"the region '{item.label}' collapses: nothing of it is left after "
                        f"merging points closer than {d:g}", item.span,
                        "draw it larger, or set a smaller merge distance")

    def face_labels(self, regions, cover: csr_matrix, pieces, faces) -> list[str]:
        exterior = self.source.exterior
        top = _last_per_row(cover, np.arange(len(regions)))
        painted: list[str | None] = [regions[r].paint.label if r >= 0 else None for r in top]
        painted[0] = exterior
        stated: dict[int, tuple[str, object]] = {}
        for e, srcs in enumerate(pieces.sources):
            for sid, forward in srcs:
                item = self.items[sid]
                if item.kind != "explicit":
                    continue
                edge = item.paint
                left, right = (edge.left, edge.right) if forward else (edge.right, edge.left)
                for face, label, side in ((faces.face_of[2 * e], left, "left"),
                                          (faces.face_of[2 * e + 1], right, "right")):
                    face = int(face)
                    if painted[face] is not None and painted[face] != label:
                        why = ("outside the drawing" if face == 0
                               else "in a face the drawing paints")
                        self.report(f"this edge says the face on its {side} is '{label}', but "
                                    f"that face is {why} '{painted[face]}'", edge.span,
                                    "make the edge's labels agree with the filled shapes")
                    elif face in stated and stated[face][0] != label:
                        other = stated[face][1]
                        self.report(f"conflicting labels for one face: this edge says "
                                    f"'{label}' on its {side}, another edge ({other}) says "
                                    f"'{stated[face][0]}'", edge.span,
                                    "edges around one face must name the same label")
                    else:
                        stated.setdefault(face, (label, edge.span))
        return [painted[f] if painted[f] is not None
                else stated.get(f, (exterior,))[0] for f in range(faces.count)]

    def assemble(self, pieces, faces, labels, regions, cover: csr_matrix) -> ExampleGraph:
        left_face, right_face = faces.face_of[0::2], faces.face_of[1::2]
        # The last region painting both sides of a piece hides every earlier source of it.
        both = cover[left_face].multiply(cover[right_face]).tocsr()
        hidden_after = _last_per_row(both, np.array([s.order for s in regions], dtype=np.int64))
        kinds = [item.kind for item in self.items]
        orders = [item.order for item in self.items]
        ends, lefts, rights = pieces.ends.tolist(), left_face.tolist(), right_face.tolist()
        kept: list[tuple[int, int, str, str, str, Span | None]] = []
        for e, (srcs, hidden) in enumerate(zip(pieces.sources, hidden_after.tolist())):
            visible = [sid for sid, _ in srcs if kinds[sid] == "explicit" or orders[sid] >= hidden]
            if not visible:
                continue
            # A line's class beats a bare outline; among lines the last drawn wins.
            classed = [sid for sid in visible if kinds[sid] != "region"]
            decider = max(classed or visible, key=orders.__getitem__)
            paint = self.items[decider].paint
            cls = DEFAULT_CLASS if kinds[decider] == "region" else paint.cls
            kept.append((ends[e][0], ends[e][1], labels[lefts[e]], labels[rights[e]], cls,
                         paint.span))
        kept = _dissolve(kept, pieces.vertices, pieces.is_input)
        return _canonical(pieces.vertices, kept)


def _last_per_row(matrix: csr_matrix, values: np.ndarray) -> np.ndarray:
    """For each row, the largest `values[column]` over its non-zero columns, else -1."""
    out = np.full(matrix.shape[0], -1, dtype=np.int64)
    coo = matrix.tocoo()
    if coo.nnz:
        np.maximum.at(out, coo.row, values[coo.col])
    return out


def _ring_area(ring) -> float:
    if len(ring) < 3:
        return 0.0
    arr = np.asarray(ring, dtype=float)
    x, y = arr[:, 0], arr[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _face_samples(vertices: np.ndarray, ends: np.ndarray, faces) -> np.ndarray:
    """A point strictly inside each face (row 0, the unbounded face, is unused).

    Each side of each edge offers the point just off its midpoint, closer than any other edge
    (so it lies in the face on that side); a face takes the offer farthest from other edges.
    """
    a, b = vertices[ends[:, 0]], vertices[ends[:, 1]]
    mid = (a + b) / 2.0
    d = b - a
    length = np.hypot(d[:, 0], d[:, 1])
    normal = np.stack([-d[:, 1], d[:, 0]], axis=1) / length[:, None]
    lines = shapely.linestrings(np.stack([a, b], axis=1))
    mids = shapely.points(mid)
    room = length / 4.0
    # Only edges within twice the room can shrink it.
    qi, li = shapely.STRtree(lines).query(mids, predicate="dwithin", distance=2.0 * room)
    others = qi != li
    qi, li = qi[others], li[others]
    if len(qi):
        np.minimum.at(room, qi, shapely.distance(mids[qi], lines[li]) / 2.0)
    offer_face = faces.face_of                        # half-edge 2e: left side, 2e+1: right
    offer_room = np.repeat(room, 2)
    sign = np.tile([1.0, -1.0], len(ends))
    offer_point = np.repeat(mid, 2, axis=0) + (sign * offer_room)[:, None] \
        * np.repeat(normal, 2, axis=0)
    order = np.lexsort((-offer_room, offer_face))
    faces_sorted, first = np.unique(offer_face[order], return_index=True)
    samples = np.zeros((faces.count, 2))
    samples[faces_sorted] = offer_point[order[first]]
    return samples


def _dissolve(kept, vertices: np.ndarray, is_input: np.ndarray):
    """Join the two pieces at a vertex noding made (not one the user drew) when only they are
    left there, run straight on, and carry the same labels and class: it was a crossing with
    something that turned out hidden."""
    made = set(np.flatnonzero(~is_input).tolist())
    if not made:
        return kept
    at: dict[int, list[int]] = {}
    for k, (u, v, *_rest) in enumerate(kept):
        for end in (u, v):
            if end in made:
                at.setdefault(end, []).append(k)
    alive = list(kept)
    for vertex in sorted(at):
        ks = [k for k in at[vertex] if alive[k] is not None]
        if len(ks) != 2:
            continue
        e1, e2 = alive[ks[0]], alive[ks[1]]
        # Orient e1 to end at the vertex and e2 to start there.
        if e1[0] == vertex:
            e1 = (e1[1], e1[0], e1[3], e1[2], e1[4], e1[5])
        if e2[1] == vertex:
            e2 = (e2[1], e2[0], e2[3], e2[2], e2[4], e2[5])
        if e1[2:5] != e2[2:5] or e1[0] == e2[1]:
            continue
        da, db = vertices[vertex] - vertices[e1[0]], vertices[e2[1]] - vertices[vertex]
        if abs(da[0] * db[1] - da[1] * db[0]) > 1e-9 * np.hypot(*da) * np.hypot(*db) \
                or da @ db <= 0:
            continue
        alive[ks[0]], alive[ks[1]] = (e1[0], e2[1], e1[2], e1[3], e1[4], e1[5] or e2[5]), None
        far = e2[1]
        if far in at:
            at[far] = [ks[0] if k == ks[1] else k for k in at[far]]
    return [k for k in alive if k is not None]


def _canonical(vertices: np.ndarray, kept) -> ExampleGraph:
    used = sorted({u for u, *_ in kept} | {v for _, v, *_ in kept})
    coords = np.round(vertices[used], 9) + 0.0        # + 0.0 turns -0.0 into 0.0
    order = np.lexsort((coords[:, 1], coords[:, 0]))
    new_id = {used[k]: rank for rank, k in enumerate(order.tolist())}
    out_vertices = tuple((float(x), float(y)) for x, y in coords[order].tolist())
    edges = []
    for u, v, left, right, cls, span in kept:
        a, b = new_id[u], new_id[v]
        if a > b:
            a, b, left, right = b, a, right, left
        edges.append(((a, b, left, right, cls), span))
    edges.sort(key=lambda item: item[0])
    return ExampleGraph(out_vertices, tuple(e for e, _ in edges), tuple(s for _, s in edges))
