"""SVG to PNG through resvg (a real SVG renderer, shipped as a self-contained wheel).

Both `ggrun --out x.png` and `ggc report --png DIR` render here. The size is the SVG's own
(its width/height attributes) times `scale`, or `width` pixels wide with the height in
proportion; both are bounded so that a typo cannot ask for gigapixels.
"""

from __future__ import annotations

from pathlib import Path

from .diagnostics import error
from .fileio import atomic_write

MAX_WIDTH = 16384
MAX_SCALE = 16.0


def check_size(width: int | None, scale: float | None) -> None:
    """Reject sizes out of range (a clear error, before any work is done)."""
    if width is not None and scale is not None:
        raise error("give --width or --scale, not both")
    if width is not None and not 1 <= width <= MAX_WIDTH:
        raise error(f"--width {width} is out of range", None,
                    f"give a width from 1 to {MAX_WIDTH} pixels")
    if scale is not None and not 0 < scale <= MAX_SCALE:
        raise error(f"--scale {scale:g} is out of range", None,
                    f"give a scale above 0 and at most {MAX_SCALE:g}")


def svg_to_png(svg: str, width: int | None = None, scale: float | None = None) -> bytes:
    """The SVG text rendered on white as PNG bytes."""
    import resvg_py

    check_size(width, scale)
    try:
        return bytes(resvg_py.svg_to_bytes(svg_string=svg, background="#ffffff", width=width,
                                           zoom=scale))
    except ValueError as exc:   # resvg refuses the document: our bug, not the user's input
        raise RuntimeError(f"resvg could not render the SVG: {exc}") from exc


def write_png(svg: str, path: str | Path, width: int | None = None,
              scale: float | None = None) -> None:
    atomic_write(path, svg_to_png(svg, width, scale))
