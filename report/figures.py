"""SVG figures of angle graphs: rule sides, primitives and the example itself.

A rule side has no positions, only edge directions; `runtime.geometry.solver.place_side` places it
with the generation solver (lengths drawn from the edge classes), one connected component at
a time, and the components (and bare wires) are set side by side in a row here. Open
half-edges are drawn as dashed stubs ending in a numbered marker: the i-th open slot of both
sides of a rule is the same interface point (grammar_lang.rules), so it gets the same number
and colour on both sides. Each edge is stroked in its class's colour between two bands in the
colours of the face labels on its left and right.

Coordinates are px with y down: drawing units times `PX / unit`, y negated.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from grammar_lang import boundary as bd
from grammar_lang.graph import Side
from grammar_lang.rules import Header
from runtime.engine.host import Host
from runtime.geometry.solver import place_side
from runtime.geometry.tables import unit_vector
from runtime.output.svg_out import FILL_PALETTE, STROKE_PALETTE, decorations, edge_paint, face_paint

from .markup import esc, num

PX = 100.0          # px per unit length
STUB = 0.4          # open half-edge stub, in units
GAP = 36.0          # px between the pieces of a side, and around a figure
MARKER_R = 8.5
BAND = 5.0          # px: width of the face-label bands beside an edge
INTERFACE_COLOURS = ("#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf",
                     "#e377c2", "#8c564b", "#bcbd22", "#7f7f7f")
FONT = 'font-family="DejaVu Sans, Helvetica, Arial, sans-serif"'


@dataclass(frozen=True)
class Palette:
    """Colours shared by every figure of one grammar."""

    faces: dict[str, str | None]       # None: unpainted (the undecorated exterior)
    classes: dict[str, str]
    names: tuple[str, ...]             # edge label names
    prims: tuple[str, ...]             # primitive names

    @staticmethod
    def build(header: Header) -> "Palette":
        plain = [f for f in header.face_labels if f != header.exterior
                 and not (len(f) == 7 and f.startswith("#"))]
        face_decos = decorations(header, "face")
        faces = {f: face_paint(f, plain, header.exterior, face_decos)[0]
                 for f in (*header.face_labels, header.exterior)}
        order = [c.name for c in header.classes]
        order += [l.cls for l in header.labels if l.cls not in order]
        edge_decos = decorations(header, "edge")
        beside: dict[str, set[str]] = {c: set() for c in order}
        for l in header.labels:
            beside[l.cls].update((l.left, l.right))
        classes = {c: edge_paint(c, order, edge_decos,
                                 (faces.get(f) for f in sorted(beside[c])))["stroke"]
                   for c in order}
        return Palette(faces, classes, tuple(l.name for l in header.labels),
                       tuple(p.name for p in header.primitives))

    def token(self, token: int) -> str:
        return bd.format_tokens((token,), self.names)

    def prim_colour(self, p: int) -> str:
        return STROKE_PALETTE[p % len(STROKE_PALETTE)] if p < len(STROKE_PALETTE) else \
            FILL_PALETTE[p % len(FILL_PALETTE)]


@dataclass
class Piece:
    """One component (or wire) of a side, as SVG elements around its own origin, and its box."""

    parts: list[str] = field(default_factory=list)
    box: list[float] = field(default_factory=lambda: [math.inf, math.inf, -math.inf, -math.inf])

    def grow(self, x: float, y: float, pad: float = 0.0) -> None:
        b = self.box
        b[0], b[1] = min(b[0], x - pad), min(b[1], y - pad)
        b[2], b[3] = max(b[2], x + pad), max(b[3], y + pad)


class Drafter:
    """Draws the sides of one grammar's rules."""

    def __init__(self, header: Header, seed: int = 0):
        self.h = header
        self.host = Host(header)
        self.t = self.host.t
        self.k = PX / self.t.unit
        self.pal = Palette.build(header)
        self.seed = seed
        self.failed: list[str] = []     # sides the solver could not place
        self.crossed: list[str] = []    # sides drawn with crossing edges (no planar placement)

    # --- pieces -------------------------------------------------------------------------------
    def _edge(self, piece: Piece, a, b, token: int) -> None:
        """Edge from px point a to b, walking along half-edge `token` from a."""
        lab = self.h.labels[token >> 1]
        # Walk along the label's own direction, so left and right are the label's faces.
        if token & 1:
            a, b = b, a
        dx, dy = b[0] - a[0], b[1] - a[1]
        n = math.hypot(dx, dy) or 1.0
        nx, ny = dy / n, -dx / n      # left normal, y down
        for face, o in ((lab.left, BAND / 2), (lab.right, -BAND / 2)):
            fill = self.pal.faces.get(face)
            if fill:
                piece.parts.append(
                    f'<line x1="{num(a[0] + o * nx)}" y1="{num(a[1] + o * ny)}" '
                    f'x2="{num(b[0] + o * nx)}" y2="{num(b[1] + o * ny)}" stroke="{esc(fill)}" '
                    f'stroke-width="{num(BAND)}" stroke-opacity="0.85"/>')
        piece.parts.append(
            f'<line class="e" x1="{num(a[0])}" y1="{num(a[1])}" x2="{num(b[0])}" y2="{num(b[1])}" '
            f'stroke="{esc(self.pal.classes.get(lab.cls, "#1a1a1a"))}" stroke-width="2.5" '
            f'stroke-linecap="round" data-label="{esc(lab.name)}"><title>{esc(lab.name)}: '
            f'{esc(lab.left)} | {esc(lab.right)}, class {esc(lab.cls)}</title></line>')
        piece.grow(*a, BAND)
        piece.grow(*b, BAND)

    def _stub(self, piece: Piece, at, token: int, number: int) -> None:
        d = unit_vector(self.h.labels[token >> 1].direction(bool(token & 1)))
        ux, uy = d[0], -d[1]
        r = STUB * PX
        tip = (at[0] + ux * r, at[1] + uy * r)
        colour = INTERFACE_COLOURS[(number - 1) % len(INTERFACE_COLOURS)]
        lab = self.h.labels[token >> 1]
        piece.parts.append(
            f'<g class="i" data-interface="{number}"><title>interface {number}: '
            f'{esc(self.pal.token(token))}</title>'
            f'<line x1="{num(at[0])}" y1="{num(at[1])}" x2="{num(tip[0] - ux * MARKER_R)}" '
            f'y2="{num(tip[1] - uy * MARKER_R)}" stroke="'
            f'{esc(self.pal.classes.get(lab.cls, "#1a1a1a"))}" stroke-width="2" '
            f'stroke-dasharray="5 3"/>'
            f'<circle cx="{num(tip[0])}" cy="{num(tip[1])}" r="{MARKER_R}" fill="{colour}"/>'
            f'<text x="{num(tip[0])}" y="{num(tip[1] + 4)}" text-anchor="middle" font-size="11" '
            f'font-weight="bold" fill="#fff" {FONT}>{number}</text></g>')
        piece.grow(*tip, MARKER_R + 1)

    def _vertex(self, piece: Piece, at, prim: int) -> None:
        p = self.h.primitives[prim]
        piece.parts.append(
            f'<circle cx="{num(at[0])}" cy="{num(at[1])}" r="3.5" fill="#222">'
            f'<title>{esc(p.name)}: {esc(bd.format_tokens(p.boundary, self.pal.names))}'
            f'</title></circle>')
        piece.grow(*at, 4)

    def _pieces(self, side: Side, rng, key: str) -> list[Piece] | None:
        try:
            placed, planar = place_side(self.host, side, rng)
        except ValueError:
            return None
        if not planar:
            self.crossed.append(key)
        number = {s: k + 1 for k, s in enumerate(side.open_slots())}
        partner = side.partner()
        rings = [p.ring for p in self.h.primitives]
        out = []
        for pos in placed:
            piece = Piece()
            px = {v: (x * self.k, -y * self.k) for v, (x, y) in pos.items()}
            for v in sorted(pos):
                ring = rings[side.vertices[v]]
                for i, tok in enumerate(ring):
                    w = partner.get((v, i))
                    if w is None:
                        self._stub(piece, px[v], tok, number.get((v, i), 0))
                    elif (v, i) < w:
                        self._edge(piece, px[v], px[w[0]], tok)
            for v in sorted(pos):
                self._vertex(piece, px[v], side.vertices[v])
            out.append(piece)
        for e, tok in enumerate(side.wires):
            # A bare edge: its `a` end is where half-edge a points out, its `ā` end the start.
            piece = Piece()
            d = unit_vector(self.h.labels[tok >> 1].angle)
            a, b = (0.0, 0.0), (d[0] * PX, -d[1] * PX)
            self._edge(piece, a, b, tok & ~1)
            self._stub(piece, b, tok & ~1, number.get((-1 - e, 0), 0))
            self._stub(piece, a, tok | 1, number.get((-1 - e, 1), 0))
            out.append(piece)
        return out

    # --- figures -----------------------------------------------------------------------------
    def side_group(self, side: Side, key: str) -> tuple[list[str], float, float]:
        """The side's elements laid out in a row from x = 0, centred on y = 0; width, height."""
        if side.is_empty:
            return [f'<text x="20" y="12" text-anchor="middle" font-size="34" fill="#555" '
                    f'{FONT}>∅</text>'], 40.0, 44.0
        rng = np.random.default_rng([self.seed, *key.encode()])
        pieces = self._pieces(side, rng, key)
        if pieces is None:
            self.failed.append(key)
            return [f'<text x="0" y="5" font-size="13" fill="#b00" {FONT}>(no placement '
                    f'found)</text>'], 130.0, 20.0
        out, x, height = [], 0.0, 0.0
        for p in pieces:
            x0, y0, x1, y1 = p.box
            dx, dy = x - x0, -(y0 + y1) / 2
            out.append(f'<g transform="translate({num(dx)} {num(dy)})">' + "".join(p.parts) + "</g>")
            x += (x1 - x0) + GAP
            height = max(height, y1 - y0)
        return out, x - GAP, height

    def rule_svg(self, rule) -> str:
        """`L ⇄ R` (or `∅ ⇄ G` for a starter), both sides at one scale."""
        left, right = (rule.rhs, rule.lhs) if rule.is_starter else (rule.lhs, rule.rhs)
        lg, lw, lh = self.side_group(left, rule.name + "/l")
        rg, rw, rh = self.side_group(right, rule.name + "/r")
        arrow = 44.0
        w = GAP + lw + arrow + rw + GAP
        h = max(lh, rh) + 2 * GAP
        cy = h / 2
        body = [f'<g class="side lhs" transform="translate({num(GAP)} {num(cy)})">', *lg, "</g>",
                f'<text x="{num(GAP + lw + arrow / 2)}" y="{num(cy + 8)}" text-anchor="middle" '
                f'font-size="24" fill="#666" {FONT}>⇄</text>',
                f'<g class="side rhs" transform="translate({num(GAP + lw + arrow)} {num(cy)})">',
                *rg, "</g>"]
        return _svg(w, h, body, f"rule {rule.name}")

    def graph_svg(self, side: Side, title: str) -> str:
        g, w, h = self.side_group(side, title)
        return _svg(w + 2 * GAP, h + 2 * GAP,
                    [f'<g transform="translate({num(GAP)} {num(h / 2 + GAP)})">', *g, "</g>"], title)

    def primitive_svg(self, prim: int) -> str:
        """The primitive as its vertex with its ring of half-edges, each labelled, arrowed."""
        p = self.h.primitives[prim]
        r = 0.55 * PX
        parts = []
        for k, tok in enumerate(p.ring):
            d = unit_vector(self.h.labels[tok >> 1].direction(bool(tok & 1)))
            ux, uy = d[0], -d[1]
            lab = self.h.labels[tok >> 1]
            colour = esc(self.pal.classes.get(lab.cls, "#1a1a1a"))
            tip = (ux * r, uy * r)
            head = [(tip[0] - 9 * ux + 4.5 * uy, tip[1] - 9 * uy - 4.5 * ux),
                    (tip[0] - 9 * ux - 4.5 * uy, tip[1] - 9 * uy + 4.5 * ux)]
            parts.append(
                f'<line x1="0" y1="0" x2="{num(tip[0] - 6 * ux)}" y2="{num(tip[1] - 6 * uy)}" '
                f'stroke="{colour}" stroke-width="2.5"/>'
                f'<path d="M {num(tip[0])} {num(tip[1])} L {num(head[0][0])} {num(head[0][1])} '
                f'L {num(head[1][0])} {num(head[1][1])} Z" fill="{colour}"/>'
                f'<text x="{num(tip[0] + 22 * ux)}" y="{num(tip[1] + 22 * uy + 5)}" '
                f'text-anchor="middle" font-size="15" {FONT}>{esc(self.pal.token(tok))}'
                f'<title>half-edge {k + 1} of the ring: {esc(self.pal.token(tok))}, '
                f'{num(lab.direction(bool(tok & 1)))}°</title></text>')
        parts.append(f'<circle r="5" fill="{self.pal.prim_colour(prim)}" stroke="#222"/>')
        span = r + 44
        return (f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{num(-span)} {num(-span)} '
                f'{num(2 * span)} {num(2 * span)}" width="{num(1.6 * span)}" '
                f'height="{num(1.6 * span)}" role="img"><title>{esc(p.name)}</title>'
                + "".join(parts) + "</svg>")


def _svg(w: float, h: float, body: list[str], title: str) -> str:
    return (f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {num(w)} {num(h)}" '
            f'width="{num(w)}" height="{num(h)}" role="img"><title>{esc(title)}</title>'
            + "".join(body) + "</svg>")


def example_svg(example) -> str:
    """The example as the tool reads it (`ggc draw`): runtime.output.svg_out's drawing of its graph
    (faces by label, edges by class), with every vertex, merged points and split points
    included, marked in its primitive's colour and named in a tooltip."""
    from runtime.output.drawing import drawing_from_example
    from runtime.output.svg_out import render_svg

    drawing = drawing_from_example(example)
    svg = render_svg(drawing, example)
    pal = Palette.build(example)
    r = 0.06 * example.unit
    marks = ['  <g id="primitives" stroke="#222" stroke-width="{}">'.format(num(r / 4))]
    for v, p in zip(drawing.vertices, example.vertex_primitive):
        prim = example.primitives[p]
        marks.append(f'    <circle cx="{num(v.x)}" cy="{num(-v.y)}" r="{num(r)}" '
                     f'fill="{pal.prim_colour(p)}" data-primitive="{esc(prim.name)}"><title>'
                     f'vertex {v.id}: {esc(prim.name)} = '
                     f'{esc(bd.format_tokens(prim.boundary, pal.names))}</title></circle>')
    marks.append("  </g>")
    end = svg.rindex("</svg>")
    return svg[:end] + "\n".join(marks) + "\n" + svg[end:]
