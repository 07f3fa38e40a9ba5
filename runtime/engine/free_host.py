"""The host graph of hand-written productions: attributed vertices, edges and faces, indexed.

Every element has one id from a single counter, so ids grow with age and "oldest first" is
"smallest id first". Indexes kept up to date on every change, so that matching starts from a
few candidates instead of the whole graph: per kind and label, the live ids (a list with
positions, for a uniform random pick in O(1), and a heap, for the oldest in O(log n)); per
vertex, its incident edges and faces. Nothing is ever copied: a step edits the host in place.
"""

from __future__ import annotations

import heapq
import math


class Element:
    __slots__ = ("id", "kind", "label", "attrs", "gen", "ends")

    def __init__(self, id: int, kind: str, label: str, attrs: dict, gen: int, ends: tuple):
        self.id, self.kind, self.label, self.attrs, self.gen, self.ends = \
            id, kind, label, attrs, gen, ends


class LabelIndex:
    """The live ids of one kind and label."""

    __slots__ = ("items", "where", "heap")

    def __init__(self):
        self.items: list[int] = []
        self.where: dict[int, int] = {}
        self.heap: list[int] = []

    def add(self, i: int) -> None:
        self.where[i] = len(self.items)
        self.items.append(i)
        heapq.heappush(self.heap, i)

    def remove(self, i: int) -> None:
        k = self.where.pop(i)
        last = self.items.pop()
        if last != i:
            self.items[k] = last
            self.where[last] = k
        # the heap is cleaned lazily, in oldest()

    def oldest(self) -> int | None:
        heap = self.heap
        while heap and heap[0] not in self.where:
            heapq.heappop(heap)
        return heap[0] if heap else None

    def in_age_order(self):
        return sorted(self.items)

    def __len__(self) -> int:
        return len(self.items)


class FreeHost:
    def __init__(self, defaults: dict[str, dict] | None = None):
        # kind → declared attribute → default; an element's own attrs hold what was set
        self.defaults = defaults or {"vertex": {}, "edge": {}, "face": {}}
        self.elements: dict[int, Element] = {}
        self.index: dict[tuple[str, str], LabelIndex] = {}
        self.incident: dict[int, dict[int, None]] = {}      # vertex → edges and faces on it
        self.counts = {"vertex": 0, "edge": 0, "face": 0}
        self._next = 0

    def labelled(self, kind: str, label: str | None) -> LabelIndex | list[LabelIndex]:
        if label is not None:
            return self.index.get((kind, label)) or LabelIndex()
        return [ix for (k, _), ix in sorted(self.index.items()) if k == kind]

    def add(self, kind: str, label: str, attrs: dict, gen: int, ends: tuple = ()) -> Element:
        """A new element; the ends of an edge or the corners of a face are distinct vertices
        (the loader checks that every side names them so)."""
        i = self._next
        self._next = i + 1
        el = Element(i, kind, label, attrs, gen, ends)
        self.elements[i] = el
        ix = self.index.get((kind, label))
        if ix is None:
            ix = self.index[(kind, label)] = LabelIndex()
        ix.add(i)
        self.counts[kind] += 1
        if kind == "vertex":
            self.incident[i] = {}
        incident = self.incident
        for v in ends:
            incident[v][i] = None
        return el

    def remove(self, i: int) -> None:
        el = self.elements.pop(i)
        self.index[(el.kind, el.label)].remove(i)
        self.counts[el.kind] -= 1
        for v in el.ends:
            self.incident[v].pop(i, None)
        if el.kind == "vertex":
            del self.incident[i]

    def relabel(self, i: int, label: str) -> None:
        el = self.elements[i]
        if el.label != label:
            self.index[(el.kind, el.label)].remove(i)
            el.label = label
            self.index.setdefault((el.kind, label), LabelIndex()).add(i)

    @property
    def size(self) -> int:
        return len(self.elements)

    # -- derived values, as expressions see them (free_rules.DERIVED) --

    def pos(self, v: int) -> tuple[float, float]:
        a = self.elements[v].attrs
        return (a["x"], a["y"])

    def value(self, el: Element, key: str):
        """An attribute as expressions see it: set on the element, else the declared default,
        else a built-in value."""
        if key in el.attrs:
            return el.attrs[key]
        defaults = self.defaults[el.kind]
        return defaults[key] if key in defaults else self.derived(el, key)

    def attributes(self, el: Element) -> dict:
        """Every declared attribute of the element, with what was set on it."""
        return {**self.defaults[el.kind], **el.attrs}

    def derived(self, el: Element, key: str):
        if key == "label":
            return el.label
        if key == "generation":
            return float(el.gen)
        if el.kind == "vertex":
            if key == "pos":
                return (el.attrs["x"], el.attrs["y"])
            if key == "degree":
                return float(sum(1 for k in self.incident[el.id]
                                 if self.elements[k].kind == "edge"))
        elif el.kind == "edge":
            (ax, ay), (bx, by) = self.pos(el.ends[0]), self.pos(el.ends[1])
            if key == "vec":
                return (bx - ax, by - ay)
            if key == "mid":
                return ((ax + bx) / 2, (ay + by) / 2)
            if key == "length":
                return math.hypot(bx - ax, by - ay)
            if key == "angle":
                return math.degrees(math.atan2(by - ay, bx - ax))
        else:
            pts = [self.pos(v) for v in el.ends]
            if key == "sides":
                return float(len(pts))
            area = 0.5 * sum(p[0] * q[1] - q[0] * p[1] for p, q in zip(pts, pts[1:] + pts[:1]))
            if key == "area":
                return area
            if key == "centre":
                return (sum(p[0] for p in pts) / len(pts), sum(p[1] for p in pts) / len(pts))
        raise KeyError(key)
