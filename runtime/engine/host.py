"""The host drawing: primitive instances glued at their half-edge slots, with positions.

A vertex is an instance of a primitive, so its ring of half-edges (the rotation system) is
fixed by the primitive; the host records only which slot is glued to which, where each vertex
is, and indexes that keep every query local: vertices by primitive (for anchored matching),
edge counts by label (for costs) and a spatial grid of edges and vertices (for geometry).
Face labels are carried by the half-edges: a slot's left and right faces come from its label.

Every change goes through five operations (add/remove vertex, glue/unglue, move), each of which
is written to the open journal, so a step can be undone exactly and redone (the REPL's undo).
Fresh ids come from a counter and are never reused.
"""

from __future__ import annotations

from grammar_lang.algorithms.components import glued_components
from grammar_lang.graph import Slot
from grammar_lang.rules import Header

from ..output.drawing import DEdge, Drawing, DVertex
from ..geometry.spatial import Grid, Point
from ..geometry.tables import Tables, grid_cell

# Heights closer than this (times the unit) count as level in the face test: positions come from
# least squares, so vertices joined by a horizontal edge can differ by rounding noise (~1e-15).
LEVEL_TOL = 1e-7

# Segments are filed in cells this many times finer than the unit cells of points: drawings
# densify as they grow (curl's median edge falls from 0.36 to 0.19 units between 1,000 and
# 20,000 vertices), and the crossing tests and the face test's ray read whole cells. At 20,000
# vertices half-unit cells save 1–3 % of a step; at 1,000 they cost as much as they save.
SEGMENT_CELLS = 2

# Each journaled operation, as (method, indexes of its record's fields) to do it again or to
# undo it: `add v prim p` is undone by `remove v`, `glue a b` by `unglue a`, `move v old new`
# by `move v old`.
_FORWARD = {"add": ("add_vertex", (1, 2, 3)), "remove": ("remove_vertex", (1,)),
            "glue": ("glue", (1, 2)), "unglue": ("unglue", (1,)), "move": ("move", (1, 3))}
_INVERSE = {"add": ("remove_vertex", (1,)), "remove": ("add_vertex", (1, 2, 3)),
            "glue": ("unglue", (1,)), "unglue": ("glue", (1, 2)), "move": ("move", (1, 2))}


class Host:
    def __init__(self, header: Header, tables: Tables | None = None):
        self.header = header
        self.t = tables or Tables.build(header)
        self.prim: dict[int, int] = {}
        self.pos: dict[int, Point] = {}
        self.link: dict[int, list[Slot | None]] = {}
        self.by_prim: list[list[int]] = [[] for _ in self.t.rings]
        # The primitives with no vertex, sorted: the schedule's key for the moves they block.
        # Changed only when a primitive's first vertex comes or its last goes.
        self.absent: tuple[int, ...] = tuple(range(len(self.t.rings)))
        self._where: dict[int, int] = {}
        self.next_id = 0
        cell = grid_cell(self.t)
        self.grid = Grid(cell, fine=2 * self.t.clearance, seg=cell / SEGMENT_CELLS)
        self.label_count = [0] * len(self.t.label_names)
        self.n_edges = 0
        self.n_open = 0
        self.journal: list[tuple] | None = None
        self.pinned: frozenset[int] = frozenset()   # the frame's corners (runtime/geometry/framing.py)
        self.frame = None                           # the placed Frame, when there is one
        self.on_border: frozenset[int] = frozenset()  # primitives with a border half-edge
        self.border_labels: frozenset[int] = frozenset()
        self.side_labels: frozenset[int] = frozenset()      # the frame's bare sides
        self.unsized_sides: frozenset[int] = frozenset()    # those but the gaps
        self.frame_face: str | None = None          # the face just inside the frame

    # --- reading ----------------------------------------------------------------------------
    def __len__(self) -> int:
        return len(self.prim)

    def vertices(self) -> list[int]:
        return sorted(self.prim)

    def degree(self, v: int) -> int:
        return len(self.link[v])

    def neighbours(self, v: int) -> list[int]:
        return [s[0] for s in self.link[v] if s is not None]

    def edges(self) -> list[tuple[int, int, int, int]]:
        out = []
        for v in sorted(self.link):
            for i, s in enumerate(self.link[v]):
                if s is not None and (v, i) < s:
                    out.append((v, i, s[0], s[1]))
        return out

    def new_id(self) -> int:
        self.next_id += 1
        return self.next_id - 1

    # --- the five journaled operations ------------------------------------------------------
    def add_vertex(self, v: int, prim: int, p: Point) -> None:
        assert v not in self.prim
        self.prim[v] = prim
        self.pos[v] = p
        self.link[v] = [None] * len(self.t.rings[prim])
        lst = self.by_prim[prim]
        self._where[v] = len(lst)
        lst.append(v)
        if len(lst) == 1:
            self.absent = tuple(p for p in self.absent if p != prim)
        self.grid.add_point(v, p, prim)
        self.n_open += len(self.link[v])
        self.next_id = max(self.next_id, v + 1)
        self._log(("add", v, prim, p))

    def remove_vertex(self, v: int) -> None:
        assert all(s is None for s in self.link[v]), "unglue a vertex before removing it"
        prim, p = self.prim.pop(v), self.pos.pop(v)
        self.n_open -= len(self.link.pop(v))
        lst = self.by_prim[prim]
        k = self._where.pop(v)
        last = lst.pop()
        if last != v:
            lst[k] = last
            self._where[last] = k
        if not lst:
            self.absent = tuple(sorted((*self.absent, prim)))
        self.grid.remove_point(v)
        self._log(("remove", v, prim, p))

    def glue(self, a: Slot, b: Slot) -> None:
        (v, i), (w, j) = a, b
        assert self.link[v][i] is None and self.link[w][j] is None and a != b
        assert self.t.rings[self.prim[v]][i] == self.t.rings[self.prim[w]][j] ^ 1
        self.link[v][i] = b
        self.link[w][j] = a
        self.n_open -= 2
        self.n_edges += 1
        self.label_count[self.t.label[self.prim[v]][i]] += 1
        k, o = (a, b) if a < b else (b, a)
        self.grid.add_segment(k, self.pos[k[0]], self.pos[o[0]])
        self._log(("glue", a, b))

    def unglue(self, a: Slot) -> Slot:
        v, i = a
        b = self.link[v][i]
        assert b is not None
        self.link[v][i] = None
        self.link[b[0]][b[1]] = None
        self.n_open += 2
        self.n_edges -= 1
        self.label_count[self.t.label[self.prim[v]][i]] -= 1
        self.grid.remove_segment(min(a, b))
        self._log(("unglue", a, b))
        return b

    def move(self, v: int, p: Point) -> None:
        old = self.pos[v]
        if old == p:
            return
        keys = [min((v, i), s) for i, s in enumerate(self.link[v]) if s is not None]
        for k in keys:
            self.grid.remove_segment(k)
        self.pos[v] = p
        self.grid.remove_point(v)
        self.grid.add_point(v, p, self.prim[v])
        for k in keys:
            a, b = k, self.link[k[0]][k[1]]
            self.grid.add_segment(k, self.pos[a[0]], self.pos[b[0]])
        self._log(("move", v, old, p))

    def _log(self, op: tuple) -> None:
        if self.journal is not None:
            self.journal.append(op)

    # --- journal ----------------------------------------------------------------------------
    def begin(self) -> None:
        self.journal = []

    def end(self) -> list[tuple]:
        ops, self.journal = self.journal or [], None
        return ops

    def undo_ops(self, ops: list[tuple]) -> None:
        """Reverse a journal (not itself journaled)."""
        self._replay(reversed(ops), _INVERSE)

    def redo_ops(self, ops: list[tuple]) -> None:
        self._replay(ops, _FORWARD)

    def _replay(self, ops, table) -> None:
        saved, self.journal = self.journal, None
        try:
            for op in ops:
                method, args = table[op[0]]
                getattr(self, method)(*(op[k] for k in args))
        finally:
            self.journal = saved

    # --- faces ------------------------------------------------------------------------------
    def face_ok(self, v: int) -> bool:
        """Is the face left of `v` (along -x) labelled as `v`'s ring says?

        The ray from v to the first edge it hits lies inside one face, so the label v's ring
        gives that direction must equal the label on the facing side of the hit edge, or the
        exterior when nothing is hit. Holding for every vertex of a planar drawing, this makes
        every face's label consistent, nested components included.
        """
        want = self.t.outer[self.prim[v]]
        if want is None:
            return True
        hit = self.grid.ray_left(self.pos[v], tol=LEVEL_TOL * self.t.unit)
        if hit is None:
            return want == self.t.exterior
        (a, i) = hit[0]
        b = self.link[a][i][0]
        pa = self.prim[a]
        upward = self.pos[b][1] > self.pos[a][1]
        # Walking upward, +x (where v is) is on the right; walking downward it is on the left.
        got = self.t.right[pa][i] if upward else self.t.left[pa][i]
        return got == want

    # --- output and checks ------------------------------------------------------------------
    def to_drawing(self, meta: dict | None = None) -> Drawing:
        ids = {v: k for k, v in enumerate(sorted(self.prim))}
        verts = tuple(DVertex(ids[v], self.pos[v][0], self.pos[v][1]) for v in sorted(self.prim))
        edges = []
        for v, i, w, j in self.edges():
            tok = self.t.rings[self.prim[v]][i]
            lab = tok >> 1
            u, x = (w, v) if tok & 1 else (v, w)   # walk along the label's own direction
            left, right = self.t.label_faces[lab]
            edges.append(DEdge(ids[u], ids[x], left, right, self.t.label_class[lab],
                               self.t.label_names[lab]))
        edges.sort(key=lambda e: (e.u, e.v, e.label or ""))
        return Drawing(verts, tuple(edges), dict(meta or {}))

    def components(self) -> list[list[int]]:
        """Vertex sets of the connected components, in order of their smallest vertex."""
        return glued_components(self.prim, self.edges())

    def check_consistency(self) -> list[str]:
        """Recount every index from scratch; the list of disagreements (empty when sound)."""
        errs = []
        n_open = n_edges = 0
        counts = [0] * len(self.label_count)
        for v in sorted(self.prim):
            ring = self.t.rings[self.prim[v]]
            if len(self.link[v]) != len(ring):
                errs.append(f"vertex {v}: {len(self.link[v])} slots for a ring of {len(ring)}")
            for i, s in enumerate(self.link[v]):
                if s is None:
                    n_open += 1
                    continue
                w, j = s
                if w not in self.prim or self.link[w][j] != (v, i):
                    errs.append(f"slot {(v, i)} glued to {s}, which does not glue back")
                    continue
                if self.t.rings[self.prim[w]][j] != ring[i] ^ 1:
                    errs.append(f"slot {(v, i)} glued to a half-edge of another label")
                if (v, i) < s:
                    n_edges += 1
                    counts[self.t.label[self.prim[v]][i]] += 1
                    seg = self.grid.segment((v, i))
                    if seg != (self.pos[v], self.pos[w]):
                        errs.append(f"edge {(v, i)} filed at a stale position")
            if self.by_prim[self.prim[v]][self._where[v]] != v:
                errs.append(f"vertex {v} misfiled in the primitive index")
        if sum(len(l) for l in self.by_prim) != len(self.prim):
            errs.append("primitive index holds stale vertices")
        if self.absent != tuple(p for p, l in enumerate(self.by_prim) if not l):
            errs.append("absent primitives disagree with the primitive index")
        if n_open != self.n_open or n_edges != self.n_edges or counts != self.label_count:
            errs.append("edge or open-slot counts disagree with a recount")
        return errs
