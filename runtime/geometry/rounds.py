"""What stays the same for every sample of a solver round (`Round`): the system, the free
vertices' base coordinates, the known and drawn lengths and their ranges."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .spatial import Point
from .system import REPAIR_MARGIN, Factor

# New edges are drawn between half and 1.8 times their label's typical length in the example
# (stretched as their neighbourhood is), or the local scale where the typical length is not
# known. Longer than short: a part that is to hold more than the example's part did (a
# station's module with a second connector under it, a castle's block with a keep on it)
# must be drawn wider than typical. Within ±50 % the paper's castle grew mostly thin poles
# and one keep, and its station covered less (over seeds 0-3 at the paper's N: station
# 117 → 153 vertices, 32 → 49 % of its frame covered; castle 272 → 291, 40 → 45 %).
_LOW, _HIGH = 0.5, 1.8


@dataclass
class Round:
    """A round's system (its edges, matrix, right-hand side, column scales, minimum-norm
    inverse) and constants: free vertices' base coordinates (old: where they are, new: their
    aim, nan: no aim, the change's centre per sample), which coordinates are new (`moving`)
    and which of those have no aim; edge lengths known in advance (fixed, or kept; nan:
    drawn), which edges are drawn, their class bounds, where drawn ones are centred, the
    tiled edges. Lists of indices, so that a sample's loops visit only the coordinates it
    changes. Draw ranges and what the crossing tests leave out are made once, when first
    needed."""

    edges: list
    fact: Factor             # the system's matrix, column scales and minimum-norm inverse
    b: np.ndarray
    base: list
    moving: list
    aimless: list
    known: list
    drawn: list
    lo: list
    hi: list
    centre: list             # per drawn edge
    tiles: list
    tiled: tuple             # the tiled edges alone: the key of their pinned system
    lo_tol: list             # the class bounds widened by the tolerance
    hi_tol: list
    context: tuple | None = None     # what the crossing tests leave out (_planar_context)
    sides: list | None = None        # per edge, whether it is a frame's side (_crowds)
    hoods: dict = field(default_factory=dict)   # vertex → those near it in the graph (_hood)
    unrepaired: int = 0              # samples in a row `repair` found no point for
    _ranges: dict = field(default_factory=dict)
    _clip: tuple | None = None       # clip_box's, made once

    def targets_at(self, centre: Point) -> list:
        """The base coordinates, those without an aim at `centre`, then the known lengths
        (nan where drawn): a new list, for a sample to fill in."""
        x = self.base + self.known
        cx, cy = centre
        for k in self.aimless:
            x[k] = cy if k & 1 else cx
        return x

    def clip_box(self, tol: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Each length's range for `repair`: the test's, less a margin on each side (the
        margin is `repair`'s slack), so that a repaired length passes the test."""
        box = self._clip
        if box is None:
            lo = np.array([max(lt, tol) for lt in self.lo_tol])
            hi = np.array(self.hi_tol, dtype=float)
            m = np.maximum(np.minimum(REPAIR_MARGIN * np.maximum(lo, 1.0), 0.25 * (hi - lo)), 0.0)
            box = self._clip = (lo + m, hi - m, m)
        return box

    def ranges(self, f: float) -> tuple[list, list, list]:
        """Where new edges' target lengths are drawn at size factor `f`: (low end, high end,
        width) per drawn edge. From _LOW·centre·f to _HIGH·centre·f, inside the range the
        length test allows (the class, above the label's floor), or that whole range when it
        misses it; when a shrunk range falls below it, its shortest length."""
        r = self._ranges.get(f)
        if r is None:
            los, his, widths = [], [], []
            # Asked for most samples (each failure changes f): max and min written out, as
            # the builtins decide them (a later argument wins only when strictly beyond).
            for e, c in zip(self.drawn, self.centre):
                # The shortest length the test lets through: the class's minimum, or the
                # label's floor when that is higher (drawn below it, a sample always failed).
                lo, hi = max(self.lo[e], self.lo_tol[e]), self.hi[e]
                a, bb = _LOW * c * f, _HIGH * c * f
                a = a if a > lo else lo
                bb = bb if bb < hi else hi
                if a > bb:
                    # The whole range, as wide as a usual draw where it has no end (a border
                    # class's).
                    a, bb = (lo, hi if hi < math.inf else lo * _HIGH / _LOW) \
                        if f == 1.0 or hi < a else (lo, lo)
                los.append(a)
                his.append(bb)
                widths.append(bb - a)
            r = self._ranges[f] = (los, his, widths)
        return r
