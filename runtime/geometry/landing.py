"""Where a free-standing new component lands.

A component created on its own (a starter applied, say) must end up in a face whose label is
its outer face label: a window inside a tower, not in the sky. The face test refuses every
other place, so a component whose outer label is not the exterior is aimed into a corner
(a sector between two half-edges of an existing vertex) that carries that label; a random
place near any vertex would almost always be refused.

The outer label is read off the rule's side without positions: edge directions are fixed, so
walking each face with the face on the left sums its turns to +360° for a bounded face and
−360° for the outer one (a U-turn at a dangling end counts −180°).
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from grammar_lang.graph import Slot

from .change import HostView
from .spatial import Point
from .tables import Tables


def _angle(t: Tables, p: int, i: int) -> float:
    dx, dy = t.direction[p][i]
    return math.degrees(math.atan2(dy, dx))


def outer_label(t: Tables, prim: dict[int, int],
                partner: Callable[[int, int], Slot | None]) -> str | None:
    """The outer face label shared by the components on `prim` (vertex → primitive), or None
    when a half-edge is open or the components disagree."""
    seen: set[Slot] = set()
    labels = set()
    for v in sorted(prim):
        for i in range(len(t.rings[prim[v]])):
            if (v, i) in seen:
                continue
            turn, walk = 0.0, (v, i)
            while walk not in seen:
                seen.add(walk)
                a, ai = walk
                nxt = partner(a, ai)
                if nxt is None or nxt[0] not in prim:
                    return None
                w, j = nxt
                k = (j - 1) % len(t.rings[prim[w]])
                d = (_angle(t, prim[w], k) - _angle(t, prim[a], ai)) % 360.0
                turn += -180.0 if k == j else (d if d < 180.0 else d - 360.0)
                walk = (w, k)
            if turn < 0:
                labels.add(t.left[prim[v]][i])
    return labels.pop() if len(labels) == 1 else None


def sectors(t: Tables) -> dict[str, list[tuple[int, float, float]]]:
    """Per face label, the corners that carry it: (primitive, from angle, ccw width)."""
    out: dict[str, list[tuple[int, float, float]]] = {}
    for p, ring in enumerate(t.rings):
        n = len(ring)
        for k in range(n):
            a = _angle(t, p, k)
            width = 360.0 if n == 1 else (_angle(t, p, (k + 1) % n) - a) % 360.0
            out.setdefault(t.left[p][k], []).append((p, a, width))
    return out


def spot(host: HostView, rng: np.random.Generator, corners: list[tuple[int, float, float]],
         reach: float) -> Point | None:
    """A point inside one of `corners` at a random existing vertex, about `reach` away;
    None when the drawing has no such vertex."""
    counts = np.array([len(host.by_prim[p]) for p, _, _ in corners], dtype=float)
    if counts.sum() == 0:
        return None
    c = int(rng.choice(len(corners), p=counts / counts.sum()))
    p, a, width = corners[c]
    lst = host.by_prim[p]
    x, y = host.pos[lst[int(rng.integers(len(lst)))]]
    ang = math.radians(a + width * (0.25 + 0.5 * float(rng.random())))
    r = reach * (0.5 + float(rng.random()))
    return (x + r * math.cos(ang), y + r * math.sin(ang))
