"""The linear system of a solver round, and what its shape alone fixes (paper §6.2).

For the free vertices F and every edge e = uv touching them, `p_v − p_u − s_e d_e = 0`, with
the length s_e unknown and the fixed ends moved to the right-hand side: A x = b over positions
and lengths. The matrix depends only on the move's topology, so its factorisation (a
minimum-norm inverse of the column-scaled matrix, `min_norm.py`) is made once per shape and
kept (`SystemCache`). `repair` finds the point of the system nearest a sample whose lengths
lie in their ranges.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import dataclass, field

import numpy as np

from .min_norm import min_norm_inverse
from .slides import Slide

# Column scales of the weighted projection: a larger scale is cheaper to move.
NEW_POS, OLD_POS, LENGTH = 10.0, 1.0, 1.0
# A new vertex glued to no old one (in a structure made whole, or stood on a frame's side) has
# only the change's centre to aim at: its place comes from the lengths, or the projection
# would squeeze the structure towards that point.
LOOSE_POS = 100.0
# A frame's sides are as long as the frame: a structure standing on one takes what it needs
# and the stretches of bare side beside it take the rest, so their lengths are cheapest.
FRAME_SIDE = 100.0
# A new edge's drawn length is stiffer than the old drawing: the projection lets old vertices
# (once freed) give way rather than squash the new part. At LENGTH the misfit of a part
# squeezed between old ones was shared equally, so its new edges came out far shorter than
# drawn, often negative: on the paper's castle most rounds could not pass ("length out of
# range", "edge length"). 0.1: ten times stiffer.
DRAWN_LENGTH = 0.1
# At most this many lengths `repair` pins where a projection left them out of range; a
# length is pinned REPAIR_MARGIN of its lower bound inside its range.
REPAIR = 12
REPAIR_MARGIN = 1e-3


@dataclass(frozen=True)
class Factor:
    """What a system's shape alone fixes: its matrix, column scales and a minimum-norm inverse,
    the rows of lengths that no target moves, and whether the solution is unique."""

    A: np.ndarray
    scale: np.ndarray
    M: np.ndarray
    Minv: np.ndarray
    R: np.ndarray
    fixed_idx: list          # the lengths that no target moves
    unique: bool
    absR: np.ndarray
    Minv_len: np.ndarray     # the rows of Minv and of the scales for the lengths
    scale_len: np.ndarray
    P_len: np.ndarray        # the null-space projection's columns for the lengths (`repair`)
    # By tiled edges: the system with their lengths pinned. Kept with the shape, since the
    # same tiled edges come back with it (castle: 969 of 1,367 pinned systems were repeats).
    _pinned: dict = field(default_factory=dict)

    def pinned_system(self, tiled: tuple[int, ...], nF: int) -> tuple[np.ndarray, np.ndarray]:
        """A with a row pinning each tiled length, and its minimum-norm inverse: the same for
        every sample (only the pinned values change)."""
        pinned = self._pinned.get(tiled)
        if pinned is None:
            rows = np.zeros((len(tiled), self.A.shape[1]))
            for r, e in enumerate(tiled):
                rows[r, 2 * nF + e] = 1.0
            A2 = np.vstack([self.A, rows])
            pinned = self._pinned[tiled] = (A2, min_norm_inverse(A2))
        return pinned

    def project_pinned(self, x: np.ndarray, n: int, pins: dict[int, float]) -> np.ndarray | None:
        """The point of the system nearest its point `x`, in the projection's weighted norm,
        whose lengths `pins` (by edge index; lengths start at index `n`) have the values given;
        None when the pins leave the system without a solution.

        The step d from `x` lies in the system's null space and is the shortest that sets the
        pinned lengths: d = P[:, E] · P[E, E]⁻¹ · r, with P the projection onto the null space
        (`P_len`: its columns for the lengths), E the pinned lengths and r how far each is
        from its pin. A k×k solve, where an inverse of the pinned system took 20 times
        as long and, made for every sample's pins, tripled the castle's time."""
        tol = 1e-9 * (1.0 + float(np.abs(x).max()))
        if len(pins) == 1:
            # One pin, as in most of the station's repairs (46 % of them at seed 6): the 1×1
            # solve is one division, the same number LAPACK's would give, without its checks.
            (e, value), = pins.items()
            col = self.P_len[:, e]
            g, r1 = float(col[n + e]), value - float(x[n + e])
            if abs(g) > tol:
                d = col * (r1 / g)
                if abs(float(d[n + e]) - r1) <= tol \
                        and float(np.abs(self.A.dot(d)).max(initial=0.0)) <= tol:
                    return x + d
        idx = np.fromiter(pins, dtype=int, count=len(pins))
        r = np.fromiter(pins.values(), dtype=float, count=len(pins)) - x[n + idx]
        cols = self.P_len[:, idx]
        G = cols[n + idx]
        # Pins the system ties together (a rectangle's two sides) make P[E, E] singular, or
        # nearly: a plain solve then gives a step off the system (0.04 px on the castle) that
        # the pins alone do not show. So the step is checked on the system too, and made
        # again by least squares when it fails there.
        for solve in (np.linalg.solve, _least_squares):
            try:
                d = cols.dot(solve(G, r))
            except np.linalg.LinAlgError:
                continue
            if float(np.abs(d[n + idx] - r).max(initial=0.0)) <= tol \
                    and float(np.abs(self.A.dot(d)).max(initial=0.0)) <= tol:
                return x + d
        return None


def _least_squares(G: np.ndarray, r: np.ndarray) -> np.ndarray:
    return np.linalg.lstsq(G, r, rcond=1e-10)[0]


class SystemCache:
    """Factorisations by system shape. A move's system depends only on its topology (which
    vertices are free and old, each edge's ends, direction and fixed length), never on where
    the old vertices are, and the same shapes come back step after step: one inverse each.
    Bounded: when full the least recently used shape goes. Emptying it instead threw away
    the shapes of the matches being retried (on the castle, 1,600 of 9,900 factorisations
    were of a shape seen before)."""

    def __init__(self, size: int = 4096):
        self.size, self.table = size, OrderedDict()

    def get(self, shape):
        fact = self.table.get(shape)
        if fact is not None:
            self.table.move_to_end(shape)
        return fact

    def put(self, shape, fact: Factor) -> Factor:
        if len(self.table) >= self.size:
            self.table.popitem(last=False)
        self.table[shape] = fact
        return fact


def slid_pos(slide: Slide) -> float:
    # A slide moves all its vertices: the projection is charged as if each moved alone (the
    # squares of their moves add up), so a large part gives way less than a corner.
    return OLD_POS / math.sqrt(1 + len(slide.offsets))


def factorise(pos_scale: tuple[float, ...], edges) -> Factor:
    """`A` over (positions of the free vertices, edge lengths): row pair e says
    p_w − p_v − s_e d_e = (fixed ends moved to b), then one row per fixed length. An edge of
    the shape is (free index of v or −1, of w or −1, direction, fixed length, frame side,
    drawn: new, not an existing edge kept); `pos_scale`: each free vertex's column scale."""
    nF, nE = len(pos_scale), len(edges)
    fixed = [e for e, (_, _, _, f, _, _) in enumerate(edges) if f is not None]
    A = np.zeros((2 * nE + len(fixed), 2 * nF + nE))
    # Cell by cell: on systems of this size numpy's index arrays cost more than the loop
    # (2,205 castle systems: 0.13 s by np.add.at, 0.095 s so).
    for e, (iv, iw, d, _, _, _) in enumerate(edges):
        for c in (0, 1):
            if iw >= 0:
                A[2 * e + c, 2 * iw + c] += 1.0
            if iv >= 0:
                A[2 * e + c, 2 * iv + c] -= 1.0
            A[2 * e + c, 2 * nF + e] = -d[c]
    A[2 * nE + np.arange(len(fixed)), 2 * nF + np.asarray(fixed, dtype=int)] = 1.0
    scale = np.empty(2 * nF + nE)
    scale[:2 * nF] = np.repeat(pos_scale, 2)
    scale[2 * nF:] = [FRAME_SIDE if side else DRAWN_LENGTH if drawn else LENGTH
                      for *_, side, drawn in edges]
    M = A * scale
    Minv = min_norm_inverse(M)
    P = np.eye(A.shape[1]) - scale[:, None] * (Minv @ A)
    R = P[2 * nF:]
    fixed_rows = np.abs(R).max(axis=1, initial=0.0) < 1e-9
    return Factor(A, scale, M, Minv, R, np.flatnonzero(fixed_rows).tolist(),
                  bool(np.abs(P).max(initial=0.0) < 1e-9), np.abs(R), Minv[2 * nF:],
                  scale[2 * nF:], np.ascontiguousarray(P[:, 2 * nF:]))


def repair(x: np.ndarray, n: int, fact: Factor, lo: np.ndarray, hi: np.ndarray,
           slack: np.ndarray, pins: dict[int, float]) -> np.ndarray | None:
    """The point of the system nearest its point `x` (in the projection's weighted norm)
    whose lengths (from index `n` on) lie in [lo, hi] and whose lengths `pins` (tiled edges,
    by edge index) have the values given; None when none was found; `x` itself when it needs
    nothing.

    An active set: project with the pins; the length the projection leaves furthest out of
    range (by more than `slack`) is pinned at its nearest bound, and the projection is made
    again, until none is out (REPAIR pins at most). Pins are only added, so this may miss a
    point that exists, but it never returns one that is not there. Pinning every length out
    of range at once failed where lengths are tied (a rectangle's opposite sides, pinned at
    two bounds); one at a time, the worst first, the ties follow the first pin. This
    replaces alternating projections between the box and the system, which crawl where the
    two meet at a shallow angle: on the castle a keep on a 75 px block top needed hundreds
    of them, and a stall test gave up first; and whose tiles, rounded after, broke the
    lengths they had fitted."""
    pins = dict(pins)
    y = x
    for _ in range(REPAIR + 1):
        if pins:
            y = fact.project_pinned(x, n, pins)
            if y is None:
                return None
        lengths = y[n:]
        if not len(lengths):
            return y
        miss = np.maximum(lo - lengths, lengths - hi)
        if pins:
            miss[list(pins)] = 0.0
        e = int(np.argmax(miss))
        if miss[e] <= slack[e]:
            return y
        pins[e] = min(max(float(lengths[e]), float(lo[e])), float(hi[e]))
    return None


def right_hand_side(shape_edges, edges, pos, attached) -> list[float]:
    """b: the fixed ends' positions (a slide's member: its offset from its anchor, whose
    column it shares), then the fixed lengths."""
    b = []
    for (iv, iw, _, _, _, _), (v, _, w, _, _, _) in zip(shape_edges, edges):
        bx = by = 0.0
        if iw < 0:
            pw = pos[w]
            bx -= pw[0]
            by -= pw[1]
        elif w in attached:
            bx -= attached[w][1]
            by -= attached[w][2]
        if iv < 0:
            pv = pos[v]
            bx += pv[0]
            by += pv[1]
        elif v in attached:
            bx += attached[v][1]
            by += attached[v][2]
        b += (bx, by)
    b.extend(f for _, _, _, f, _, _ in shape_edges if f is not None)
    return b
