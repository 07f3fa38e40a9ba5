"""One entry point from a user's file to the typed example: `.gg` or `.svg` → `Example`."""

from __future__ import annotations

from pathlib import Path

from .diagnostics import Span, error
from .example import Example
from .source import ExampleSource


def load_source(path: str | Path) -> ExampleSource:
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix == ".gg":
        from .gg_parser import parse_file
        return parse_file(p)
    if suffix == ".svg":
        from .svg_import import import_svg
        return import_svg(p)
    if suffix == ".json":
        from .example_json import load_example_json
        return load_example_json(p)
    raise error(f"don't know how to read '{p.name}'", Span(str(p)),
                "give a .gg example file, an .svg drawing or a gg-example/1 .json file")


def load_example(path: str | Path) -> Example:
    from dataclasses import replace

    from .grounding import close_ground, ground_note
    from .labelling import label_example
    from .planar import build_planar_graph
    source = load_source(path)
    note = ground_note(source)
    source = close_ground(source)
    graph = build_planar_graph(source) if source.paint else None
    example = label_example(source, graph)
    return replace(example, notes=example.notes + (note,)) if note else example
