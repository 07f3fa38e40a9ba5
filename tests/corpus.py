"""Reading the corpus README's reference figures, for tests and benchmarks."""

import re

from conftest import CORPUS


def reference_types() -> dict[str, tuple[int, int, int]]:
    """example name → (primitives, edge labels, face labels) at 10° tolerance."""
    out = {}
    for line in (CORPUS.parent / "README.md").read_text().splitlines():
        cells = [c.strip() for c in line.split("|")]
        if len(cells) > 7 and re.fullmatch(r"\d+/\d+/\d+", cells[6]):
            out[cells[2]] = tuple(int(x) for x in cells[6].split("/"))
    return out
