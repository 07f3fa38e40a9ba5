"""Fuzz benchmark (slow; CI does not run it): hostile inputs through every format and command.

Each case writes a mutated input (a .gg, .svg, .ggr, gg-drawing/1 or gg-example/1 file, a
REPL script, or a set of option values; seeds are the shipped examples, the corpus and the
issue's reproducing inputs) and runs one command on it in this process: `ggc check`, `ggc
compile`, `ggc primitives`, `ggrun FILE` with random options, `ggrun check`, `ggrun --repl`.
A case is an internal error (exit 70, or a traceback), a user error (exit 2), ok (exit 0, 1 or
130) or a hang (over --timeout seconds); and, whatever its exit, a memory hog when it raised the
process's peak memory by more than --memory MB. The goal is no internal error, no hang and no
hog.

    .venv/bin/python benchmarks/fuzz.py --n 1000 [--seed 0] [--timeout 30] [--show 5] [--keep DIR]

With --keep, the input files of each internal error and hang are copied to DIR (as
NUMBER-NAME, numbered as they are printed) so that they can be run again.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import random
import re
import resource
import shutil
import signal
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from grammar_lang.blas import pin_blas_threads  # noqa: E402

pin_blas_threads()

from compiler.cli import main as ggc  # noqa: E402
from report.ggrun import main as ggrun  # noqa: E402

CORPUS = ROOT.parent / "shared" / "corpus"
OUTCOMES = ("internal error", "user error (exit 2)", "ok", "hang/timeout")
HOSTILE = ["1e999", "-1", "1e-320", "9" * 5000, "NaN", "Infinity", "-0", "0", "1e308",
           '"', "\\", "\\ud800", "\\u0000", "<script>alert(1)</script>", '" onload="x',
           "&amp;", "<!ENTITY x 'y'>", "\x00", "\t", "\r\n", "é", "\u2028", "{", "}", "[", "]",
           "(", ")", ",", ":", "=", "#", "#ggg", "#c0f0ff", "*", "~", "x" * 300, "/etc/passwd",
           "/dev/zero", "../", "true", "null", "[]", "{}", '""', "'", "-", "+"]
NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e-?\d+)?(?![\w.])")
NUMBERS = ["0", "-0", "-1", "1e999", "-1e999", "1e-320", "1e308", "9" * 400, "0.5", "360",
           "-360", "1e12", "2", "1000000", "3.14159"]
OPTIONS = {
    # (A huge --steps is the user's own time bound: it runs that long, so it is not fuzzed.)
    "--steps": ["0", "1", "5", "-1", "x", "1e3", "200", "9" * 5000],
    "--seed": ["0", "1", "-1", "2", "9" * 30, "x", "18446744073709551616"],
    "--cost": ["none", "size", "size:0", "size:1:2", "size:-1", "density:0.5", "density",
               "density:nan", "label:x", "label:x:2", "label", "bogus", ":", "size:9" * 3],
    "--temperature": ["0", "1", "-1", "nan", "inf", "1e308", "x"],
    "--limit": ["0=0", "0=5", "x", "0=-1", "1=2=3", "=", "0=" + "9" * 30],
    "--direction": ["both", "forward", "sideways"],
    "--count": ["1", "2", "0", "-3"],
    "--jobs": ["1", "0", "-1"],
    "--out": ["o.svg", "o.json", "o.graphml", "o.txt", "sub/o.svg", "", "/dev/null/x.svg"],
}
REPL = ["rules", "primitives", "matches s0", "matches r0 --backward", "apply s0", "apply r0 1",
        "step", "step 5", "step -1", "run 10", "run 1e9", "undo", "undo all", "redo", "redo 3",
        "reset", "seed 3", "seed -1", "seed " + "9" * 5000, "show", "show 0", "check",
        "render o.svg", "watch o.svg", "watch off", "save o.json", "open o.json",
        "open missing.json", "load G.ggr", "load /dev/zero", "help", "help apply", "bogus",
        '"unclosed', "apply", "matches", "quit"]


class Hang(BaseException):
    """Raised by the alarm; a BaseException so that no `except Exception` swallows it."""


def _alarm(signum, frame):
    raise Hang()


def mutate(rng: random.Random, text: str, rounds: int | None = None) -> str:
    for _ in range(rounds or rng.randint(0, 3)):
        op = rng.choice(["delete", "insert", "insert", "replace", "dup-line", "swap-lines",
                         "truncate", "repeat", "number", "number", "number"])
        i = rng.randint(0, len(text))
        numbers = list(NUMBER.finditer(text)) if op == "number" else []
        if numbers:           # a value changed in place: the file still parses, deeper code runs
            m = rng.choice(numbers)
            text = text[:m.start()] + rng.choice(NUMBERS) + text[m.end():]
        elif op == "delete":
            text = text[:i] + text[i + rng.randint(1, 20):]
        elif op == "insert":
            text = text[:i] + rng.choice(HOSTILE) + text[i:]
        elif op == "replace" and text:
            j = min(i, len(text) - 1)
            text = text[:j] + chr(rng.choice([rng.randint(32, 126), rng.randint(0, 0x2FFF)])) \
                + text[j + 1:]
        elif op in ("dup-line", "swap-lines"):
            lines = text.split("\n")
            a, b = rng.randrange(len(lines)), rng.randrange(len(lines))
            if op == "dup-line":
                lines.insert(b, lines[a])
            else:
                lines[a], lines[b] = lines[b], lines[a]
            text = "\n".join(lines)
        elif op == "truncate":
            text = text[:i]
        elif op == "repeat":       # a line many times over: size and limit paths
            lines = text.split("\n")
            a = rng.randrange(len(lines))
            lines[a:a] = [lines[a]] * rng.choice([10, 100, 1000])
            text = "\n".join(lines)
    return text


class Fuzzer:
    def __init__(self, work: Path, rng: random.Random):
        self.work, self.rng = work, rng
        self.gg = [p.read_text(encoding="utf-8") for p in sorted((ROOT / "examples").glob("*.gg"))]
        self.svg = [p.read_text(encoding="utf-8") for p in sorted(CORPUS.glob("*/*.svg"))]
        self.example_json = [p.read_text(encoding="utf-8")
                             for p in sorted((CORPUS / "examples").glob("*.json"))]
        shutil.copy(ROOT / "examples" / "cottage.svg", work / "cottage.svg")
        self.ggr = [(ROOT / "examples" / "square-walls.ggr").read_text(encoding="utf-8")]
        for name in ("house", "tree", "corners"):
            out = work / f"{name}.ggr"
            _quiet(ggc, ["compile", str(ROOT / "examples" / f"{name}.gg"), "-o", str(out)])
            self.ggr.append(out.read_text(encoding="utf-8"))
        (work / "G.ggr").write_text(self.ggr[1], encoding="utf-8")
        _quiet(ggrun, [str(work / "G.ggr"), "--steps", "30", "--out", str(work / "d.json")])
        self.drawing = (work / "d.json").read_text(encoding="utf-8")

    def write(self, name: str, text: str) -> str:
        path = self.work / name
        path.write_text(text, encoding="utf-8", errors="surrogatepass")
        return str(path)

    def options(self) -> list[str]:
        out = []
        for flag in self.rng.sample(sorted(OPTIONS), self.rng.randint(0, 3)):
            value = self.rng.choice(OPTIONS[flag])
            out += [flag, str(self.work / value) if flag == "--out" and value else value]
        if "--steps" not in out:
            out += ["--steps", "10"]
        if "--out" not in out:
            out += ["--out", str(self.work / "o.svg")]
        return out

    def case(self) -> tuple[str, callable, list[str], str | None]:
        """(kind, command, argv, stdin)."""
        r = self.rng
        kind = r.choice(["gg", "gg", "svg", "ggr", "ggr", "drawing", "example-json", "options",
                         "repl"])
        if kind == "gg":
            f = self.write("fuzz.gg", mutate(r, r.choice(self.gg)))
            cmd = r.choice([(ggc, ["check", f]), (ggc, ["compile", f, "-o", str(self.work / "c.ggr"),
                                                       "--force"]),
                            (ggc, ["primitives", f]), (ggrun, [f, *self.options()])])
        elif kind == "svg":
            f = self.write("fuzz.svg", mutate(r, r.choice(self.svg)))
            cmd = r.choice([(ggc, ["check", f]), (ggrun, [f, "--steps", "10", "--out",
                                                          str(self.work / "o.svg")])])
        elif kind == "ggr":
            f = self.write("fuzz.ggr", mutate(r, r.choice(self.ggr)))
            cmd = (ggrun, [f, *self.options()])
        elif kind == "drawing":
            f = self.write("fuzz.json", mutate(r, self.drawing))
            cmd = r.choice([(ggrun, ["check", str(self.work / "G.ggr"), f]),
                            (ggrun, [str(self.work / "G.ggr"), "--repl"])])
            if cmd[1][-1] == "--repl":
                return kind, cmd[0], cmd[1], f"open {f}\nshow\ncheck\nrender {self.work}/r.svg\n"
        elif kind == "example-json":
            f = self.write("fuzz-example.json", mutate(r, r.choice(self.example_json)))
            cmd = (ggc, ["check", f])
        elif kind == "options":
            cmd = (ggrun, [str(self.work / "G.ggr"), *self.options()])
        else:
            lines = [mutate(r, r.choice(REPL), 1) if r.random() < 0.3 else r.choice(REPL)
                     for _ in range(r.randint(1, 12))]
            # 'run N' and 'step N' with a huge N run as long as asked: not a hang to find.
            lines = [re.sub(r"^(run|step)(\s+)\d{5,}", r"\1\g<2>1000", x) for x in lines]
            return kind, ggrun, [str(self.work / "G.ggr"), "--repl"], "\n".join(lines) + "\n"
        return kind, cmd[0], cmd[1], None


def signatures(work: Path) -> list[tuple[str, callable, list[str], str | None]]:
    """The issue's reproducing inputs, each run once."""
    def w(name, text):
        (work / name).write_text(text, encoding="utf-8", errors="surrogatepass")
        return str(work / name)

    g = str(work / "G.ggr")
    drawing = json.loads((work / "d.json").read_text(encoding="utf-8"))
    bad_drawings = []
    for value in ("1e999", "9" * 5000, "12", '"\\ud800"'):
        text = json.dumps(drawing).replace('"id": 0', f'"id": {value}', 1)
        bad_drawings.append(text.replace('"left": "', '"left": 5, "x": "', 1))
    base = (work / "G.ggr").read_text(encoding="utf-8")
    out = [("signature", ggrun, [g, "--seed", "-1", "--out", str(work / "o.svg")], None),
           ("signature", ggrun, [g, "--cost", "size:1:2", "--out", str(work / "o.svg")], None),
           ("signature", ggrun, [g, "--cost", "size:0", "--out", str(work / "o.svg")], None),
           ("signature", ggrun, [g, "--limit", "0=0", "--out", str(work / "o.svg")], None),
           ("signature", ggc, ["check", w("imp.gg", f'import "{"x" * 300}"\n')], None),
           ("signature", ggc, ["check", w("pw.gg", 'import "/etc/passwd"\n')], None),
           ("signature", ggc, ["check", "/dev/zero"], None),
           ("signature", ggc, ["check", w("long.gg", "polyline " + " ".join(
               f"({k % 997}, {k % 991})" for k in range(250_000)) + "\n")], None),
           ("signature", ggc, ["check", w("path.svg", '<svg xmlns="http://www.w3.org/2000/svg">'
                                          '<path d="M 0 0 ' + "L 1 2 L 3 1 " * 150_000
                                          + '"/></svg>')], None)]
    for k, text in enumerate(bad_drawings):
        out.append(("signature", ggrun, ["check", g, w(f"bad{k}.json", text)], None))
    lines = ('decorate edge * stroke="red\\" onmouseover=\\"alert(1)"',
             'decorate vertex * fill="red\\"/><script>alert(1)</script>"',
             'decorate face * opacity="x"', "unit 1e-320")
    for k, line in enumerate(lines):
        text = base.replace("\nunit ", "\n" + line + "\nunit ", 1) if line.startswith("decorate") \
            else base.replace("\nunit ", "\nunit 1e-320\n#", 1)
        out.append(("signature", ggrun, [w(f"sig{k}.ggr", text), "--out", str(work / "o.svg")], None))
    return out


def _quiet(cmd, argv, stdin: str | None = None) -> tuple[int, str]:
    err = io.StringIO()
    old_in = sys.stdin
    sys.stdin = io.StringIO(stdin or "")
    try:
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
            code = cmd(argv)
    except SystemExit as exc:           # argparse
        code = exc.code if isinstance(exc.code, int) else 2
    finally:
        sys.stdin = old_in
    return code, err.getvalue()


def run_case(case, timeout: float) -> tuple[str, str]:
    kind, cmd, argv, stdin = case
    signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, timeout)
    try:
        code, err = _quiet(cmd, argv, stdin)
    except Hang:
        return "hang/timeout", f"over {timeout} s"
    except Exception as exc:             # noqa: BLE001 - an escape past the CLI's own guard
        return "internal error", f"{type(exc).__name__}: {exc}"
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
    if code == 70 or "Traceback" in err:
        return "internal error", err.strip().splitlines()[0] if err.strip() else "exit 70"
    if code == 2:
        return "user error (exit 2)", ""
    return "ok", ""


def _keep(folder: Path, number: int, case) -> None:
    """Copy the files a failed case read (its arguments, and the words of its REPL script, that
    name files in the work folder), and its REPL script, to `folder`."""
    folder.mkdir(parents=True, exist_ok=True)
    _, _, argv, stdin = case
    # A REPL script names the files it opens on its own lines.
    for a in [*argv, *(stdin or "").split()]:
        f = Path(a)
        if f.is_file() and f.parent == Path.cwd():
            shutil.copy(f, folder / f"{number}-{f.name}")
    if stdin:
        (folder / f"{number}-stdin.txt").write_text(stdin, encoding="utf-8", errors="replace")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=1000, help="number of random cases")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--timeout", type=float, default=30.0, help="seconds before a case hangs")
    ap.add_argument("--show", type=int, default=5, help="failures to print")
    ap.add_argument("--keep", type=Path, help="copy the inputs of failures to this folder")
    ap.add_argument("--memory", type=int, default=1024,
                    help="how far (MB) a case may raise the peak memory before it is a hog")
    args = ap.parse_args()
    keep = args.keep.resolve() if args.keep is not None else None     # before the chdir
    work = Path(tempfile.mkdtemp(prefix="gg-fuzz-bench-"))
    os.chdir(work)          # REPL scripts and default output paths write relative files
    rng = random.Random(args.seed)
    fuzzer = Fuzzer(work, rng)
    sigs = signatures(work)
    # Each case writes its input files when made, so it is made just before it runs.
    cases = (*sigs, *(None for _ in range(args.n)))
    counts: dict[str, Counter] = {}
    failures, slowest, t0 = [], (0.0, ""), time.perf_counter()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024
    for case in cases:
        case = case or fuzzer.case()
        start = time.perf_counter()
        outcome, detail = run_case(case, args.timeout)
        took = time.perf_counter() - start
        # The process's peak only rises, and the cases share the process: a case is a hog
        # when it raised the peak by more than the bound (what earlier cases left behind
        # raises it by little).
        peak, before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024, peak
        if peak - before > args.memory:
            failures.append((case, f"raised the peak memory by {peak - before} MB, to "
                                   f"{peak} MB (bound {args.memory} MB); it ended as {outcome}"))
            if keep is not None:
                _keep(keep, len(failures), case)
        if took > slowest[0]:
            slowest = (took, f"{case[0]}: {' '.join(a[:40] for a in case[2])}")
        counts.setdefault(case[0], Counter())[outcome] += 1
        if outcome in ("internal error", "hang/timeout"):
            failures.append((case, detail))
            if keep is not None:
                _keep(keep, len(failures), case)
    shutil.rmtree(work, ignore_errors=True)
    print(f"{len(cases)} cases ({args.n} random, seed {args.seed}, {len(sigs)} "
          f"signatures) in {time.perf_counter() - t0:.0f} s; slowest {slowest[0]:.1f} s "
          f"({slowest[1]}); peak memory {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024} MB\n")
    print(f"| {'input':<14} | " + " | ".join(f"{o:>19}" for o in OUTCOMES) + " |")
    print(f"|{'-' * 16}|" + "|".join("-" * 21 for _ in OUTCOMES) + "|")
    total = Counter()
    for kind in sorted(counts):
        total.update(counts[kind])
        print(f"| {kind:<14} | " + " | ".join(f"{counts[kind][o]:>19}" for o in OUTCOMES) + " |")
    print(f"| {'all':<14} | " + " | ".join(f"{total[o]:>19}" for o in OUTCOMES) + " |")
    for (kind, cmd, argv, stdin), detail in failures[:args.show]:
        print(f"\n{kind}: {' '.join(a[:60] for a in argv)}\n  {detail[:300]}")
        if stdin:
            print("  stdin: " + " | ".join(line[:60] for line in stdin.splitlines()))
    return 1 if failures else 0


if __name__ == "__main__":
    raise SystemExit(main())
