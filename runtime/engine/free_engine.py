"""Run hand-written productions (grammar_lang.free_rules) on an attributed host graph.

A step takes the lowest priority level that has not reached its limit and has an applicable
production; among its productions one is drawn by weight, a match is found (free_match), the
conditions are checked, a daughter is drawn by weight, the `let`s and `set`s are evaluated
against the match as it is, the new vertices are placed, and only then is the host edited: so a
step that fails (an evaluation error, a coordinate that is not finite, a dangling edge in DPO)
changes nothing, and its reason is counted. Positions of new vertices without a `set` come
from their pattern positions carried by the similarity (barycentre, rotation by total least
squares, scale by extent) that takes the mother graph's pattern onto the match (§4.3).
"""

from __future__ import annotations

import math
import random
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from grammar_lang.expr_eval import Scope, compile_expr
from grammar_lang.expr_functions import EvalError
from grammar_lang.free_rules import Daughter, FSide, Production
from grammar_lang.diagnostics import error
from grammar_lang.ggr_free import MAX_COORDINATE, context_of, edge_key, face_key, lhs_scope
from grammar_lang.rules import Grammar

from .free_host import Element, FreeHost
from .free_match import Binding, Matcher
from .generate import MAX_STALL, Summary
from ..geometry.rejections import Rejection

MATCH_TRIES = 64    # matches tried per production and step before it counts as not applicable


class _Reject(Exception):
    """This match cannot be rewritten; the reason (a Rejection) is counted."""

    def __init__(self, reason: Rejection, detail: str = ""):
        super().__init__(f"{reason}: {detail}" if detail else str(reason))
        self.reason = reason


class _Env:
    __slots__ = ("host", "elements", "values", "rng")

    def __init__(self, host: FreeHost, elements: dict[str, Element], rng):
        self.host, self.elements, self.values, self.rng = host, elements, {}, rng

    def get(self, name: str, key: str):
        el = self.elements[name]
        attrs = el.attrs
        return attrs[key] if key in attrs else self.host.value(el, key)


@dataclass
class _Compiled:
    production: Production
    matcher: Matcher
    conditions: tuple
    lets: tuple
    daughters: tuple        # a _Shape for each daughter


class FreeEngine:
    def __init__(self, grammar: Grammar, seed: int = 0, limits: dict[int, int] | None = None):
        self.grammar = grammar
        # Declared attributes are not copied into elements: an element holds what was set on
        # it, and the host falls back to the defaults (so a decoration can beat a default).
        self.defaults = {k: {a.name: a.value for a in grammar.header.attributes if a.kind == k}
                         for k in ("vertex", "edge", "face")}
        self.limits = dict(limits or {})
        self.context = context_of(grammar.header)
        self.compiled = [self._compile(p) for p in grammar.productions]
        self.levels = sorted({p.priority for p in grammar.productions})
        self.by_level = {level: [c for c in self.compiled if c.production.priority == level]
                         for level in self.levels}
        self.dpo = grammar.header.mode == "dpo"
        self.reset(seed)

    def reset(self, seed: int) -> None:
        self.rng = random.Random(seed)
        self.host = FreeHost(self.defaults)
        self.step_no = 0
        self.applied: dict[int, int] = {}
        self.reasons: dict[Rejection, int] = {}
        self.last_error = ""        # the last rejection, in words, for the summary
        if self.grammar.start is not None:
            start = self._compile(self.grammar.start)
            env = _Env(self.host, {}, self.rng)
            try:
                self._rewrite(start, start.daughters[0], Binding({}, [], [], set()), env)
            except (EvalError, _Reject) as exc:
                raise error(f"the start graph cannot be built: {exc}",
                            grammar_start_span(self.grammar)) from None

    # -- compilation --

    def _compile(self, p: Production) -> _Compiled:
        scope = lhs_scope(p.lhs, self.context)
        conditions = tuple(self._fn(c.expr, lhs_scope(p.lhs, self.context))
                           for c in p.conditions)
        lets = tuple((l.name, self._fn(l.expr, scope, l.name, l.type)) for l in p.lets)
        daughters = []
        for d in p.daughters:
            local = Scope(dict(scope.variables), scope.elements)
            dl = tuple((l.name, self._fn(l.expr, local, l.name, l.type)) for l in d.lets)
            sets = tuple((a.element, a.key, self._fn(a.expr, local)) for a in d.sets)
            daughters.append(_Shape.of(d, p.lhs, dl, sets))
        return _Compiled(p, Matcher(p.lhs, p.match == "oldest"), conditions, lets,
                         tuple(daughters))

    @staticmethod
    def _fn(expr, scope: Scope, define: str | None = None, t=None):
        # Types were checked when the file loaded; this builds the closures again.
        _, fn = compile_expr(expr, scope)
        if define is not None:
            scope.variables[define] = t
        return fn

    # -- running --

    def run(self, steps: int, progress: Callable[[Summary], None] | None = None,
            per_step: list | None = None, stop: Callable[[], bool] | None = None) -> Summary:
        """Up to `steps` steps; `stop()` is asked between steps (Ctrl-C, runtime.interrupt)."""
        s = Summary()
        t0 = time.perf_counter()
        stall = 0
        s.stop = f"reached {steps} steps"
        while s.applied < steps:
            if stop is not None and stop():
                s.stop = "interrupted (Ctrl-C)"
                break
            result = self.step()
            s.proposals += 1
            if result is None:
                s.stop = "no production applies (terminal graph)"
                break
            if result:
                s.applied += 1
                stall = 0
                if per_step is not None:
                    per_step.append((time.perf_counter(), self.host.size))
                if progress is not None and s.applied % 16 == 0:
                    progress(self.summary(s))
            else:
                stall += 1
                if stall >= MAX_STALL:
                    s.stop = f"{MAX_STALL} rejected steps in a row (the last: {self.last_error})"
                    break
        s.seconds = time.perf_counter() - t0
        return self.summary(s)

    def summary(self, s: Summary) -> Summary:
        s.reasons = dict(sorted(self.reasons.items()))
        s.rejected = sum(self.reasons.values())
        s.vertices, s.edges = self.host.counts["vertex"], self.host.counts["edge"]
        return s

    def step(self) -> bool | None:
        """Apply one production. True: applied; False: every match tried was rejected;
        None: nothing applies (or every level is at its limit)."""
        rejected = False
        for level in self.levels:
            if self.applied.get(level, 0) >= self.limits.get(level, math.inf):
                continue
            todo = list(self.by_level[level])
            while todo:
                c = self._draw(todo)
                todo.remove(c)
                outcome = self._try(c)
                if outcome:
                    self.applied[level] = self.applied.get(level, 0) + 1
                    self.step_no += 1
                    return True
                rejected = rejected or outcome is False
            if rejected:
                return False
        return False if rejected else None

    def _draw(self, todo: list[_Compiled]) -> _Compiled:
        return self._weighted(todo, [c.production.weight for c in todo])

    def _weighted(self, items: list, weights: list[float]):
        """One of `items`, drawn with probability proportional to its weight."""
        total = sum(weights)
        if len(items) == 1 or total <= 0:
            return items[0]
        x = self.rng.random() * total
        for item, w in zip(items, weights):
            x -= w
            if x < 0:
                return item
        return items[-1]

    def _try(self, c: _Compiled) -> bool | None:
        """True: applied; False: matches existed but each was rejected; None: no match."""
        found = False
        for k, b in enumerate(c.matcher.matches(self.host, self.rng)):
            if k >= MATCH_TRIES:
                break
            env = _Env(self.host, self._elements(c.production.lhs, b), self.rng)
            try:
                if not all(fn(env) for fn in c.conditions):
                    continue
                for name, fn in c.lets:
                    env.values[name] = fn(env)
                if c.production.spatial and not _spatial_ok(c.production.lhs, b, self.host):
                    continue
                found = True
                self._rewrite(c, self._pick(c), b, env)
                return True
            except (EvalError, _Reject) as exc:
                found = True
                reason = exc.reason if isinstance(exc, _Reject) else Rejection.EVALUATION
                self.reasons[reason] = self.reasons.get(reason, 0) + 1
                self.last_error = str(exc) if isinstance(exc, _Reject) else f"{reason}: {exc}"
        return False if found else None

    def _pick(self, c: _Compiled) -> "_Shape":
        return self._weighted(c.daughters, [d.weight for d in c.production.daughters])

    def _elements(self, lhs: FSide, b: Binding) -> dict[str, Element]:
        elements = self.host.elements
        els = {name: elements[i] for name, i in b.vertices.items()}
        if b.edges or b.faces:
            for e, i in zip(lhs.edges, b.edges):
                if e.name:
                    els[e.name] = elements[i]
            for f, i in zip(lhs.faces, b.faces):
                if f.name:
                    els[f.name] = elements[i]
        return els

    # -- rewriting --

    def _rewrite(self, c: _Compiled, daughter: "_Shape", b: Binding, env: _Env) -> None:
        for name, fn in daughter.lets:
            env.values[name] = fn(env)
        values = [(el, key, fn(env)) for el, key, fn in daughter.sets]
        placed = self._place(daughter, c.production.lhs, b, values)
        doomed = self._doomed(daughter, b)
        if not (doomed or daughter.grows or self._changes(daughter, b, values)):
            raise _Reject(Rejection.NO_CHANGE, "the match would stay as it was")
        self._edit(daughter, b, values, placed, doomed)

    def _place(self, d: "_Shape", lhs: FSide, b: Binding, values) -> dict[str, list[float]]:
        pos: dict[str, list[float]] = {}
        for el, key, value in values:
            if key in ("x", "y", "pos") and el in d.kept:
                p = pos.setdefault(el, [math.nan, math.nan])
                if key == "pos":
                    p[0], p[1] = value
                else:
                    p[0 if key == "x" else 1] = value
        auto = [(name, pattern) for name, _, pattern in d.new
                if name not in pos or math.isnan(pos[name][0]) or math.isnan(pos[name][1])]
        if auto:
            transform = _similarity(lhs, b, self.host)
            for name, pattern in auto:
                p = pos.setdefault(name, [math.nan, math.nan])
                q = transform(pattern)
                p[0] = q[0] if math.isnan(p[0]) else p[0]
                p[1] = q[1] if math.isnan(p[1]) else p[1]
        for name, p in pos.items():
            if d.kept[name]:        # a kept vertex moves only along what is set
                old = self.host.pos(b.vertices[name])
                p[0] = old[0] if math.isnan(p[0]) else p[0]
                p[1] = old[1] if math.isnan(p[1]) else p[1]
            if not (math.isfinite(p[0]) and math.isfinite(p[1])
                    and abs(p[0]) <= MAX_COORDINATE and abs(p[1]) <= MAX_COORDINATE):
                raise _Reject(Rejection.COORDINATE, f"({p[0]:g}, {p[1]:g}) is not within ±1e12")
        return pos

    def _doomed(self, d: "_Shape", b: Binding) -> list[int]:
        """Host ids of the match that the daughter does not keep, edges and faces first."""
        out = [b.edges[k] for k in d.doomed_edges] + [b.faces[k] for k in d.doomed_faces]
        if not d.gone:
            return out
        gone = [b.vertices[name] for name in d.gone]
        dead = set(out)
        for v in gone:
            dangling = [k for k in self.host.incident[v] if k not in dead]
            if dangling and self.dpo:
                raise _Reject(Rejection.DANGLING, "a deleted vertex has edges outside the match")
            out += dangling     # SPO: they go with it
            dead.update(dangling)
        return out + gone

    def _changes(self, d: "_Shape", b: Binding, values) -> bool:
        """Whether a daughter that adds and deletes nothing still changes something."""
        host = self.host
        if any(host.elements[b.vertices[name]].label != label for name, label in d.relabel):
            return True
        if any(host.elements[b.edges[k]].label != e[3] for e in d.edges for k in [e[5]]):
            return True
        if any(host.elements[b.faces[k]].label != f[2] for f in d.faces for k in [f[3]]):
            return True
        els = self._elements(d.lhs, b)
        return any(el not in els or env_value(host, els[el], key) != value
                   for el, key, value in values)

    def _edit(self, d: "_Shape", b: Binding, values, placed, doomed) -> None:
        host, gen = self.host, self.step_no
        for i in doomed:
            if i in host.elements:
                host.remove(i)
        ids = dict(b.vertices)
        for name, label in d.relabel:
            host.relabel(ids[name], label)
        for name, label, _ in d.new:
            attrs = {"x": placed[name][0], "y": placed[name][1]}
            ids[name] = host.add("vertex", label, attrs, gen).id
        for name, p in placed.items():
            if d.kept[name]:
                attrs = host.elements[ids[name]].attrs
                attrs["x"], attrs["y"] = p
        named = self._edges_and_faces(d, b, ids, gen)
        for el, key, value in values:
            if key not in ("x", "y", "pos"):
                host.elements[named[el]].attrs[key] = value

    def _edges_and_faces(self, d: "_Shape", b: Binding, ids: dict, gen: int) -> dict:
        host, named = self.host, ids
        for name, u, v, label, directed, old in d.edges:
            if old is None:
                i = host.add("edge", label, {}, gen, (ids[u], ids[v])).id
            else:
                i = b.edges[old]
                host.relabel(i, label)
            if name:
                named[name] = i
        for name, cycle, label, old in d.faces:
            if old is None:
                i = host.add("face", label, {}, gen,
                             tuple(ids[n] for n in cycle)).id
            else:
                i = b.faces[old]
                host.relabel(i, label)
            if name:
                named[name] = i
        return named


@dataclass(frozen=True)
class _Shape:
    """A daughter, worked out once against its mother graph: what is kept, made and deleted."""

    lhs: FSide
    lets: tuple
    sets: tuple
    kept: dict            # daughter vertex name → kept from the lhs?
    new: tuple            # (name, label, pattern) of each new vertex
    relabel: tuple        # (name, label) of each kept, non-wildcard vertex
    gone: tuple           # lhs vertex names not in the daughter
    doomed_edges: tuple   # indices into lhs.edges / lhs.faces of what is not kept
    doomed_faces: tuple
    edges: tuple          # (name, u, v, label, directed, lhs index if kept, else None)
    faces: tuple          # (name, cycle, label, lhs index if kept, else None)
    grows: bool           # whether it makes or deletes something, whatever the match

    @staticmethod
    def of(d: Daughter, lhs: FSide, lets, sets) -> "_Shape":
        old_e = {(edge_key(e), e.directed): k for k, e in enumerate(lhs.edges)}
        old_f = {face_key(f): k for k, f in enumerate(lhs.faces)}
        edges = tuple((e.name, e.u, e.v, e.label, e.directed, old_e.get((edge_key(e), e.directed)))
                      for e in d.side.edges)
        faces = tuple((f.name, f.cycle, f.label, old_f.get(face_key(f))) for f in d.side.faces)
        kept_e = {e[5] for e in edges} - {None}
        kept_f = {f[3] for f in faces} - {None}
        new = tuple((v.name, v.label, v.pattern) for v in d.side.vertices if not v.kept)
        gone = tuple(v.name for v in lhs.vertices if d.side.vertex(v.name) is None)
        doomed_e = tuple(k for k in range(len(lhs.edges)) if k not in kept_e)
        doomed_f = tuple(k for k in range(len(lhs.faces)) if k not in kept_f)
        grows = bool(new or gone or doomed_e or doomed_f or any(e[5] is None for e in edges)
                     or any(f[3] is None for f in faces))
        return _Shape(lhs, lets, sets, {v.name: v.kept for v in d.side.vertices}, new,
                      tuple((v.name, v.label) for v in d.side.vertices
                            if v.kept and v.label is not None),
                      gone, doomed_e, doomed_f, edges, faces, grows)


def grammar_start_span(grammar: Grammar):
    sets = grammar.start.daughters[0].sets if grammar.start else ()
    return sets[0].span if sets else None


def env_value(host: FreeHost, el: Element, key: str):
    if key == "pos":
        return host.pos(el.id)
    return el.attrs[key] if key in el.attrs else host.value(el, key)


def _similarity(lhs: FSide, b: Binding, host: FreeHost):
    """The map from pattern positions onto the host that takes the mother's pattern onto its
    match: barycentre to barycentre, principal directions (total least squares) aligned, and
    scaled by the ratio of extents. With one point it is a translation."""
    names = [v.name for v in lhs.vertices if v.pattern is not None and v.name in b.vertices]
    if not names:
        return lambda p: (p[0], p[1])       # a start graph: pattern positions are positions
    pat = np.array([lhs.vertex(n).pattern for n in names], dtype=float)
    got = np.array([host.pos(b.vertices[n]) for n in names], dtype=float)
    cp, cg = [float(x) for x in pat.mean(axis=0)], [float(x) for x in got.mean(axis=0)]
    ext_p, ext_g = _extent(pat), _extent(got)
    if len(names) < 2 or ext_p == 0 or ext_g == 0:
        return lambda p: (p[0] - cp[0] + cg[0], p[1] - cp[1] + cg[1])
    turn = _direction(got - np.array(cg)) - _direction(pat - np.array(cp))
    k = ext_g / ext_p
    c, s = k * math.cos(turn), k * math.sin(turn)

    def carry(p):
        dx, dy = p[0] - cp[0], p[1] - cp[1]
        return (cg[0] + c * dx - s * dy, cg[1] + s * dx + c * dy)
    return carry


def _extent(pts: np.ndarray) -> float:
    return float(np.max(np.linalg.norm(pts[:, None, :] - pts[None, :, :], axis=-1)))


def _direction(centred: np.ndarray) -> float:
    """The angle of the principal axis (total least squares), signed so that the first point
    lies on its negative side (or, failing that, the second on its positive side)."""
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    axis = vt[0]
    proj = centred @ axis
    if proj[0] > 1e-12 or (abs(proj[0]) <= 1e-12 and proj[-1] < 0):
        axis = -axis
    return math.atan2(axis[1], axis[0])


def _spatial_ok(lhs: FSide, b: Binding, host: FreeHost) -> bool:
    """Matched vertices keep the order of the pattern positions along x and along y."""
    pts = [(v.pattern, host.pos(b.vertices[v.name])) for v in lhs.vertices
           if v.pattern is not None]
    for i, (p, q) in enumerate(pts):
        for p2, q2 in pts[i + 1:]:
            for axis in (0, 1):
                dp, dq = p2[axis] - p[axis], q2[axis] - q[axis]
                if (dp > 0 and dq <= 0) or (dp < 0 and dq >= 0):
                    return False
    return True
