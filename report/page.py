"""The report as one self-contained HTML page: no network, no external files, one small inline
script (the filter box). Figures of rules and primitives are inline SVG; drawings made by
runtime.output.svg_out (the example, the gallery) are data-URI images, so that their element ids
cannot clash, and they load lazily. Off-screen cards are not rendered until scrolled to
(`content-visibility`), which keeps a page of hundreds of rules quick to open."""

from __future__ import annotations

import base64
from dataclasses import asdict

from grammar_lang import boundary as bd
from grammar_lang.rules import Grammar, Rule

from .build import Shot, Subject
from .figures import Drafter
from .markup import esc

CSS = """
:root{--fg:#1d2330;--mute:#5b6475;--line:#dde2ea;--bg:#f6f7f9;--ok:#2e7d32;--warn:#b26a00}
*{box-sizing:border-box}
body{margin:0;font:14px/1.45 "DejaVu Sans",Helvetica,Arial,sans-serif;color:var(--fg);background:var(--bg)}
header{padding:20px 28px 12px;background:#fff;border-bottom:1px solid var(--line)}
h1{margin:0 0 4px;font-size:22px} h2{margin:28px 0 10px;font-size:18px}
.sub{color:var(--mute)}
main{padding:0 28px 40px}
nav{position:sticky;top:0;z-index:2;display:flex;gap:16px;align-items:center;flex-wrap:wrap;
 padding:8px 28px;background:#fffffff0;border-bottom:1px solid var(--line)}
nav a{color:var(--fg);text-decoration:none;font-weight:600}
nav input{margin-left:auto;padding:5px 9px;width:260px;border:1px solid #b9c0cc;border-radius:6px;font:inherit}
.verdict{display:inline-block;margin:10px 0 6px;padding:6px 12px;border-radius:6px;font-weight:600;color:#fff}
.verdict.ok{background:var(--ok)} .verdict.limited{background:var(--warn)} .verdict.unknown{background:#6b7280}
table{border-collapse:collapse;background:#fff}
td,th{padding:4px 10px;border-bottom:1px solid var(--line);text-align:left;vertical-align:top}
th{color:var(--mute);font-weight:600}
.facts td:first-child{color:var(--mute)}
.grid{display:flex;flex-wrap:wrap;gap:14px;align-items:flex-start}
.card{background:#fff;border:1px solid var(--line);border-radius:8px;padding:10px 12px;
 content-visibility:auto;contain-intrinsic-size:auto 260px;max-width:100%}
.card h3{margin:0 0 4px;font-size:15px}
.card .fig{overflow:auto} .card svg,.card img{display:block;max-width:100%;height:auto}
.rule .fig svg{max-height:420px;width:auto}
.meta{color:var(--mute);font-size:12.5px} .meta.warn{color:var(--warn)}
.bs{font-family:"DejaVu Sans Mono",monospace;font-size:13px;word-break:break-all}
.chips a{display:inline-block;margin:2px 3px 0 0;padding:0 6px;border-radius:9px;background:#eef1f5;
 color:var(--fg);text-decoration:none;font-size:12px}
.sw{display:inline-block;width:12px;height:12px;border:1px solid #888;border-radius:2px;vertical-align:-1px}
.example img{max-height:560px;width:auto;background:#fff}
.gallery .card{width:320px} .gallery img{width:100%}
[hidden]{display:none!important}
section,.card,tr{scroll-margin-top:60px}
:target{outline:3px solid #f2b705}
"""

SCRIPT = """
const q=document.getElementById('q');
function filter(){const w=q.value.toLowerCase().split(/\\s+/).filter(Boolean);
 for(const el of document.querySelectorAll('[data-search]')){const s=el.dataset.search;
  el.hidden=!w.every(x=>s.includes(x));}}
q.addEventListener('input',filter);
"""


def _data_uri(svg: str) -> str:
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode("utf-8")).decode("ascii")


def rule_tokens(rule: Rule, rings) -> set[int]:
    """Every half-edge token either side of the rule holds (edges, open slots, wires)."""
    out: set[int] = set()
    for side in (rule.lhs, rule.rhs):
        for v, i, _, _ in side.edges:
            out.add(rings[side.vertices[v]][i] & ~1)
        for s in side.open_slots():
            out.add(side.slot_token(s, rings) & ~1)
    return out


TIMES = "<!--times-->"


class Page:
    def __init__(self, subject: Subject, drafter: Drafter, shots: list[Shot], times: bool,
                 gallery_error: str = ""):
        self.s, self.d, self.shots, self.show_times = subject, drafter, shots, times
        self.gallery_error = gallery_error
        self.g: Grammar = subject.grammar
        self.rings = [p.ring for p in self.g.header.primitives]
        self.names = [l.name for l in self.g.header.labels]
        self.uses: dict[int, list[int]] = {k: [] for k in range(len(self.names))}
        for r, rule in enumerate(self.g.rules):
            for tok in sorted(rule_tokens(rule, self.rings)):
                self.uses[tok >> 1].append(r)

    def with_times(self, text: str) -> str:
        """The page with its timing rows filled in (they are known only once it is built)."""
        rows = "".join(f"<tr><td>time: {esc(k)}</td><td>{t:.2f} s</td></tr>"
                       for k, t in self.s.times.items())
        return text.replace(TIMES, rows, 1)

    def fmt(self, tokens) -> str:
        return bd.format_tokens(tokens, self.names)

    def html(self) -> str:
        g, s = self.g, self.s
        title = s.example.name if s.example else (g.header.source or s.path)
        parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
                 '<meta name="viewport" content="width=device-width, initial-scale=1">',
                 f"<title>{esc(title)}: grammar report</title><style>{CSS}</style></head><body>",
                 self._header(title),
                 '<nav><a href="#example">Example</a><a href="#labels">Labels</a>'
                 '<a href="#primitives">Primitives</a><a href="#rules">Rules</a>'
                 + ('<a href="#remaining">Remaining</a>' if s.verdict.remaining else "")
                 + ('<a href="#gallery">Gallery</a>' if self.shots or self.gallery_error else "")
                 + '<input id="q" type="search" placeholder="filter by label, rule or primitive"'
                 ' aria-label="filter"></nav><main>',
                 self._example(), self._labels(), self._primitives(), self._rules(),
                 self._remaining(), self._gallery(), "</main>",
                 f"<script>{SCRIPT}</script></body></html>"]
        return "\n".join(p for p in parts if p) + "\n"

    def _header(self, title: str) -> str:
        v, s = self.s.verdict, self.s
        kind = "ok" if v.complete else ("unknown" if v.complete is None else "limited")
        rows = list(v.counts) + [("mode", self.g.header.mode),
                                 ("limits", ", ".join(f"{k}={val:g}" if val is not None else f"{k}=none"
                                                      for k, val in
                                                      asdict(self.g.header.options.limits).items()))]
        facts = "".join(f"<tr><td>{esc(a)}</td><td>{esc(b)}</td></tr>" for a, b in rows)
        facts += TIMES if self.show_times else ""
        return (f"<header><h1>{esc(title)}</h1><div class=\"sub\">report on {esc(s.path)}; "
                f"rules as in <code>{esc(s.ggr_name)}</code></div>"
                f'<div class="verdict {kind}">{esc(v.text)}</div>'
                f'<table class="facts">{facts}</table></header>')

    def _example(self) -> str:
        ex = self.s.example
        if ex is None or ex.graph is None:
            return ('<section id="example"><h2>Example</h2><p class="meta">The example this '
                    "rule file was compiled from was not found; only the rules are shown.</p>"
                    "</section>")
        from .figures import example_svg
        faces = "".join(
            f'<span class="chips"><span class="sw" style="background:{esc(c or "#fff")}">'
            f"</span> {esc(f)}</span>&nbsp; " for f, c in self.d.pal.faces.items())
        classes = "".join(
            f'<span class="chips"><span class="sw" style="background:{esc(c)}"></span> '
            f"class {esc(n)}</span>&nbsp; " for n, c in self.d.pal.classes.items())
        return (f'<section id="example"><h2>Example</h2><div class="card example">'
                f'<img alt="the example as read" src="{_data_uri(example_svg(ex))}">'
                f'<p class="meta">{len(ex.graph.vertices)} vertices (merged and split points '
                f"included, coloured by primitive), {len(ex.graph.edges)} edges. Faces: {faces}"
                f"<br>Edges: {classes}</p></div></section>")

    def _labels(self) -> str:
        rows = []
        for k, lab in enumerate(self.g.header.labels):
            links = " ".join(f'<a href="#rule-{r}">{esc(self.g.rules[r].name)}</a>'
                             for r in self.uses[k])
            rows.append(
                f'<tr id="label-{k}" data-search="{esc(lab.name.lower())}"><td class="bs">'
                f"{esc(lab.name)}</td><td>{esc(lab.left)}</td><td>{esc(lab.right)}</td>"
                f"<td>{lab.angle:g}°</td><td>{esc(lab.cls)}</td>"
                f'<td class="chips">{links or "—"}</td></tr>')
        return ('<section id="labels"><h2>Edge labels</h2><table><tr><th>label</th><th>left</th>'
                "<th>right</th><th>angle</th><th>class</th><th>rules using it</th></tr>"
                + "".join(rows) + "</table></section>")

    def _primitives(self) -> str:
        cards = []
        for k, p in enumerate(self.g.header.primitives):
            search = " ".join([p.name, *(self.names[t >> 1] for t in p.ring)]).lower()
            cards.append(f'<div class="card" id="prim-{k}" data-search="{esc(search)}">'
                         f"<h3>{esc(p.name)}</h3><div class=\"fig\">{self.d.primitive_svg(k)}</div>"
                         f'<div class="bs">{esc(self.fmt(p.boundary))}</div>'
                         f'<div class="meta">×{p.count} in the example</div></div>')
        return ('<section id="primitives"><h2>Primitives</h2><div class="grid">'
                + "".join(cards) + "</div></section>")

    def _rules(self) -> str:
        cards = []
        for r, rule in enumerate(self.g.rules):
            toks = sorted(rule_tokens(rule, self.rings))
            chips = " ".join(f'<a href="#label-{t >> 1}">{esc(self.names[t >> 1])}</a>'
                             for t in toks)
            prims = {self.g.header.primitives[p].name for side in (rule.lhs, rule.rhs)
                     for p in side.vertices}
            search = " ".join([rule.name, *(self.names[t >> 1] for t in toks), *sorted(prims)])
            line = f", line {rule.span.line} of {esc(self.s.ggr_name)}" if rule.span else ""
            kind = "starter" if rule.is_starter else "rule"
            svg = self.d.rule_svg(rule)
            crossed = any(k.startswith(rule.name + "/") for k in self.d.crossed)
            note = ('<div class="meta warn">approximate: no placement of a side met every '
                    "test (class lengths, tiles, no crossings); it is drawn keeping only the "
                    "edge directions</div>") if crossed else ""
            cards.append(
                f'<div class="card rule" id="rule-{r}" data-search="{esc(search.lower())}">'
                f"<h3>{esc(rule.name)} <span class=\"meta\">{kind}</span></h3>"
                f'<div class="meta">priority {rule.priority}, weight {rule.weight:g}, '
                f"{esc(self.g.header.mode)}{line}</div>"
                f'<div class="bs">∂ = {esc(self.fmt(rule.lhs.tokens(self.rings)))}</div>'
                f'<div class="fig">{svg}</div>{note}'
                f'<div class="chips">{chips}</div></div>')
        return (f'<section id="rules"><h2>Rules ({len(self.g.rules)})</h2><p class="meta">Left '
                "side ⇄ right side; a starter is ∅ ⇄ its graph. Numbered markers are the "
                "interface: the same number on both sides is the same open half-edge. Bands "
                "beside an edge show the face labels on its two sides.</p><div class=\"grid\">"
                + "".join(cards) + "</div></section>")

    def _remaining(self) -> str:
        v = self.s.verdict
        if not v.remaining:
            return ""
        cards = []
        for k, (side, text) in enumerate(zip(v.remaining, v.remaining_strings)):
            svg = self.d.graph_svg(side, f"remaining/{k}")
            cards.append(f'<div class="card"><div class="fig">{svg}</div>'
                         f'<div class="bs">{esc(text)}</div></div>')
        return ('<section id="remaining"><h2>Remaining irreducible graphs</h2><p class="meta">'
                "A few of the graphs the search left unreduced when it stopped.</p>"
                '<div class="grid">' + "".join(cards) + "</div></section>")

    def _gallery(self) -> str:
        if self.gallery_error:
            return (f'<section id="gallery"><h2>Gallery</h2><p class="meta warn">The runtime '
                    f"could not grow drawings: {esc(self.gallery_error)}</p></section>")
        if not self.shots:
            return ""
        cards = "".join(
            f'<div class="card"><img loading="lazy" alt="seed {sh.seed}" '
            f'src="{_data_uri(sh.svg)}"><div class="meta">seed {sh.seed}: {sh.steps} steps, '
            f"{sh.vertices} vertices, {sh.edges} edges"
            + (f", {sh.seconds:.2f} s" if self.show_times else "")
            + ("" if sh.stop.startswith("reached") else f"; {esc(sh.stop)}") + "</div></div>"
            for sh in self.shots)
        return f'<section id="gallery" class="gallery"><h2>Gallery</h2><div class="grid">{cards}</div></section>'

