"""The REPL's commands: one function per command, and its help text.

A command gets the session and its words; it prints through `session.out`, raises `UserError`
for anything the user got wrong, and returns False when it ran but did not succeed (a rule that
could not be placed, a drawing that fails `check`), so that scripts exit non-zero.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from grammar_lang import boundary as bd
from grammar_lang.diagnostics import did_you_mean, error
from grammar_lang.graph import Side, face_walk

from ..output.drawing import load_drawing
from ..engine.matching import find_match
from ..geometry.rejections import Rejection
from .session import Quit, Session
from ..verifier import check_drawing

# How many matches, components or failures a listing shows before summing up the rest.
SHOWN = 20
# `matches` counts up to this many; more are reported as "at least".
COUNT_CAP = 1000


@dataclass(frozen=True)
class Command:
    name: str
    run: Callable[[Session, list[str]], bool | None]
    usage: str
    summary: str
    details: str = ""
    complete: str = ""          # what its arguments are: "rule", "file", "command", "watch"


COMMANDS: dict[str, Command] = {}
ALIASES = {"exit": "quit", "?": "help", "q": "quit"}


def command(usage: str, summary: str, details: str = "", complete: str = ""):
    def register(fn):
        name = usage.split()[0]
        COMMANDS[name] = Command(name, fn, usage, summary, details, complete)
        return fn
    return register


def dispatch(session: Session, words: list[str]) -> bool | None:
    name = ALIASES.get(words[0], words[0])
    cmd = COMMANDS.get(name)
    if cmd is None:
        raise error(f"unknown command '{words[0]}'", None,
                    did_you_mean(words[0], list(COMMANDS) + list(ALIASES))
                    or "'help' lists the commands")
    return cmd.run(session, words[1:])


# --- argument helpers ---------------------------------------------------------------------------

def _flags(args: list[str], cmd: str, known: tuple[str, ...]) -> tuple[list[str], set[str]]:
    """Positional words and the set of flags given; an unknown flag is an error."""
    pos, flags = [], set()
    for a in args:
        if a.startswith("--"):
            if a not in known:
                raise error(f"{cmd}: unknown option '{a}'", None,
                            did_you_mean(a, known) or _usage_hint(cmd))
            flags.add(a)
        else:
            pos.append(a)
    return pos, flags


def _usage_hint(cmd: str) -> str:
    return f"usage: {COMMANDS[cmd].usage}"


def _arity(args: list[str], cmd: str, lo: int, hi: int) -> None:
    if not lo <= len(args) <= hi:
        what = "too many arguments" if len(args) > hi else "missing argument"
        raise error(f"{cmd}: {what}", None, _usage_hint(cmd))


def _whole(text: str, cmd: str, what: str, minimum: int = 0) -> int:
    try:
        value = int(text)
    except ValueError:
        raise error(f"{cmd}: {what} '{text}' is not a whole number", None,
                    _usage_hint(cmd)) from None
    if value < minimum:
        raise error(f"{cmd}: {what} must be at least {minimum}", None, _usage_hint(cmd))
    return value


def _path(text: str, cmd: str, suffixes: tuple[str, ...], other: str) -> str:
    if Path(text).suffix.lower() not in suffixes:
        raise error(f"{cmd}: '{text}' does not end in {' or '.join(suffixes)}", None, other)
    return text


def _tokens(tokens, names) -> str:
    """A boundary string with a space between items: label names are often several letters."""
    return " ".join(bd.format_tokens((t,), names) for t in tokens)


def _num(x: float) -> str:
    text = f"{x:.3f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _pt(p) -> str:
    return f"({_num(p[0])}, {_num(p[1])})"


_PLURAL = {"vertex": "vertices", "match": "matches"}


def _n(count: int, word: str) -> str:
    return f"{count} {word if count == 1 else _PLURAL.get(word, word + 's')}"


def _state(session: Session) -> str:
    h = session.engine.host
    return f"{_n(len(h), 'vertex')}, {_n(h.n_edges, 'edge')}"


def _step_name(rec) -> str:
    return rec.rule + ("" if rec.forward else " (backward)")


# --- the grammar ------------------------------------------------------------------------------

@command("load FILE", "load a grammar (.ggr) or compile an example (.gg, .svg)",
         "Starts a new session on that grammar, with an empty drawing and the seed last set.\n"
         "The current session stays as it was if the file cannot be loaded.", "file")
def _load(session: Session, args: list[str]):
    _arity(args, "load", 1, 1)
    session.load(args[0])
    session.out.line(f"loaded {session.name}: {len(session.grammar.rules)} rules")
    session.changed()


@command("rules", "the rules: boundary strings, priorities and weights",
         "Sides are given as vertices/edges. Forward applies lhs → rhs, backward rhs → lhs;\n"
         "a starter (empty rhs) creates a component backward and deletes one forward.")
def _rules(session: Session, args: list[str]):
    _arity(args, "rules", 0, 0)
    e = session.need_engine()
    g = session.grammar
    names = [l.name for l in g.header.labels]
    scheduled = Counter(m.rule.name for m in e.moves())
    width = max((len(r.name) for r in g.rules), default=4)
    session.out.line(f"{'rule':<{width}}  prio  weight  lhs    rhs    boundary", style="bold")
    for r in g.rules:
        b = _tokens(r.lhs.tokens(g.rings), names) or "ε"
        note = "  starter" if r.is_starter else ""
        if not scheduled[r.name]:
            note += "  (never scheduled: weight 0)"
        session.out.line(f"{r.name:<{width}}  {r.priority:>4}  {_num(r.weight):>6}  "
                         f"{_size(r.lhs):<5}  {_size(r.rhs):<5}  {b}{note}")
    mode = "both directions" if any(not m.forward for m in e.moves()) else "forward only"
    session.out.line(f"{len(g.rules)} rules, {g.header.mode}; step and run use them {mode}")


def _size(side: Side) -> str:
    return f"{len(side.vertices)}/{len(side.edges)}"


@command("primitives", "the primitives: each one's ring of half-edges, and how many are drawn")
def _primitives(session: Session, args: list[str]):
    _arity(args, "primitives", 0, 0)
    e = session.need_engine()
    h = session.grammar.header
    names = [l.name for l in h.labels]
    width = max((len(p.name) for p in h.primitives), default=4)
    for k, p in enumerate(h.primitives):
        session.out.line(f"{p.name:<{width}}  {len(e.host.by_prim[k]):>5} drawn  "
                         f"{_tokens(p.ring, names)}")


# --- matching and rewriting -------------------------------------------------------------------

def _move(session: Session, args: list[str], cmd: str, hi: int):
    pos, flags = _flags(args, cmd, ("--backward",))
    _arity(pos, cmd, 1, hi)
    rule = session.rule(pos[0])
    return session.directed(rule, "--backward" not in flags), pos[1:]


def _describe(session: Session, move, m) -> str:
    h = session.engine.host
    side = move.pattern.side
    if not side.vertices and not side.wires:
        return "anywhere: a new component"
    parts = [f"{side.vertex_name(v)}=v{hv}" for v, hv in enumerate(m.vmap)]
    parts += [f"wire{k}=v{a[0]}–v{b[0]}" for k, (a, b) in enumerate(m.wmap)]
    pts = [h.pos[v] for v in m.vmap] + [h.pos[s[0]] for pair in m.wmap for s in pair]
    at = (sum(p[0] for p in pts) / len(pts), sum(p[1] for p in pts) / len(pts))
    return " ".join(parts) + f"  at {_pt(at)}"


@command("matches RULE [--backward]", "number the places RULE can be applied",
         "Forward matches the rule's lhs, --backward its rhs. The numbers are what 'apply'\n"
         f"takes; the first {SHOWN} are listed, and up to {COUNT_CAP} are counted.", "rule")
def _matches(session: Session, args: list[str]):
    move, _ = _move(session, args, "matches", 1)
    found = session.engine.matches(move, COUNT_CAP)
    for k, m in enumerate(found[:SHOWN]):
        session.out.line(f"{k + 1:>4}  {_describe(session, move, m)}")
    more = "at least " if len(found) >= COUNT_CAP else ""
    rest = f" (first {SHOWN} shown)" if len(found) > SHOWN else ""
    session.out.line(f"{move.name}: {more}{_n(len(found), 'match')}{rest}")


@command("apply RULE [MATCH] [--backward]", "apply RULE at a numbered match (else a random one)",
         "Places the new part as generation does (the engine's geometry), without the cost;\n"
         "fails, changing nothing, when no placement is found. MATCH is a number from\n"
         "'matches RULE'.", "rule")
def _apply(session: Session, args: list[str]):
    move, rest = _move(session, args, "apply", 2)
    e = session.engine
    if rest:
        k = _whole(rest[0], "apply", "MATCH", 1)
        found = e.matches(move, k)
        if len(found) < k:
            raise error(f"{move.name} has {len(found)} matches, not {k}", None,
                        f"'matches {move.rule.name}"
                        f"{'' if move.forward else ' --backward'}' lists them")
        match = found[k - 1]
    else:
        match = find_match(e.host, move.pattern, e.rng, e.schedule.spo)
        if match is None:
            raise error(f"{move.name} does not match anywhere", None,
                        "'rules' lists the rules; try the other direction with --backward"
                        if move.forward else "'rules' lists the rules")
    outcome = e.apply(move, match, use_cost=False)
    if outcome.applied is None:
        session.out.problem(f"could not place {move.name} there: {outcome.reason}\n"
                            "  hint: try another match, or undo to make room")
        return False
    rec = outcome.applied
    session.out.line(f"applied {move.name}: −{len(rec.removed)} +{len(rec.added)} vertices; "
                     f"now {_state(session)}")
    session.changed()


@command("step [N]", "N steps of the schedule, one proposal each, shown one by one (default 1)",
         "Each proposal picks a level, a rule and a match as generation does, asks the cost,\n"
         "and is applied or rejected.")
def _step(session: Session, args: list[str]):
    _arity(args, "step", 0, 1)
    n = _whole(args[0], "step", "N", 1) if args else 1
    e = session.need_engine()
    try:
        for k in range(n):
            out = e.step()
            if out.reason == Rejection.TERMINAL:
                session.out.line("no rule applies: the drawing is terminal")
                break
            rec = out.applied
            if rec is None:
                # The match is still there to describe, as nothing was changed.
                session.out.line(f"{k + 1:>4}  {out.move.name} rejected ({out.reason}): "
                                 f"{_describe(session, out.move, out.match)}", style="dim")
            else:
                session.out.line(f"{k + 1:>4}  {_step_name(rec)}: −{len(rec.removed)} "
                                 f"+{len(rec.added)} vertices; now {_state(session)}")
            session.check_interrupt()
    finally:
        session.changed()


@command("run N", "apply N steps, as 'ggrun --steps N' does, and sum up",
         "Stops early on a terminal drawing or after a long run of rejected proposals.")
def _run(session: Session, args: list[str]):
    _arity(args, "run", 1, 1)
    n = _whole(args[0], "run", "N", 0)
    e = session.need_engine()
    try:
        s = e.run(n, session.check_interrupt, every=1)
    finally:
        session.changed()
    why = ", ".join(f"{k} {v}" for k, v in sorted(s.reasons.items()))
    session.out.line(f"{s.applied} steps applied, {s.rejected} rejected"
                     f"{' (' + why + ')' if why else ''}; now {_state(session)}")
    if not s.stop.startswith("reached"):
        session.out.line(f"stopped early: {s.stop}")


def _times(args: list[str], cmd: str) -> int | None:
    _arity(args, cmd, 0, 1)
    if args and args[0] == "all":
        return None
    return _whole(args[0], cmd, "N", 1) if args else 1


@command("undo [N|all]", "take back the last N changes (default 1)",
         "Every change is undoable: rule applications, steps, reset and open.")
def _undo(session: Session, args: list[str]):
    return _walk(session, _times(args, "undo"), "undo")


@command("redo [N|all]", "apply again what undo took back")
def _redo(session: Session, args: list[str]):
    return _walk(session, _times(args, "redo"), "redo")


def _walk(session: Session, n: int | None, cmd: str):
    e = session.need_engine()
    take = e.undo if cmd == "undo" else e.redo
    done = []
    while n is None or len(done) < n:
        rec = take()
        if rec is None:
            break
        done.append(rec)
    if done:
        session.changed()
    verb = "undid" if cmd == "undo" else "redid"
    for rec in done[:SHOWN // 4]:
        session.out.line(f"{verb} {_step_name(rec)}")
    if len(done) > SHOWN // 4:
        session.out.line(f"{verb} {len(done) - SHOWN // 4} more")
    left = len(e.history) if cmd == "undo" else len(e.redo_stack)
    session.out.line(f"now {_state(session)}; {left} more to {cmd}")
    if not done and n is not None:
        session.out.problem(f"nothing to {cmd}" + (" (this is the start)" if cmd == "undo" else "")
                            + f"\n  hint: 'show' shows the drawing; '{cmd} all' never fails")
        return False


@command("reset", "start over from an empty drawing with the current seed (undoable)")
def _reset(session: Session, args: list[str]):
    _arity(args, "reset", 0, 0)
    e = session.need_engine()
    _replace(session, "reset", [])
    e.reseed(e.seed)
    session.out.line(f"reset: empty drawing, seed {e.seed}; 'undo' brings the drawing back")


def _replace(session: Session, name: str, new) -> None:
    """Replace the whole drawing by `new` ((primitive, position) per vertex and glued slot
    pairs by index) as one journaled edit in the engine's history."""
    e = session.engine
    h = e.host
    if not len(h) and not (new and new[0]):
        return
    h.begin()
    try:
        for v, i, _, _ in h.edges():
            h.unglue((v, i))
        for v in h.vertices():
            h.remove_vertex(v)
        if new:
            verts, glued = new
            ids = [h.new_id() for _ in verts]
            for v, (prim, p) in zip(ids, verts):
                h.add_vertex(v, prim, p)
            for (a, i), (b, j) in glued:
                h.glue((ids[a], i), (ids[b], j))
    except BaseException:
        h.undo_ops(h.end())
        raise
    e.record_edit(name, h.end())
    session.changed()


@command("seed N", "seed the random choices from here on (the drawing stays)",
         "'reset' then starts over with this seed; 'load' uses it too.")
def _seed(session: Session, args: list[str]):
    _arity(args, "seed", 1, 1)
    n = _whole(args[0], "seed", "N", 0)
    session.options.seed = n
    if session.engine is not None:
        session.engine.reseed(n)
    session.out.line(f"seed {n}")


# --- looking ----------------------------------------------------------------------------------

@command("show [COMPONENT]", "the drawing: summary, components, boundary strings of open parts",
         "With a component's number: its vertices, each with its primitive, position and\n"
         "neighbours slot by slot ('-' for an open half-edge). Vertex names v12 are the ones\n"
         "'matches' shows.")
def _show(session: Session, args: list[str]):
    _arity(args, "show", 0, 1)
    e = session.need_engine()
    h = e.host
    comps = h.components()
    if args:
        k = _whole(args[0], "show", "COMPONENT", 1)
        if k > len(comps):
            raise error(f"show: there {'is' if len(comps) == 1 else 'are'} "
                        f"{_n(len(comps), 'component')}, not {k}", None,
                        "'show' lists them")
        _show_component(session, comps[k - 1])
        return
    session.out.line(f"{session.name}: {_state(session)}, {_n(len(comps), 'component')}, "
                     f"{_n(h.n_open, 'open half-edge')}; seed {e.seed}; "
                     f"{len(e.history)} to undo, {len(e.redo_stack)} to redo", style="bold")
    by_label = [f"{n} {c}" for n, c in zip(h.t.label_names, h.label_count) if c]
    if by_label:
        session.out.line("edges by label: " + ", ".join(by_label))
    names = list(h.t.label_names)
    for k, comp in enumerate(comps[:SHOWN]):
        xs = [h.pos[v][0] for v in comp]
        ys = [h.pos[v][1] for v in comp]
        n_edges = sum(1 for v in comp for s in h.link[v] if s is not None) // 2
        walks = _open_boundaries(h, comp)
        state = "closed" if not walks else "open"
        session.out.line(f"{k + 1:>4}: {_n(len(comp), 'vertex')}, {_n(n_edges, 'edge')}, "
                         f"{_pt((min(xs), min(ys)))}–{_pt((max(xs), max(ys)))}, {state}")
        for w in walks:
            session.out.line(f"        boundary {_tokens(w, names)}")
    if len(comps) > SHOWN:
        session.out.line(f"… and {len(comps) - SHOWN} more components")


def _show_component(session: Session, comp: list[int]) -> None:
    h = session.engine.host
    prims = session.grammar.header.primitives
    names = list(h.t.label_names)
    for v in comp:
        ring = h.t.rings[h.prim[v]]
        slots = "  ".join(f"{_tokens((t,), names)}→{'-' if s is None else f'v{s[0]}'}"
                          for t, s in zip(ring, h.link[v]))
        session.out.line(f"v{v:<5} {prims[h.prim[v]].name:<8} {_pt(h.pos[v]):<20} {slots}")


def _open_boundaries(h, comp: list[int]) -> list[bd.Tokens]:
    """The boundary string around each face of a component that has open half-edges."""
    local = {v: k for k, v in enumerate(comp)}
    edges = tuple((local[v], i, local[s[0]], s[1]) for v in comp
                  for i, s in enumerate(h.link[v]) if s is not None and (v, i) < s)
    side = Side(tuple(h.prim[v] for v in comp), edges, ())
    rings = h.t.rings
    seen, out = set(), []
    for v in comp:
        for i, s in enumerate(h.link[v]):
            if s is not None or (local[v], i) in seen:
                continue
            walk = face_walk(side, (local[v], i), rings)
            seen.update(slot for slot, _ in walk)
            out.append(bd.canonical(bd.from_gaps((side.slot_token(slot, rings), turns)
                                                 for slot, turns in walk)))
    return out


@command("check", "run the verifier: is the drawing locally similar to the example?",
         "The same check as 'ggrun check'; the command fails when the drawing does not pass.")
def _check(session: Session, args: list[str]):
    _arity(args, "check", 0, 0)
    session.need_engine()
    d = session.drawing()
    failures = check_drawing(session.grammar, d)
    if not failures:
        session.out.line(f"ok: {_state(session)}",
                         style="green")
        return
    for f in failures[:SHOWN]:
        session.out.line(f.render())
    kinds = Counter(f.kind for f in failures)
    session.out.problem(f"failed: {len(failures)} problem(s): "
                        + ", ".join(f"{kinds[k]} {k}" for k in sorted(kinds)))
    return False


# --- files ------------------------------------------------------------------------------------

@command("render FILE.svg", "draw the drawing as SVG", complete="file")
def _render(session: Session, args: list[str]):
    _arity(args, "render", 1, 1)
    path = _path(args[0], "render", (".svg",), "'save FILE.json' writes the drawing as JSON")
    session.need_engine()
    session.render(path)
    session.out.line(f"wrote {path}")


@command("watch [FILE.svg|off]", "re-render FILE.svg after every change",
         "A browser or viewer watching the file then shows each step. 'watch off' stops;\n"
         "'watch' alone says what is watched.", "watch")
def _watch(session: Session, args: list[str]):
    _arity(args, "watch", 0, 1)
    if not args:
        session.out.line(f"watching {session.watch}" if session.watch else "not watching")
        return
    if args[0] == "off":
        session.watch = None
        session.out.line("not watching")
        return
    path = _path(args[0], "watch", (".svg",), "give an .svg file, or 'off'")
    session.need_engine()
    session.render(path)
    session.watch = path
    session.out.line(f"watching {path}")


@command("save FILE.json", "write the drawing as gg-drawing/1 JSON", complete="file")
def _save(session: Session, args: list[str]):
    _arity(args, "save", 1, 1)
    path = _path(args[0], "save", (".json",), "'render FILE.svg' draws it as SVG")
    session.need_engine()
    session.drawing().save(path)
    session.out.line(f"saved {path}: {_state(session)}")


@command("open FILE.json", "replace the drawing by a saved one (undoable)",
         "Reads a gg-drawing/1 file written by 'save' or 'ggrun --out FILE.json': its edges\n"
         "name their labels, which fix each vertex's primitive.", "file")
def _open(session: Session, args: list[str]):
    _arity(args, "open", 1, 1)
    path = _path(args[0], "open", (".json",), "open reads drawings saved as .json")
    session.need_engine()
    new = _from_drawing(session, load_drawing(path), path)
    _replace(session, f"open {Path(path).name}", new)
    session.out.line(f"opened {path}: {_state(session)}")


def _from_drawing(session: Session, d, path: str):
    """(primitive, position) per vertex and glued slots, from a drawing's labelled edges."""
    header = session.grammar.header
    label_id = {l.name: k for k, l in enumerate(header.labels)}
    index = {v.id: k for k, v in enumerate(d.vertices)}
    tokens: list[list[tuple[int, int]]] = [[] for _ in d.vertices]   # (token, edge) per vertex
    for k, edge in enumerate(d.edges):
        if edge.label is None:
            raise error(f"{path}: edge #{k} names no label", None,
                        "open reads drawings written by ggrun ('save', 'ggrun --out x.json')")
        if edge.label not in label_id:
            raise error(f"{path}: edge #{k} has label '{edge.label}', which "
                        f"{session.name} does not have", None,
                        did_you_mean(edge.label, label_id) or "was it made with another grammar?")
        lab = label_id[edge.label]
        # Edges run along their label's unbarred half-edge, from u to v.
        tokens[index[edge.u]].append((bd.half(lab, False), k))
        tokens[index[edge.v]].append((bd.half(lab, True), k))
    rings = [p.ring for p in header.primitives]
    exact = {tuple(sorted(r)): p for p, r in reversed(list(enumerate(rings)))}
    verts, ends = [], {}
    names = [l.name for l in header.labels]
    for k, (v, have) in enumerate(zip(d.vertices, tokens)):
        mine = tuple(sorted(t for t, _ in have))
        prim = exact.get(mine)
        if prim is None:   # an open vertex: the first primitive holding all of its half-edges
            prim = next((p for p, r in enumerate(rings)
                         if not Counter(mine) - Counter(r) and len(set(mine)) == len(mine)), None)
        if prim is None:
            raise error(f"{path}: vertex {v.id} has half-edges "
                        f"{_tokens(mine, names)}, which no primitive has", None,
                        "was it made with another grammar? 'primitives' lists this one's")
        verts.append((prim, (v.x, v.y)))
        for t, e in have:
            ends.setdefault(e, []).append((k, rings[prim].index(t)))
    glued = [tuple(ends[e]) for e in sorted(ends)]
    _check_span(d, index, path)
    return verts, glued


def _check_span(d, index: dict, path: str) -> None:
    """Refuse a drawing far wider than its shortest edge (planar.MAX_SPAN), which the engine
    could not file in its grid."""
    if not d.edges:
        return
    import numpy as np      # the loader's own bound: imported here, when a drawing is opened
    from grammar_lang.planar import MAX_SPAN, span_and_least
    points = np.array([(v.x, v.y) for v in d.vertices], dtype=float)
    segments = np.array([(index[e.u], index[e.v]) for e in d.edges], dtype=int)
    found = span_and_least(points, segments)
    if found is not None and found[0] > MAX_SPAN * found[1]:
        raise error(f"{path}: the drawing spans {found[0]:g}, more than {MAX_SPAN:g} times its "
                    f"shortest edge ({found[1]:g})", None,
                    "was a vertex moved far away by hand? 'ggrun check' lists the drawing's "
                    "problems")


# --- the rest ---------------------------------------------------------------------------------

@command("help [COMMAND]", "list the commands, or explain one", complete="command")
def _help(session: Session, args: list[str]):
    _arity(args, "help", 0, 1)
    if args:
        name = ALIASES.get(args[0], args[0])
        if name not in COMMANDS:
            raise error(f"help: no command '{args[0]}'", None,
                        did_you_mean(args[0], COMMANDS) or "'help' lists the commands")
        c = COMMANDS[name]
        session.out.line(c.usage, style="bold")
        session.out.line(f"  {c.summary}")
        for line in c.details.split("\n") if c.details else ():
            session.out.line(f"  {line}")
        return
    width = max(len(c.usage) for c in COMMANDS.values())
    for c in COMMANDS.values():
        session.out.line(f"{c.usage:<{width}}  {c.summary}")


@command("quit", "leave the REPL (also: exit, end of input)")
def _quit(session: Session, args: list[str]):
    _arity(args, "quit", 0, 0)
    raise Quit()
