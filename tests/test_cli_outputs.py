"""What the commands write and say about it: `--report` replaces only an earlier report, an
empty drawing is reported, and a cost takes only the arguments it knows."""

from __future__ import annotations

import contextlib
import io
import json

from compiler.cli import main as ggc
from conftest import ROOT
from report.ggrun import main as ggrun

EXAMPLE = str(ROOT / "examples" / "square-hollow.gg")
GRAMMAR = str(ROOT / "examples" / "square-walls.ggr")


def run(cmd, argv) -> tuple[int, str]:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        try:
            code = cmd(argv)
        except SystemExit as exc:
            code = exc.code
    return code, err.getvalue()


def test_report_replaces_only_an_earlier_report(tmp_path):
    notes = tmp_path / "notes.json"
    notes.write_text('{"mine": true}\n', encoding="utf-8")
    argv = ["compile", EXAMPLE, "-o", str(tmp_path / "g.ggr"), "--report", str(notes)]
    code, err = run(ggc, argv)
    assert code == 2 and "not a report written by ggc" in err and "--force" in err
    assert json.loads(notes.read_text()) == {"mine": True}
    report = tmp_path / "report.json"
    argv[-1] = str(report)
    assert run(ggc, argv)[0] == 0
    assert json.loads(report.read_text())["format"] == "ggc-report/1"
    assert run(ggc, argv + ["--force"])[0] == 0        # an earlier report is replaced
    assert run(ggc, argv[:-1] + [str(notes), "--force"])[0] == 0


def test_an_empty_drawing_is_reported_on_stderr(tmp_path):
    # At temperature 0 a size:0 cost refuses the first step; at 1 whether a walk ends empty
    # depends on its path.
    for extra in (["--cost", "size:0", "--temperature", "0"], ["--limit", "0=0"]):
        code, err = run(ggrun, [GRAMMAR, "--quiet", "--out", str(tmp_path / "e.svg"), *extra])
        assert code == 1
        assert "the drawing is empty" in err and "hint:" in err


def test_a_cost_takes_only_its_arguments(tmp_path):
    for spec in ("size:1:2", "none:1", "density:0.5:1", "label:x:0.5:1"):
        code, err = run(ggrun, [GRAMMAR, "--cost", spec, "--out", str(tmp_path / "e.svg")])
        assert code == 2 and "takes" in err, (spec, err)
