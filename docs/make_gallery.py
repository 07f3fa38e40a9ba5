"""Regenerate docs/gallery.md and its pictures in docs/images/gallery/.

Run from the repository root with the package installed:
    python docs/make_gallery.py             # the paper's N (several minutes)
    python docs/make_gallery.py --quick     # 40 and 80 iterations, to check that it runs
For each scene it draws the example as `ggc draw` reads it, then two drawings with `ggrun`: one
at a quarter of the paper's N and one at its N (Table 1 of the paper, the illustrations'
README), N counted as the paper counts it, in iterations (proposals, applied or not: `ggrun
--iterations`), and writes what each run reported.
The paper's illustrations are read from the corpus (`GG_CORPUS`, default
../shared/corpus/examples beside the repository; the illustrations sit next to it).
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = Path(os.environ.get("GG_CORPUS", ROOT.parent / "shared" / "corpus" / "examples"))
ILLUSTRATIONS = CORPUS.parent / "illustrations"


@dataclass(frozen=True)
class Scene:
    name: str
    source: Path
    iterations: int     # the paper's N
    seed: int
    about: str
    extent: str | None = None     # `ggrun --extent`; None: the example's own frame


SCENES = (
    Scene("castle-scene", ROOT / "examples" / "castle-scene.gg", 4000, 5,
          "this project's castle in a frame (`examples/castle-scene.gg`)"),
    Scene("castle-grounded", ROOT / "examples" / "castle.gg", 2000, 5,
          "this project's castle on a ground line with no frame (`examples/castle.gg`): the "
          "ground is closed into a frame four grounds wide"),
    Scene("flowers-scene", ROOT / "examples" / "flowers.gg", 2000, 3,
          "this project's flowers in a frame (`examples/flowers.gg`), their stems bent "
          "(Appendix B)"),
    Scene("village-scene", ROOT / "examples" / "village.gg", 4200, 65,
          "this project's village in a frame (`examples/village.gg`): two strips of land and "
          "the sky above, houses and trees along each"),
    Scene("station-scene", ROOT / "examples" / "space-station.gg", 3700, 22,
          "this project's space station in a frame (`examples/space-station.gg`): modules "
          "and solar panels along two trusses that span the frame"),
    Scene("castle", ILLUSTRATIONS / "castle.gg", 4000, 80, "the paper's Fig. 1 castle"),
    Scene("flowers", ILLUSTRATIONS / "flowers.gg", 2000, 42, "the paper's Fig. 9f flowers"),
    Scene("space-station", ILLUSTRATIONS / "space-station.gg", 3700, 22,
          "the paper's Fig. 9b space station"),
    Scene("space-station-paper-extent", ILLUSTRATIONS / "space-station.gg", 3700, 22,
          "the paper's Fig. 9b space station at the original settings' extent, 2,040 × 800 "
          "(51 × 20 cells of 40 px)", "2040x800"),
    Scene("village", ILLUSTRATIONS / "village.gg", 4200, 65, "the paper's Fig. 9g village"),
    Scene("village-paper-extent", ILLUSTRATIONS / "village.gg", 4200, 65,
          "the paper's Fig. 9g village at the original settings' extent, 2,720 × 1,600 (68 × 40 "
          "cells of 40 px; the example's own frame is 1,540 × 780)", "2720x1600"),
)


def tool(args: list[str]) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", *args], cwd=ROOT, capture_output=True,
                          text=True)


def summary(res: subprocess.CompletedProcess) -> str:
    """The run's own account: its summary line and why it stopped early, or its error."""
    lines = [ln.strip() for ln in res.stderr.splitlines() if ln.strip()]
    # Without the path and the seconds, so that the page changes only when the drawings do.
    keep = [re.sub(r"; [\d.]+ s \(\d+ steps/s\)", "", re.sub(r"^\S+\.(svg|png|gg): ", "", ln))
            for ln in lines if "steps applied" in ln or "stopped early" in ln or "error" in ln]
    return " ".join(keep) or f"exit {res.returncode}"


def draw_scene(s: Scene, out: Path, quick: bool, page_dir: Path) -> list[str]:
    rel = Path(os.path.relpath(out, page_dir))
    row = [f"### {s.name}", "", f"{s.about}; seed {s.seed}.", ""]
    example = out / f"{s.name}-example.png"
    tool(["report.ggc", "draw", str(s.source), "-o", str(example), "--width", "800"])
    cells = [("the example, as read", example.name, "")]
    for n in ((40, 80) if quick else (s.iterations // 4, s.iterations)):
        png = out / f"{s.name}-{n}.png"
        extent = ["--extent", s.extent] if s.extent else []
        res = tool(["report.ggrun", str(s.source), "--iterations", str(n), "--seed",
                    str(s.seed), "--out", str(png), "--width", "800", *extent])
        if res.returncode != 0:
            # An error is not a result to show: the page keeps its last good version.
            raise RuntimeError(f"{s.name}, {n} iterations: {summary(res)}")
        cells.append((f"{n:,} iterations", png.name if png.exists() else "", summary(res)))
    row += ["| " + " | ".join(c[0] for c in cells) + " |",
            "|" + "---|" * len(cells),
            "| " + " | ".join(f"![{c[0]}]({rel / c[1]})" if c[1] else "(no drawing)"
                              for c in cells) + " |", ""]
    row += [f"- {c[0]}: {c[2]}" for c in cells if c[2]] + [""]
    return row


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true",
                    help="40 and 80 iterations, to check that it runs")
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "images" / "gallery",
                    help="where the pictures go")
    ap.add_argument("--page", type=Path, default=ROOT / "docs" / "gallery.md")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    text = [
        "# Gallery: scenes in a frame", "",
        "Made by `python docs/make_gallery.py`, which writes this page. Each scene shows its",
        "example as `ggc draw` reads it and two drawings grown by `ggrun`, at a quarter of the",
        "paper's number of iterations N and at N (the paper's Table 1; an iteration is one",
        "proposal, applied or not, as in the paper's Algorithm 3: `ggrun --iterations`). Under",
        "each is what the run reported (for this project's own examples N is ours). See",
        "[scenes.md](scenes.md) for how frames work and what is still open.", ""]
    for s in SCENES:
        print(f"{s.name} …", flush=True)
        try:
            text += draw_scene(s, args.out.resolve(), args.quick, args.page.resolve().parent)
        except RuntimeError as e:
            print(f"not written: {e}", file=sys.stderr)
            return 1
    args.page.write_text("\n".join(text), encoding="utf-8")
    print(f"wrote {args.page}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
