"""`ggc check` and `ggc primitives`: show how the tool understands an example."""

from __future__ import annotations

import json
import math

from rich.console import Console
from rich.table import Table

from grammar_lang.example import Example
from grammar_lang.frame import Frame, find_frame
from grammar_lang.loader import load_example


def run(args) -> int:
    example = load_example(args.file)
    out = Console(highlight=False, soft_wrap=True)
    err = Console(stderr=True, highlight=False, soft_wrap=True)
    for note in example.notes:
        err.print(note.render(), markup=False)
    if args.command == "check":
        # A border that is not one closed loop, or a bent side, is an error here as in compile.
        out.print(summary(example, find_frame(example)), markup=False)
    elif args.json:
        out.print_json(json.dumps(as_json(example)))
    else:
        for table in tables(example, ascii=args.ascii):
            out.print(table)
    return 0


def summary(ex: Example, frame: Frame | None = None) -> str:
    parts = [f"ok: {ex.path}: '{ex.name}'"]
    if ex.graph is not None:
        parts.append(f"  {len(ex.graph.vertices)} vertices, {len(ex.graph.edges)} edges")
    if frame is not None:
        w, h = frame.size
        parts.append(f"  frame: {len(frame.corners)} corners, {w:g} × {h:g}")
    parts.append(f"  {len(ex.face_labels)} face labels, {len(ex.labels)} edge labels, "
                 f"{len(ex.primitives)} primitives")
    parts.append(f"  unit {ex.unit:g}; classes: "
                 + ", ".join(f"{c.name} [{c.min_length:g}, {c.max_length:g}]"
                             + (" rigid" if c.rigid else "") for c in ex.classes))
    return "\n".join(parts)


def tables(ex: Example, ascii: bool = False) -> list[Table]:
    faces = Table(title="face labels")
    faces.add_column("label")
    faces.add_column("role")
    for f in ex.face_labels:
        faces.add_row(f, "exterior" if f == ex.exterior else "")

    labels = Table(title="edge labels")
    for col in ("name", "angle", "left", "right", "class"):
        labels.add_column(col)
    for l in ex.labels:
        angle = f"{l.angle:g}°" + (f" len {l.length:g}" if l.length is not None else "")
        labels.add_row(l.name, angle, l.left, l.right, l.cls)

    prims = Table(title="primitives")
    for col in ("name", "vertices", "half-edges", "boundary string"):
        prims.add_column(col)
    for p in ex.primitives:
        prims.add_row(p.name, str(p.count), str(len(p.ring)), ex.format(p.boundary, ascii))
    return [faces, labels, prims]


def as_json(ex: Example) -> dict:
    return {
        "name": ex.name,
        "source": ex.path,
        "exterior": ex.exterior,
        "face_labels": list(ex.face_labels),
        "unit": ex.unit,
        # JSON has no infinity: a border class's unbounded max is written as none.
        "classes": [{"name": c.name, "min_length": c.min_length,
                     "max_length": c.max_length if math.isfinite(c.max_length) else None,
                     "fixed": c.fixed, "tile": c.tile, "rigid": c.rigid} for c in ex.classes],
        "edge_labels": [{"name": l.name, "angle": l.angle, "left": l.left, "right": l.right,
                         "class": l.cls, "length": l.length} for l in ex.labels],
        "primitives": [{"name": p.name, "count": p.count,
                        "ring": [ex.format((t,), ascii=True) for t in p.ring],
                        "boundary": ex.format(p.boundary),
                        "boundary_ascii": ex.format(p.boundary, ascii=True)}
                       for p in ex.primitives],
        "notes": [n.render() for n in ex.notes],
    }
