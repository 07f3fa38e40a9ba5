"""A uniform grid over segments and points, so geometric tests look at neighbours only.

Cells are squares of side `cell`. A segment is filed in every cell of side `seg` (the host's:
half a cell) its bounding box touches, which is a handful for edges of about the unit length
the grid is sized for. The segment queries (the crossing tests' candidates, the face test's
ray) have exact answers, so their cells may be any size: the host's drawings densify as they
grow, and smaller cells hold fewer segments that a test reads and discards. Queries return ids
sorted, so nothing depends on insertion or hash order.

Points are also filed in much finer cells (side `fine`, a couple of clearances): the test for a
vertex on top of another looks at a radius of one clearance, and as a drawing fills in, a unit
cell comes to hold dozens of vertices (curl at 20,000 vertices: 17 a cell, against 5 at 1,000).
A point is filed in every fine cell within fine/2 of it (one to four), so that a test of a
radius up to fine/2 reads one cell: it runs for every new vertex of every sample, a vertex is
filed once. That test is exact, so it does not depend on the cells; the coarse cells stay as
they are for the queries whose answer is a superset that depends on them (candidates, bounds).
"""

from __future__ import annotations

import bisect
import heapq
import math
from operator import itemgetter
from typing import Hashable, Iterator

Point = tuple[float, float]
_first = itemgetter(0)


class Grid:
    def __init__(self, cell: float, fine: float | None = None, seg: float | None = None):
        if not cell > 0 or any(x is not None and not x > 0 for x in (fine, seg)):
            raise ValueError("grid cell size must be positive")
        self.cell = float(cell)
        self.fine = float(fine or cell)
        self.seg = float(seg or cell)
        self._fine_cells: dict[tuple[int, int], list] = {}
        self._seg_cells: dict[tuple[int, int], set] = {}
        # Per row of cells, the sorted columns whose cell holds a segment: a ray cast to the
        # left jumps over empty cells instead of stepping through each (a sparse drawing is
        # mostly empty cells, and a ray can cross all of its width).
        self._seg_cols: dict[int, list[int]] = {}
        self._pt_cells: dict[tuple[int, int], set] = {}
        self._tag_cells: dict[Hashable, dict] = {}  # tag → cell → the points with that tag
        self._tag_of: dict[Hashable, Hashable] = {}
        # Segment id → (low x, low y, high x, high y, end, end): its box, made once when it is
        # filed, for the crossing tests of every sample that comes near it. Read, don't change.
        self.boxes: dict[Hashable, tuple] = {}
        self._pts: dict[Hashable, Point] = {}
        # Occupied columns and rows (point counts), for bounds and ray casts.
        self._cols: dict[int, int] = {}
        self._rows: dict[int, int] = {}
        self._box: tuple[float, float, float, float] | None = None

    # --- cells ------------------------------------------------------------------------------
    def key(self, p: Point) -> tuple[int, int]:
        return (math.floor(p[0] / self.cell), math.floor(p[1] / self.cell))

    def span(self, x0: float, y0: float, x1: float, y1: float,
             c: float | None = None) -> tuple[int, int, int, int]:
        """The columns i0..i1 and rows j0..j1 of the cells (of side `c`, the point cells'
        unless given) a box touches."""
        c = c or self.cell
        return (math.floor(min(x0, x1) / c), math.floor(max(x0, x1) / c),
                math.floor(min(y0, y1) / c), math.floor(max(y0, y1) / c))

    def _seg_cells_of(self, box: tuple) -> list[tuple[int, int]]:
        """The segment cells a segment's box (see `boxes`) touches, from its low and high
        ends (filing and unfiling a segment is part of every step's commit)."""
        c = self.seg
        i0, i1 = math.floor(box[0] / c), math.floor(box[2] / c)
        j0, j1 = math.floor(box[1] / c), math.floor(box[3] / c)
        if i0 == i1 and j0 == j1:        # the usual case for a short edge
            return [(i0, j0)]
        return [(i, j) for i in range(i0, i1 + 1) for j in range(j0, j1 + 1)]

    # --- segments ---------------------------------------------------------------------------
    def add_segment(self, sid: Hashable, a: Point, b: Point) -> None:
        lx, hx = (a[0], b[0]) if a[0] < b[0] else (b[0], a[0])
        ly, hy = (a[1], b[1]) if a[1] < b[1] else (b[1], a[1])
        box = self.boxes[sid] = (lx, ly, hx, hy, a, b)
        cells = self._seg_cells
        for k in self._seg_cells_of(box):
            cell = cells.get(k)
            if cell is None:
                cell = cells[k] = set()
                bisect.insort(self._seg_cols.setdefault(k[1], []), k[0])
            cell.add(sid)

    def remove_segment(self, sid: Hashable) -> None:
        for k in self._seg_cells_of(self.boxes.pop(sid)):
            cell = self._seg_cells[k]
            cell.discard(sid)
            if not cell:
                del self._seg_cells[k]
                cols = self._seg_cols[k[1]]
                del cols[bisect.bisect_left(cols, k[0])]
                if not cols:
                    del self._seg_cols[k[1]]

    def _next_column(self, col: int, rows) -> int | None:
        """The largest column below `col` holding a segment in one of `rows`."""
        best = None
        for row in rows:
            cols = self._seg_cols.get(row)
            if cols:
                k = bisect.bisect_left(cols, col)
                if k and (best is None or cols[k - 1] > best):
                    best = cols[k - 1]
        return best

    def segment(self, sid: Hashable) -> tuple[Point, Point]:
        return self.boxes[sid][4:]

    def segments_near(self, x0: float, y0: float, x1: float, y1: float) -> set:
        """Ids of segments filed in any cell the box touches (a superset of those meeting it).
        The set may be the grid's own: read it, do not change it."""
        out: set = set()
        cells, c = self._seg_cells, self.seg
        i0, i1 = math.floor(min(x0, x1) / c), math.floor(max(x0, x1) / c)
        j0, j1 = math.floor(min(y0, y1) / c), math.floor(max(y0, y1) / c)
        if i0 == i1 and j0 == j1:           # the usual case: one cell, no copy needed
            return cells.get((i0, j0), out)
        if (i1 - i0 + 1) * (j1 - j0 + 1) > len(cells):
            # A box larger than the drawing's filled cells (a slid stretch of a frame's side
            # 100,000 px long): those cells, not the box's. Walked cell by cell, one step of
            # the castle at that extent took 30 s.
            for (i, j), s in cells.items():
                if i0 <= i <= i1 and j0 <= j <= j1:
                    out |= s
            return out
        for i in range(i0, i1 + 1):
            for j in range(j0, j1 + 1):
                s = cells.get((i, j))
                if s:
                    out |= s
        return out

    # --- points -----------------------------------------------------------------------------
    def add_point(self, pid: Hashable, p: Point, tag: Hashable = None) -> None:
        """File point `pid` at `p`; with a `tag` (the host's: its primitive) also under that
        tag, for points_near(tag=...)."""
        self._pts[pid] = p
        k = self.key(p)
        self._pt_cells.setdefault(k, set()).add(pid)
        if tag is not None:
            self._tag_of[pid] = tag
            self._tag_cells.setdefault(tag, {}).setdefault(k, set()).add(pid)
        for fk in self._reach(p):
            self._fine_cells.setdefault(fk, []).append(pid)
        for d, key in ((self._cols, k[0]), (self._rows, k[1])):
            n = d.get(key, 0)
            d[key] = n + 1
            if not n:
                self._box = None          # a new column or row: the bounds may grow

    def remove_point(self, pid: Hashable) -> None:
        p = self._pts.pop(pid)
        k = self.key(p)
        cell = self._pt_cells[k]
        cell.discard(pid)
        if not cell:
            del self._pt_cells[k]
        tag = self._tag_of.pop(pid, None)
        if tag is not None:
            cells = self._tag_cells[tag]
            cell = cells[k]
            cell.discard(pid)
            if not cell:
                del cells[k]
        for fk in self._reach(p):
            fine = self._fine_cells[fk]
            fine.remove(pid)
            if not fine:
                del self._fine_cells[fk]
        for d, key in ((self._cols, k[0]), (self._rows, k[1])):
            d[key] -= 1
            if not d[key]:
                del d[key]
                self._box = None          # a column or row emptied: the bounds may shrink

    def points_near(self, x0: float, y0: float, x1: float, y1: float,
                    ordered: bool = True, tag: Hashable = None) -> list:
        """Ids of points filed in any cell the box touches, sorted unless `ordered` is False
        (for callers that put them in an order of their own); with a `tag`, only the points
        filed under it (a splice's search box spans about 30 cells and many primitives)."""
        out = []
        cells = self._pt_cells if tag is None else self._tag_cells.get(tag, {})
        i0, i1, j0, j1 = self.span(x0, y0, x1, y1)
        # box_cells' order, without listing the cells.
        for i in range(i0, i1 + 1):
            for j in range(j0, j1 + 1):
                s = cells.get((i, j))
                if s:
                    out.extend(s)
        return sorted(out) if ordered else out

    def nearest_first(self, x0: float, y0: float, x1: float, y1: float, centre: Point,
                      tags) -> Iterator[Hashable]:
        """points_near's points of the given tags, in order of (squared distance from
        `centre`, id), found lazily: a splice's search box holds about a hundred candidates
        at 20,000 vertices and uses the first one or two, so cells are opened nearest first
        and a point is given out once no unopened cell can hold a nearer one."""
        cx, cy = centre
        c, pts = self.cell, self._pts
        maps = [m for m in (self._tag_cells.get(t) for t in tags) if m]
        i0, i1, j0, j1 = self.span(x0, y0, x1, y1)
        # A cell's least squared distance from the centre, less a margin for the rounding of
        # floor(x / c) and of the distances: a lower bound for any point filed there.
        eps = 1e-6 * c
        gx = [_gap(i * c - cx, cx - (i + 1) * c, eps) ** 2 for i in range(i0, i1 + 1)]
        gy = [_gap(j * c - cy, cy - (j + 1) * c, eps) ** 2 for j in range(j0, j1 + 1)]
        cells = []                      # (bound, points) of the cells that hold any
        for i, bx in enumerate(gx, i0):
            for j, by in enumerate(gy, j0):
                for m in maps:
                    s = m.get((i, j))
                    if s:
                        cells.append((bx + by, s))
        cells.sort(key=_first)
        heap: list = []
        for bound, s in cells:
            while heap and heap[0][0] < bound:
                yield heapq.heappop(heap)[1]
            for h in s:
                p = pts[h]
                heapq.heappush(heap, ((p[0] - cx) ** 2 + (p[1] - cy) ** 2, h))
        while heap:
            yield heapq.heappop(heap)[1]

    def _reach(self, p: Point) -> list[tuple[int, int]]:
        """The fine cells within fine/2 of `p`, where it is filed."""
        f = self.fine
        h = 0.5 * f
        i0, i1 = math.floor((p[0] - h) / f), math.floor((p[0] + h) / f)
        j0, j1 = math.floor((p[1] - h) / f), math.floor((p[1] + h) / f)
        return [(i, j) for i in range(i0, i1 + 1) for j in range(j0, j1 + 1)]

    def point_within(self, p: Point, r: float, skip=()) -> bool:
        """Is a point not in `skip` closer than `r` to `p`? Exact; `r` up to fine/2 reads one
        cell, a larger one the cells its box touches."""
        f, fine, pts = self.fine, self._fine_cells, self._pts
        px, py = p
        if r <= 0.5 * f:
            # A point q closer than r has |px − qx| < fine/2, so px lies in q's filed range
            # [qx − fine/2, qx + fine/2] (rounding is monotonic), and so does p's cell.
            cells = (fine.get((math.floor(px / f), math.floor(py / f)), ()),)
        else:
            cells = [fine.get((i, j), ())
                     for i in range(math.floor((px - r) / f), math.floor((px + r) / f) + 1)
                     for j in range(math.floor((py - r) / f), math.floor((py + r) / f) + 1)]
        for cell in cells:
            for q in cell:
                if q not in skip:
                    x, y = pts[q]
                    if ((px - x) ** 2 + (py - y) ** 2) ** 0.5 < r:
                        return True
        return False

    def bounds(self) -> tuple[float, float, float, float] | None:
        """The box of occupied point cells (cell-aligned), or None when empty. Kept until a
        column or row of cells appears or empties, since it is asked for on every step."""
        if not self._cols:
            return None
        if self._box is None:
            c = self.cell
            self._box = (min(self._cols) * c, min(self._rows) * c,
                         (max(self._cols) + 1) * c, (max(self._rows) + 1) * c)
        return self._box

    def ray_left(self, p: Point, skip=(), tol: float = 0.0) -> tuple[Hashable, float] | None:
        """The first segment hit by the ray from `p` towards -x, at height p.y + 0⁺.

        Heights within `tol` of p.y count as equal to it, so that two vertices meant to be level
        (the ends of a horizontal edge, say) are treated as level despite rounding noise. A
        segment counts when one end is at or below the ray's height and the other strictly
        above it (above p.y + tol), which makes the ray miss segments that merely end at p or
        that leave a level vertex downwards. Segments leaving one level vertex upwards all
        meet the ray at that vertex; the one leaning furthest right is hit first, as it would
        be just above p.y. The hit is kept within the segment's box. Returns (id, x of the hit).
        """
        px, py = p
        c = self.seg
        col0 = math.floor(px / c)
        top = py + tol
        r0, r1 = math.floor((py - tol) / c), math.floor(top / c)     # their order is free
        rows = (r0,) if r0 == r1 else (r0, r1)
        b = self.bounds()
        if b is None:
            return None
        lo = math.floor(b[0] / c)
        best: tuple[float, float, Hashable] | None = None
        cells, boxes = self._seg_cells, self.boxes
        col = col0
        # Every segment ends at points, so nothing lies left of the leftmost point column.
        while col >= lo:
            for row in rows:
                cell = cells.get((col, row))
                if not cell:
                    continue
                # A segment met again in a later cell gives the same key and changes nothing,
                # so none is remembered; most in a cell do not reach the ray's height, which
                # their boxes tell first.
                for sid in cell:
                    lx, ly, hx, hy, (ax, ay), (bx, by) = boxes[sid]
                    if ly > top or hy <= top or sid in skip:     # both ends on one side
                        continue
                    if ay > by:
                        ax, ay, bx, by = bx, by, ax, ay
                    lean = (bx - ax) / (by - ay)     # x gained per unit of height
                    x = ax if ay >= py - tol else ax + (py - ay) * lean
                    # The exact hit lies in the segment's box; rounding can put the computed
                    # one just outside, past the column where the stop test below expects it.
                    x = lx if x < lx else hx if x > hx else x
                    if x >= px:
                        continue
                    key = (x, lean)
                    if best is None or key > best[:2] or (key == best[:2] and sid < best[2]):
                        best = (x, lean, sid)
            # Compared as the cells were filed (x / c), so that a segment filed only left of
            # `col` cannot hold a hit right of this one.
            if best is not None and best[0] / c >= col:
                break
            # Jump to the next column with a segment: the cells skipped are empty, and the
            # stop test above would have held at the last of them if it holds anywhere there.
            nxt = self._next_column(col, rows)
            if nxt is None:
                break
            if nxt < col - 1 and best is not None and best[0] / c >= nxt + 1:
                break
            col = nxt
        return None if best is None else (best[2], best[0])


def _gap(below: float, above: float, eps: float) -> float:
    """How far a coordinate lies outside a cell's range (`below`: the range's low end minus
    it, `above`: it minus the high end), less `eps`; 0 inside."""
    return max(below - eps, above - eps, 0.0)


def seg_distance(a: Point, b: Point, c: Point, d: Point) -> float:
    """Euclidean distance between segments ab and cd (0 when they cross or touch)."""
    if _cross(a, b, c, d):
        return 0.0
    return min(_pt_seg(a, c, d), _pt_seg(b, c, d), _pt_seg(c, a, b), _pt_seg(d, a, b))


def _orient(a: Point, b: Point, c: Point) -> float:
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def _cross(a: Point, b: Point, c: Point, d: Point) -> bool:
    o1, o2 = _orient(a, b, c), _orient(a, b, d)
    o3, o4 = _orient(c, d, a), _orient(c, d, b)
    return ((o1 > 0 > o2) or (o1 < 0 < o2)) and ((o3 > 0 > o4) or (o3 < 0 < o4))


def _pt_seg(p: Point, a: Point, b: Point) -> float:
    dx, dy = b[0] - a[0], b[1] - a[1]
    L = dx * dx + dy * dy
    t = 0.0 if L == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / L))
    ex, ey = a[0] + t * dx - p[0], a[1] + t * dy - p[1]
    return math.hypot(ex, ey)
